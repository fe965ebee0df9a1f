//! The embedded assets: the vendored three.js files are exactly those of the npm package the
//! tests install (tests/js/package-lock.json), and every module import of every served script
//! resolves to a served file, so the page cannot fail on a missing script.

use std::path::{Path, PathBuf};

use poinav_viewer::{asset, ASSETS};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn vendored_three_matches_npm() {
    let npm = root().join("tests/js/node_modules/three");
    assert!(
        npm.is_dir(),
        "{} is missing: run tests/js/setup.sh (npm ci)",
        npm.display()
    );
    let list =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("web/vendor.txt"))
            .unwrap();
    let mut n = 0;
    for line in list.lines().filter(|l| !l.trim().is_empty()) {
        let (from, to) = line.split_once(' ').unwrap();
        let want = std::fs::read(npm.join(from)).unwrap();
        let path = format!("/vendor/three/{to}");
        let served = asset(&path).unwrap_or_else(|| panic!("{path} is not served"));
        assert!(
            served.bytes == want.as_slice(),
            "{path} differs from npm's {from}: run scripts/vendor-three.sh"
        );
        n += 1;
    }
    assert_eq!(n, 8);
}

/// `from '...'` and bare `import '...'` specifiers of a module.
fn imports(js: &str) -> Vec<String> {
    let mut out = Vec::new();
    for pat in ["from '", "from \"", "import '", "import \""] {
        let quote = &pat[pat.len() - 1..];
        let mut rest = js;
        while let Some(i) = rest.find(pat) {
            rest = &rest[i + pat.len()..];
            if let Some(j) = rest.find(quote) {
                let spec = &rest[..j];
                if !spec.contains(' ') && !spec.contains('\n') && spec.ends_with(".js")
                    || spec == "three"
                {
                    out.push(spec.to_string());
                }
            }
        }
    }
    out
}

/// Resolves a specifier of the module at `base` the way the page's import map does.
fn resolve(base: &str, spec: &str) -> String {
    if spec == "three" {
        return "/vendor/three/three.module.js".into();
    }
    if let Some(rest) = spec.strip_prefix("three/addons/") {
        return format!("/vendor/three/addons/{rest}");
    }
    let mut parts: Vec<&str> = base.split('/').collect();
    parts.pop();
    for seg in spec.split('/') {
        match seg {
            "." => {}
            ".." => {
                parts.pop();
            }
            s => parts.push(s),
        }
    }
    parts.join("/")
}

#[test]
fn every_import_of_every_served_script_resolves() {
    let mut checked = 0;
    for a in ASSETS.iter().filter(|a| a.path.ends_with(".js")) {
        let js = std::str::from_utf8(a.bytes).unwrap();
        for spec in imports(js) {
            // Documentation comments in three.js name import paths too; they resolve the same.
            let url = resolve(a.path, &spec);
            assert!(
                asset(&url).is_some(),
                "{} imports `{spec}` = {url}, which is not served",
                a.path
            );
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} imports found");
    let page = std::str::from_utf8(asset("/").unwrap().bytes).unwrap();
    for needed in ["/viewer.js", "/viewer.css", "/vendor/three/three.module.js"] {
        assert!(page.contains(needed), "index.html must load {needed}");
        assert!(asset(needed).is_some());
    }
}
