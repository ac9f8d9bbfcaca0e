//! Tidy checks of the architecture invariants stated in ARCHITECTURE.md: crate layering
//! (dependencies point downwards only), which crates may use serde, faer and rayon, and that the
//! pointwise and numerical crates do no file access and no printing. Reads the manifests and
//! sources; builds nothing.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace root")
        .to_path_buf()
}

/// Layer of every workspace package (ARCHITECTURE.md code map).
fn layers() -> BTreeMap<&'static str, u32> {
    BTreeMap::from([
        ("tlsph-math", 0),
        ("tlsph-kernels", 1),
        ("tlsph-neighbours", 1),
        ("tlsph-materials", 1),
        ("tlsph-contact", 2),
        ("tlsph-solver", 3),
        ("tlsph-io", 4),
        ("tlsph-cli", 5),
        ("tlsph-validation", 5),
        ("xtask", 6),
    ])
}

/// (package name, directory, names of its normal [dependencies]) for every workspace member.
fn packages() -> Vec<(String, PathBuf, Vec<String>)> {
    let root = workspace_root();
    let mut dirs: Vec<PathBuf> = fs::read_dir(root.join("crates"))
        .expect("crates/ exists")
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.join("Cargo.toml").exists())
        .collect();
    dirs.sort();
    dirs.push(root.join("validation"));
    dirs.push(root.join("xtask"));
    dirs.into_iter()
        .map(|dir| {
            let path = dir.join("Cargo.toml");
            let text = fs::read_to_string(&path).expect("readable manifest");
            let manifest: toml::Table = text
                .parse()
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let name = manifest["package"]["name"]
                .as_str()
                .expect("package.name")
                .to_owned();
            let deps = manifest
                .get("dependencies")
                .and_then(|d| d.as_table())
                .map(|t| t.keys().cloned().collect())
                .unwrap_or_default();
            (name, dir, deps)
        })
        .collect()
}

#[test]
fn every_workspace_package_has_a_layer_and_depends_only_downwards() {
    let layers = layers();
    let packages = packages();
    assert_eq!(
        packages.len(),
        layers.len(),
        "a package was added or removed: give it a layer here and in ARCHITECTURE.md"
    );
    for (name, _, deps) in &packages {
        let own = *layers
            .get(name.as_str())
            .unwrap_or_else(|| panic!("`{name}` has no layer in ARCHITECTURE.md's code map"));
        for dep in deps {
            if let Some(&layer) = layers.get(dep.as_str()) {
                assert!(
                    layer < own,
                    "`{name}` (layer {own}) depends on `{dep}` (layer {layer}): dependencies must point downwards"
                );
            }
        }
    }
}

#[test]
fn only_the_allowed_crates_use_serde_faer_and_rayon() {
    // serde derives live on scene descriptions (io) and reference files (validation), never on
    // hot state; faer serves the linear-stability tool and fits (validation), never per-particle
    // code; materials are pointwise, so no rayon.
    let allowed: [(&str, &[&str]); 3] = [
        ("serde", &["tlsph-io", "tlsph-validation"]),
        ("faer", &["tlsph-validation"]),
        (
            "rayon",
            &["tlsph-neighbours", "tlsph-contact", "tlsph-solver"],
        ),
    ];
    for (name, _, deps) in packages() {
        for (crate_name, users) in allowed {
            if deps.iter().any(|d| d == crate_name) {
                assert!(
                    users.contains(&name.as_str()),
                    "`{name}` depends on `{crate_name}`, which only {users:?} may use"
                );
            }
        }
    }
}

/// Every `.rs` file under `dir`, recursively.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in fs::read_dir(dir).expect("readable source dir") {
        let path = entry.expect("readable entry").path();
        if path.is_dir() {
            out.extend(sources(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out
}

#[test]
fn numerical_crates_do_no_file_access_and_no_printing() {
    // The solver returns reports and errors; io writes files and the cli prints.
    let forbidden = [
        "std::fs",
        "File::",
        "println!",
        "eprintln!",
        "print!(",
        "dbg!(",
    ];
    let root = workspace_root();
    for krate in [
        "tlsph-math",
        "tlsph-kernels",
        "tlsph-neighbours",
        "tlsph-materials",
        "tlsph-contact",
        "tlsph-solver",
    ] {
        for file in sources(&root.join("crates").join(krate).join("src")) {
            let text = fs::read_to_string(&file).expect("readable source");
            for (line_no, line) in text.lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                for pattern in forbidden {
                    assert!(
                        !code.contains(pattern),
                        "{}:{}: `{pattern}` in a crate that must not do file access or print",
                        file.display(),
                        line_no + 1
                    );
                }
            }
        }
    }
}

#[test]
fn materials_are_pointwise() {
    // No particle indices' neighbours and no threads inside a material model.
    let root = workspace_root();
    for file in sources(&root.join("crates/tlsph-materials/src")) {
        let text = fs::read_to_string(&file).expect("readable source");
        for pattern in ["tlsph_neighbours", "rayon", "par_iter"] {
            assert!(
                !text.contains(pattern),
                "{}: `{pattern}` in a pointwise material model",
                file.display()
            );
        }
    }
}
