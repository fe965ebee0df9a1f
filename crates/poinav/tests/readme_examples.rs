//! The README's examples run as written: every `poinav` command line of its fenced `sh`
//! blocks runs against the corpus (`../shared/` is the corpus folder, `crates/` and `docs/`
//! the repository's, other relative paths a fresh folder shared by all examples, with `out/`
//! in it) and exits 0; where the README shows output (`# ` lines right under a command), each
//! shown line is a line of what the command prints, in order. `| jq -c PATH` and `| head -N`
//! are applied here; `poinav serve` runs until it prints its URL.

mod common;

use std::path::Path;
use std::process::{Command, Stdio};

/// One example: the command line, its line in the README and the output shown under it.
#[derive(Debug)]
struct Example {
    line: usize,
    command: String,
    shown: Vec<String>,
}

/// The `poinav` command lines of the README's `sh` blocks with the output shown under them.
fn examples(readme: &str) -> Vec<Example> {
    let mut out: Vec<Example> = Vec::new();
    let mut in_sh = false;
    let mut last_was_command = false;
    for (i, raw) in readme.lines().enumerate() {
        let line = raw.trim_end();
        if line.starts_with("```") {
            in_sh = !in_sh && line == "```sh";
            last_was_command = false;
            continue;
        }
        if !in_sh {
            continue;
        }
        if let Some(shown) = line.strip_prefix("# ") {
            if last_was_command {
                out.last_mut().unwrap().shown.push(shown.to_string());
            }
            continue;
        }
        let command = strip_comment(line);
        let words = split_words(&command);
        let is_poinav = words
            .iter()
            .find(|w| !is_env(w))
            .is_some_and(|w| w == "poinav");
        last_was_command = is_poinav;
        if is_poinav {
            out.push(Example {
                line: i + 1,
                command,
                shown: Vec::new(),
            });
        }
    }
    out
}

/// `NAME=value`.
fn is_env(word: &str) -> bool {
    word.split_once('=').is_some_and(|(k, _)| {
        !k.is_empty() && k.chars().all(|c| c.is_ascii_uppercase() || c == '_')
    })
}

/// The line without a trailing `# comment` (outside quotes).
fn strip_comment(line: &str) -> String {
    let mut quote = None;
    let mut prev = ' ';
    for (i, c) in line.char_indices() {
        match (quote, c) {
            (None, '\'' | '"') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            (None, '#') if prev.is_whitespace() => return line[..i].trim_end().to_string(),
            _ => {}
        }
        prev = c;
    }
    line.trim_end().to_string()
}

/// Shell words: blanks separate, `'...'` and `"..."` quote.
fn split_words(s: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut quote = None;
    for c in s.chars() {
        match (quote, c) {
            (None, '\'' | '"') => {
                quote = Some(c);
                in_word = true;
            }
            (Some(q), c) if c == q => quote = None,
            (None, c) if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            (_, c) => {
                word.push(c);
                in_word = true;
            }
        }
    }
    if in_word {
        words.push(word);
    }
    words
}

/// A path word as the README means it, for a process running in `work`.
fn path_word(word: &str) -> String {
    if let Some(rest) = word.strip_prefix("../shared/") {
        return common::shared().join(rest).display().to_string();
    }
    if word.starts_with("crates/") || word.starts_with("docs/") {
        return common::root().join(word).display().to_string();
    }
    word.to_string()
}

/// `jq -c PATH` for paths of keys and indexes (`.doors[0]`, `.profiles[0].doors`).
fn jq(value: &serde_json::Value, path: &str) -> serde_json::Value {
    let mut v = value;
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (key, rest) = part.split_once('[').unwrap_or((part, ""));
        if !key.is_empty() {
            v = &v[key];
        }
        for index in rest.split('[').filter(|x| !x.is_empty()) {
            v = &v[index.trim_end_matches(']').parse::<usize>().unwrap()];
        }
    }
    v.clone()
}

