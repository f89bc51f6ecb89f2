//! The layering rule, checked on the source: no import cycle between the top-level modules
//! of the library, and `render` a leaf (it takes plain data).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Every `crate::module` a top-level module names outside comments, by module.
fn imports() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let top: BTreeSet<String> = std::fs::read_dir(&src)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .filter(|m| !matches!(m.as_str(), "lib" | "main" | "cli" | "layers"))
        .collect();
    let mut out: BTreeMap<String, BTreeSet<String>> = top.iter().map(|m| (m.clone(), BTreeSet::new())).collect();
    let mut files = vec![src.clone()];
    while let Some(p) = files.pop() {
        if p.is_dir() {
            files.extend(std::fs::read_dir(&p).unwrap().map(|e| e.unwrap().path()));
            continue;
        }
        let rel = p.strip_prefix(&src).unwrap();
        let module = rel.components().next().unwrap().as_os_str().to_string_lossy();
        let module = module.trim_end_matches(".rs").to_string();
        if !top.contains(&module) || p.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        for line in std::fs::read_to_string(&p).unwrap().lines() {
            let code = line.split("//").next().unwrap_or("");
            for (i, _) in code.match_indices("crate::") {
                let rest = &code[i + "crate::".len()..];
                let names: Vec<&str> = match rest.strip_prefix('{') {
                    Some(group) => group.split([',', '}']).map(|n| n.trim().split("::").next().unwrap_or("")).collect(),
                    None => vec![rest.split(|c: char| !c.is_alphanumeric() && c != '_').next().unwrap_or("")],
                };
                for n in names {
                    if n != module && top.contains(n) {
                        out.get_mut(&module).unwrap().insert(n.to_string());
                    }
                }
            }
        }
    }
    out
}

#[test]
fn layers_have_no_cycles() {
    let deps = imports();
    // Depth-first search for a back edge; on one, report the cycle.
    fn visit(
        m: &str,
        deps: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        match state.get(m) {
            Some(2) => return None,
            Some(1) => {
                let start = path.iter().position(|p| p == m).unwrap();
                return Some(path[start..].iter().cloned().chain([m.to_string()]).collect());
            }
            _ => {}
        }
        state.insert(m.to_string(), 1);
        path.push(m.to_string());
        for d in &deps[m] {
            if let Some(cycle) = visit(d, deps, state, path) {
                return Some(cycle);
            }
        }
        path.pop();
        state.insert(m.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for m in deps.keys() {
        let cycle = visit(m, &deps, &mut state, &mut Vec::new());
        assert!(cycle.is_none(), "import cycle between top-level modules: {}", cycle.unwrap().join(" → "));
    }
    assert!(deps["render"].is_empty(), "render must be a leaf taking plain data, but imports {:?}", deps["render"]);
    assert!(!deps["design"].contains("formulations"), "design code never imports formulations");
    assert!(!deps["heuristics"].contains("formulations"), "heuristics return designs only");
}
