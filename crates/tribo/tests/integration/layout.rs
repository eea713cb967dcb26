//! The house rules of the core crate, checked by reading its sources (`src/**`):
//!
//! * **the layer rule**: `error → choice → settings → [mesh → fem → contact] and [linalg →
//!   condensation → qp] → problem → results → solve → adapt`. A folder uses only the folders before it in its
//!   row of [`LAYERS`]; the two bracketed towers never use each other; `linalg` uses nothing of the crate;
//! * **files readable in one sitting**: at most [`MAX_LINES`] lines outside a file's `#[cfg(test)]`
//!   module ([`MAX_LINES_LINALG`] for the sparse kernels in `linalg/`).
//!
//! A use is a `crate::x` path in code (doc comments and the unit tests do not count), in a `use` line or
//! inline, `use crate::{x, y}` groups included.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Each folder (or top-level file) of `src/` and the folders it may use.
const LAYERS: &[(&str, &[&str])] = &[
    ("error", &[]),
    ("choice", &["error"]),
    ("settings", &["error", "choice"]),
    ("mesh", &["error", "choice", "settings"]),
    ("fem", &["error", "choice", "settings", "mesh"]),
    ("contact", &["error", "choice", "settings", "mesh", "fem"]),
    ("linalg", &[]),
    ("condensation", &["error", "choice", "settings", "linalg"]),
    ("qp", &["error", "choice", "settings", "linalg", "condensation"]),
    ("problem", &["error", "choice", "settings", "mesh", "fem", "contact", "linalg", "condensation", "qp"]),
    ("results", &["error", "choice", "settings", "mesh", "fem", "contact", "linalg", "condensation", "qp", "problem"]),
    (
        "solve",
        &[
            "error",
            "choice",
            "settings",
            "mesh",
            "fem",
            "contact",
            "linalg",
            "condensation",
            "qp",
            "problem",
            "results",
        ],
    ),
    (
        "adapt",
        &[
            "error",
            "choice",
            "settings",
            "mesh",
            "fem",
            "contact",
            "linalg",
            "condensation",
            "qp",
            "problem",
            "results",
            "solve",
        ],
    ),
];

/// Lines a file may hold outside its unit tests.
const MAX_LINES: usize = 600;
/// The same for the sparse kernels of `linalg/`: a supernodal sweep, its symbolic analysis and its
/// refinement read best in one file.
const MAX_LINES_LINALG: usize = 800;

/// Every source file under `src/` with its text, except `lib.rs` and files that are test modules
/// (declared under `#[cfg(test)]` by their parent).
fn sources() -> Vec<(PathBuf, String)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("src/ is readable") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().and_then(|e| e.to_str()) == Some("rs") {
                out.push(path);
            }
        }
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    walk(&src, &mut files);
    files.sort();
    let texts: Vec<(PathBuf, String)> = files
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("readable source");
            (p.strip_prefix(&src).expect("under src").to_path_buf(), text)
        })
        .collect();
    // `#[cfg(test)] mod name;` in a parent declares a test-only file `name.rs` beside it (or in its folder).
    let mut test_only = BTreeSet::new();
    for (path, text) in &texts {
        let dir = if path.file_name().is_some_and(|n| n == "mod.rs" || n == "lib.rs") {
            path.parent().map(Path::to_path_buf).unwrap_or_default()
        } else {
            path.with_extension("")
        };
        let lines: Vec<&str> = text.lines().map(str::trim).collect();
        for w in lines.windows(2) {
            if w[0] == "#[cfg(test)]" {
                if let Some(name) = w[1].strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
                    test_only.insert(dir.join(format!("{name}.rs")));
                }
            }
        }
    }
    texts.into_iter().filter(|(p, _)| p != Path::new("lib.rs") && !test_only.contains(p)).collect()
}

/// The folder (or top-level file) a source file belongs to: the first component of its path.
fn folder(path: &Path) -> String {
    let first = path.components().next().expect("a path").as_os_str().to_string_lossy().to_string();
    first.strip_suffix(".rs").unwrap_or(&first).to_string()
}