/// Runs one example in `work`; returns what it printed (after the pipe, if any).
fn run(example: &Example, work: &Path) -> String {
    let (left, pipe) = match example.command.split_once(" | ") {
        Some((l, r)) => (l, Some(split_words(r))),
        None => (example.command.as_str(), None),
    };
    let words = split_words(left);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_poinav"));
    cmd.current_dir(work);
    let mut args = Vec::new();
    for w in &words {
        if args.is_empty() && is_env(w) {
            let (k, v) = w.split_once('=').unwrap();
            cmd.env(k, v);
        } else if args.is_empty() && w == "poinav" {
            args.push(String::new());
        } else {
            args.push(path_word(w));
        }
    }
    let args = &args[1..];
    let at = format!("README.md:{}: `{}`", example.line, example.command);
    if args.first().map(String::as_str) == Some("serve") {
        // Until it serves: the first line is its URL (a free port instead of the one shown).
        let mut rest: Vec<String> = Vec::new();
        let mut skip = false;
        for a in &args[1..] {
            if skip {
                skip = false;
            } else if a == "--port" {
                skip = true;
            } else {
                rest.push(a.clone());
            }
        }
        let rest: Vec<&std::ffi::OsStr> = rest.iter().map(std::ffi::OsStr::new).collect();
        let served = common::serve(&rest, work).unwrap_or_else(|code| panic!("{at}: exit {code}"));
        return format!("poinav viewer: http://{}/", served.addr);
    }
    let out = cmd
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("poinav runs");
    assert!(
        out.status.success(),
        "{at}: exit {:?}\n{}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    match pipe.as_deref() {
        None => stdout,
        Some([jq_, c, path]) if jq_ == "jq" && c == "-c" => {
            let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
            format!("{}\n", jq(&v, path))
        }
        Some([head, n]) if head == "head" => stdout
            .lines()
            .take(n.trim_start_matches('-').parse().unwrap())
            .map(|l| format!("{l}\n"))
            .collect(),
        Some(other) => panic!("{at}: the test cannot run `| {}`", other.join(" ")),
    }
}

/// Equal JSON values, numbers compared by value (`2.0` is `2`, as jq prints it).
fn same_json(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    use serde_json::Value::{Array, Number, Object};
    match (a, b) {
        (Number(x), Number(y)) => x.as_f64() == y.as_f64(),
        (Array(x), Array(y)) => x.len() == y.len() && x.iter().zip(y).all(|(x, y)| same_json(x, y)),
        (Object(x), Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.get(k).is_some_and(|w| same_json(v, w)))
        }
        _ => a == b,
    }
}

/// Each shown line is a line of `printed`, in order (JSON lines compare as JSON values).
fn check_shown(example: &Example, printed: &str) {
    let mut lines = printed.lines();
    for want in &example.shown {
        let json: Option<serde_json::Value> = serde_json::from_str(want).ok();
        let found = lines.any(|l| match &json {
            Some(j) if want.starts_with('{') => {
                serde_json::from_str::<serde_json::Value>(l).is_ok_and(|v| same_json(&v, j))
            }
            _ => l == want,
        });
        assert!(
            found,
            "README.md:{}: `{}` does not print the line shown\n  {want}\nit printed:\n{printed}",
            example.line, example.command
        );
    }
}

#[test]
fn the_readme_examples_run_and_print_what_it_shows() {
    let readme = std::fs::read_to_string(common::root().join("README.md")).unwrap();
    let examples = examples(&readme);
    let work = tempfile::tempdir().unwrap();
    std::fs::create_dir(work.path().join("out")).unwrap();
    let mut shown = 0;
    for e in &examples {
        let printed = run(e, work.path());
        check_shown(e, &printed);
        shown += e.shown.len();
    }
    // What the README has today: if this changes, the examples were edited (check the numbers).
    assert!(
        examples.len() >= 15,
        "{} examples: {examples:#?}",
        examples.len()
    );
    assert!(shown >= 6, "{shown} lines of shown output");
    assert!(examples.iter().any(|e| e.command.contains("poinav route")));
}

#[test]
fn the_example_parser_reads_commands_comments_and_shown_output() {
    let text = "```sh\npoinav inspect a.ifc   # what it has\n# {\"id\": 1}\nSOURCE_DATE_EPOCH=0 poinav enrich 'a b.ifc' -o x.ifc\nbash scripts/demo.sh\n```\n```rust\npoinav not sh\n```\n";
    let e = examples(text);
    assert_eq!(e.len(), 2);
    assert_eq!(e[0].command, "poinav inspect a.ifc");
    assert_eq!(e[0].shown, ["{\"id\": 1}"]);
    assert_eq!(e[1].line, 4);
    assert_eq!(
        split_words(&e[1].command),
        [
            "SOURCE_DATE_EPOCH=0",
            "poinav",
            "enrich",
            "a b.ifc",
            "-o",
            "x.ifc"
        ]
    );
    let v = serde_json::json!({"doors": [{"id": 7}]});
    assert_eq!(jq(&v, ".doors[0]"), serde_json::json!({"id": 7}));
    assert_eq!(jq(&v, ".doors[0].id"), serde_json::json!(7));
}
