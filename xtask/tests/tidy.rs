//! Tidiness checks over the whole repository, as rust-analyzer keeps them: every Rust file
//! opens with a `//!` line saying what it is, and every dependency between the workspace's
//! crates is one of the allowed edges written here, which ARCHITECTURE.md lists too.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The allowed `[dependencies]` edges between workspace crates (dev-dependencies are free).
/// Reading IFC -> geometry -> POI rules -> navigation and simulation; exporters read their
/// outputs; the binary, the viewer and the Python package are glue. `poinav-nav` and
/// `poinav-sim` know no IFC and no geometry (not even through `poinav-poi`): roles and profiles
/// come from `poinav-roles`, their building's data types from `poinav-floor` (which knows
/// neither), and `poinav-bridge` is the one way from a model to their building.
const ALLOWED: &[(&str, &[&str])] = &[
    ("poinav-io", &[]),
    ("poinav-ifc", &["poinav-io"]),
    ("poinav-plane", &[]),
    ("poinav-geom", &["poinav-ifc", "poinav-plane"]),
    ("poinav-roles", &[]),
    ("poinav-floor", &["poinav-roles", "poinav-plane"]),
    ("poinav-poi", &["poinav-ifc", "poinav-geom", "poinav-roles"]),
    ("poinav-author", &["poinav-ifc"]),
    ("poinav-nav", &["poinav-io", "poinav-roles", "poinav-floor"]),
    ("poinav-sim", &["poinav-io", "poinav-roles", "poinav-nav"]),
    (
        "poinav-bridge",
        &[
            "poinav-ifc",
            "poinav-geom",
            "poinav-poi",
            "poinav-author",
            "poinav-nav",
            "poinav-sim",
        ],
    ),
    (
        "poinav-export",
        &["poinav-io", "poinav-ifc", "poinav-geom", "poinav-poi"],
    ),
    (
        "poinav-bcf",
        &["poinav-io", "poinav-ifc", "poinav-poi", "poinav-nav"],
    ),
    ("poinav-mcap", &["poinav-io", "poinav-roles", "poinav-nav"]),
    (
        "poinav-viewer",
        &["poinav-roles", "poinav-nav", "poinav-sim"],
    ),
    (
        "poinav",
        &[
            "poinav-io",
            "poinav-ifc",
            "poinav-geom",
            "poinav-poi",
            "poinav-author",
            "poinav-nav",
            "poinav-sim",
            "poinav-bridge",
            "poinav-export",
            "poinav-bcf",
            "poinav-mcap",
            "poinav-viewer",
        ],
    ),
    (
        "poinav-py",
        &[
            "poinav-ifc",
            "poinav-geom",
            "poinav-poi",
            "poinav-author",
            "poinav-nav",
            "poinav-sim",
            "poinav-bridge",
            "poinav-export",
        ],
    ),
    ("poinav-testkit", &[]),
];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

fn allowed_edges() -> BTreeSet<(String, String)> {
    ALLOWED
        .iter()
        .flat_map(|(from, to)| to.iter().map(move |t| (from.to_string(), t.to_string())))
        .collect()
}

/// (crate, workspace crates it depends on) for every crate under `crates/`.
fn actual_edges() -> (BTreeSet<String>, BTreeSet<(String, String)>) {
    let mut names = BTreeSet::new();
    let mut edges = BTreeSet::new();
    for entry in std::fs::read_dir(root().join("crates")).unwrap() {
        let manifest = entry.unwrap().path().join("Cargo.toml");
        let Ok(text) = std::fs::read_to_string(&manifest) else {
            continue;
        };
        let doc: toml::Table = text.parse().unwrap();
        let name = doc["package"]["name"].as_str().unwrap().to_string();
        if let Some(deps) = doc.get("dependencies").and_then(|d| d.as_table()) {
            for dep in deps.keys().filter(|d| d.starts_with("poinav")) {
                edges.insert((name.clone(), dep.clone()));
            }
        }
        names.insert(name);
    }
    (names, edges)
}

#[test]
fn crate_dependencies_point_the_allowed_way() {
    let (names, edges) = actual_edges();
    let allowed = allowed_edges();
    let listed: BTreeSet<String> = ALLOWED.iter().map(|(c, _)| c.to_string()).collect();
    assert_eq!(
        names, listed,
        "every crate under crates/ has its line in ALLOWED (xtask/tests/tidy.rs)"
    );
    let wrong: Vec<_> = edges.difference(&allowed).collect();
    assert!(
        wrong.is_empty(),
        "dependencies not in the allowed edges (xtask/tests/tidy.rs, ARCHITECTURE.md): {wrong:?}"
    );
}

#[test]
fn architecture_lists_the_allowed_edges() {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let section = text
        .split("## Dependency edges")
        .nth(1)
        .expect("ARCHITECTURE.md has a `## Dependency edges` section");
    let section = section.split("\n## ").next().unwrap();
    // Lines `- `from` -> `a`, `b``.
    let mut listed = BTreeSet::new();
    for line in section.lines().filter(|l| l.starts_with("- `")) {
        let (from, to) = line[2..].split_once("->").expect("`- `crate` -> ...`");
        let from = from.trim().trim_matches('`').to_string();
        for t in to.split(',') {
            let t = t.trim().trim_matches('`').trim_end_matches('.');
            if !t.is_empty() && t != "nothing" {
                listed.insert((from.clone(), t.trim_matches('`').to_string()));
            }
        }
    }
    assert_eq!(
        listed,
        allowed_edges(),
        "ARCHITECTURE.md's dependency edges and xtask/tests/tidy.rs's ALLOWED differ"
    );
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if p.is_dir() {
            if !matches!(
                name.as_str(),
                "target" | "node_modules" | "corpus" | "artifacts"
            ) {
                rust_files(&p, out);
            }
        } else if name.ends_with(".rs") {
            out.push(p);
        }
    }
}

#[test]
fn every_rust_file_says_what_it_is_in_its_first_line() {
    let mut files = Vec::new();
    for dir in ["crates", "xtask", "fuzz"] {
        rust_files(&root().join(dir), &mut files);
    }
    assert!(files.len() > 100, "found only {} .rs files", files.len());
    let missing: Vec<_> = files
        .iter()
        .filter(|f| {
            !std::fs::read_to_string(f)
                .unwrap_or_default()
                .starts_with("//!")
        })
        .collect();
    assert!(missing.is_empty(), "no `//!` first line: {missing:?}");
}