/// The code of a file above its unit tests, without comment lines.
fn code(text: &str) -> String {
    text.split("#[cfg(test)]\nmod tests")
        .next()
        .unwrap_or("")
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The top-level names a piece of code reaches through `crate::`.
fn crate_uses(code: &str) -> BTreeSet<String> {
    let mut deps = BTreeSet::new();
    for (i, _) in code.match_indices("crate::") {
        // `$crate::` in a macro is the macro's own crate path, resolved where it is expanded.
        if code[..i].ends_with('$') {
            continue;
        }
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let group = &group[..group.find('}').unwrap_or(group.len())];
            for item in group.split(',') {
                deps.insert(item.trim().split("::").next().unwrap_or("").trim().to_string());
            }
        } else {
            deps.insert(rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect());
        }
    }
    deps
}

/// Folder → the folders it uses, with the file that does it for each edge.
fn folder_edges() -> BTreeMap<String, BTreeMap<String, String>> {
    let known: BTreeSet<&str> = LAYERS.iter().map(|(f, _)| *f).collect();
    let mut edges: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    for (path, text) in sources() {
        let from = folder(&path);
        let entry = edges.entry(from.clone()).or_default();
        for to in crate_uses(&code(&text)) {
            if to != from && known.contains(to.as_str()) {
                entry.entry(to).or_insert_with(|| path.display().to_string());
            }
        }
    }
    edges
}

#[test]
fn every_folder_uses_only_the_folders_below_it() {
    let edges = folder_edges();
    let allowed: BTreeMap<&str, &[&str]> = LAYERS.iter().copied().collect();
    for f in edges.keys() {
        assert!(allowed.contains_key(f.as_str()), "src/{f} is not in the layer table: add it to LAYERS");
    }
    assert!(edges["solve"].contains_key("qp"), "the uses are read: {:?}", edges["solve"]);
    let mut wrong = Vec::new();
    for (from, to) in &edges {
        for (t, file) in to {
            if !allowed[from.as_str()].contains(&t.as_str()) {
                wrong.push(format!("{from} -> {t} (in src/{file})"));
            }
        }
    }
    assert!(wrong.is_empty(), "uses against the layer rule:\n{}", wrong.join("\n"));
}

/// The table itself is a layering: every folder may use only folders listed before it, so no cycle can
/// pass, and the two towers stay apart.
#[test]
fn the_layer_table_is_a_layering() {
    for (k, (f, uses)) in LAYERS.iter().enumerate() {
        let before: Vec<&str> = LAYERS[..k].iter().map(|(g, _)| *g).collect();
        for u in *uses {
            assert!(before.contains(u), "{f} may use {u}, which is not below it");
        }
    }
    let allowed: BTreeMap<&str, &[&str]> = LAYERS.iter().copied().collect();
    let (geometry, algebra) = (["mesh", "fem", "contact"], ["linalg", "condensation", "qp"]);
    for a in geometry {
        for b in algebra {
            assert!(!allowed[a].contains(&b) && !allowed[b].contains(&a), "{a} and {b} are in different towers");
        }
    }
    assert!(allowed["linalg"].is_empty(), "linalg uses nothing of the crate");
}

/// A use against the rule is seen: the reader finds `crate::` paths in both forms and skips comments.
#[test]
fn a_use_against_the_rule_is_seen() {
    let text = "//! uses crate::solve in a doc\nuse crate::{error::Error, qp::X};\nfn f() { crate::problem::g() }\n";
    let uses = crate_uses(&code(text));
    assert_eq!(uses, BTreeSet::from(["error".into(), "qp".into(), "problem".into()]));
    let allowed: BTreeMap<&str, &[&str]> = LAYERS.iter().copied().collect();
    assert!(!allowed["qp"].contains(&"problem"), "qp -> problem would be refused");
}

#[test]
fn every_file_is_readable_in_one_sitting() {
    let mut long = Vec::new();
    let files = sources();
    assert!(files.len() > 30, "the files were read: {}", files.len());
    for (path, text) in files {
        let lines = text.split("#[cfg(test)]\nmod tests").next().unwrap_or("").lines().count();
        let max = if folder(&path) == "linalg" { MAX_LINES_LINALG } else { MAX_LINES };
        if lines > max {
            long.push(format!("src/{}: {lines} lines (at most {max})", path.display()));
        }
    }
    assert!(long.is_empty(), "files too long to read in one sitting:\n{}", long.join("\n"));
}
