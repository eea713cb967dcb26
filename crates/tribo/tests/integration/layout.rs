//! The module structure of the core crate: no module imports (through `use crate::…` or a `crate::…`
//! path) a module that imports it back, directly or through others. Checked by reading the sources, so
//! a cycle introduced later fails here with the cycle spelled out.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Module name → the modules of the crate it refers to.
fn imports() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut modules = BTreeMap::new();
    for entry in std::fs::read_dir(&src).expect("src/ is readable") {
        let path = entry.expect("entry").path();
        let name = path.file_stem().and_then(|s| s.to_str()).expect("file name").to_string();
        if path.extension().and_then(|e| e.to_str()) != Some("rs") || name == "lib" {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("readable source");
        // The code above the unit tests, without comments (a doc link is not an import): `crate::x`
        // paths anywhere in it, `use crate::{x, y}` groups too.
        let code: String = text
            .split("#[cfg(test)]")
            .next()
            .unwrap_or("")
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n");
        let mut deps = BTreeSet::new();
        for (i, _) in code.match_indices("crate::") {
            let rest = &code[i + "crate::".len()..];
            if let Some(group) = rest.strip_prefix('{') {
                let group = &group[..group.find('}').unwrap_or(group.len())];
                for item in group.split(',') {
                    let m = item.trim().split("::").next().unwrap_or("").trim();
                    deps.insert(m.to_string());
                }
            } else {
                let m: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                deps.insert(m);
            }
        }
        modules.insert(name, deps);
    }
    let known: BTreeSet<String> = modules.keys().cloned().collect();
    for (name, deps) in modules.iter_mut() {
        deps.retain(|d| known.contains(d) && d != name);
    }
    modules
}

/// A cycle through `start`, if any, as a list of modules.
fn cycle_from(start: &str, graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        m: &str,
        start: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        seen: &mut BTreeSet<String>,
    ) -> bool {
        for d in &graph[m] {
            if d == start {
                path.push(d.clone());
                return true;
            }
            if seen.insert(d.clone()) {
                path.push(d.clone());
                if visit(d, start, graph, path, seen) {
                    return true;
                }
                path.pop();
            }
        }
        false
    }
    let mut path = vec![start.to_string()];
    visit(start, start, graph, &mut path, &mut BTreeSet::new()).then_some(path)
}

#[test]
fn core_modules_have_no_import_cycle() {
    let graph = imports();
    assert!(graph.len() > 10, "the module list was read: {:?}", graph.keys());
    assert!(graph["solve"].contains("working_set"), "imports are read: {:?}", graph["solve"]);
    for m in graph.keys() {
        if let Some(cycle) = cycle_from(m, &graph) {
            panic!("import cycle: {}", cycle.join(" -> "));
        }
    }
}

/// The test above would see a cycle: a graph with one is reported.
#[test]
fn a_cycle_is_detected() {
    let mut graph = BTreeMap::new();
    graph.insert("a".to_string(), BTreeSet::from(["b".to_string()]));
    graph.insert("b".to_string(), BTreeSet::from(["c".to_string()]));
    graph.insert("c".to_string(), BTreeSet::from(["a".to_string()]));
    assert_eq!(cycle_from("a", &graph), Some(vec!["a".into(), "b".into(), "c".into(), "a".into()]));
    graph.insert("c".to_string(), BTreeSet::new());
    assert_eq!(cycle_from("a", &graph), None);
}
