//! The layering rule, checked on the source: no import cycle between the top-level modules
//! of the library, and `render` a leaf (it takes plain data); no import cycle between the files
//! of one module either (its top `mod.rs` excepted: it names the files and holds what they
//! share).

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

/// A cycle of `deps` (its nodes in order, the first repeated at the end), by a depth-first
/// search for a back edge.
fn find_cycle<K: Ord + Clone>(deps: &BTreeMap<K, BTreeSet<K>>) -> Option<Vec<K>> {
    fn visit<K: Ord + Clone>(
        m: &K,
        deps: &BTreeMap<K, BTreeSet<K>>,
        state: &mut BTreeMap<K, u8>,
        path: &mut Vec<K>,
    ) -> Option<Vec<K>> {
        match state.get(m) {
            Some(2) => return None,
            Some(1) => {
                let start = path.iter().position(|p| p == m).unwrap();
                return Some(path[start..].iter().cloned().chain([m.clone()]).collect());
            }
            _ => {}
        }
        state.insert(m.clone(), 1);
        path.push(m.clone());
        for d in &deps[m] {
            if let Some(cycle) = visit(d, deps, state, path) {
                return Some(cycle);
            }
        }
        path.pop();
        state.insert(m.clone(), 2);
        None
    }
    let mut state = BTreeMap::new();
    deps.keys().find_map(|m| visit(m, deps, &mut state, &mut Vec::new()))
}

#[test]
fn layers_have_no_cycles() {
    let deps = imports();
    if let Some(cycle) = find_cycle(&deps) {
        panic!("import cycle between top-level modules: {}", cycle.join(" → "));
    }
    assert!(deps["render"].is_empty(), "render must be a leaf taking plain data, but imports {:?}", deps["render"]);
    assert!(!deps["design"].contains("formulations"), "design code never imports formulations");
    assert!(!deps["heuristics"].contains("formulations"), "heuristics return designs only");
}

/// A module path (`compare::plan`; `layout::template` for `layout/template/mod.rs`).
type ModPath = Vec<String>;

/// Every file of a module directory under `src/`, by module path, and whether it is a `mod.rs`.
fn module_files(src: &Path) -> BTreeMap<ModPath, (std::path::PathBuf, bool)> {
    let mut out = BTreeMap::new();
    let mut dirs: Vec<std::path::PathBuf> = std::fs::read_dir(src)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir() && p.file_name().is_some_and(|n| n != "cli"))
        .collect();
    while let Some(d) = dirs.pop() {
        for p in std::fs::read_dir(&d).unwrap().map(|e| e.unwrap().path()) {
            if p.is_dir() {
                dirs.push(p);
                continue;
            }
            if p.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let rel = p.strip_prefix(src).unwrap().with_extension("");
            let mut parts: ModPath = rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
            let is_mod = parts.last().is_some_and(|l| l == "mod");
            if is_mod {
                parts.pop();
            }
            out.insert(parts, (p, is_mod));
        }
    }
    out
}

/// The code of a file without comments and without its `#[cfg(test)] mod tests`.
fn code_of(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let mut code = String::new();
    let mut in_block = false;
    for line in text.lines() {
        let mut rest = line;
        let mut kept = String::new();
        loop {
            if in_block {
                match rest.find("*/") {
                    Some(i) => {
                        rest = &rest[i + 2..];
                        in_block = false;
                    }
                    None => break,
                }
            } else {
                let line_comment = rest.find("//");
                let block = rest.find("/*");
                match (line_comment, block) {
                    (Some(l), b) if b.is_none_or(|b| l < b) => {
                        kept.push_str(&rest[..l]);
                        break;
                    }
                    (_, Some(b)) => {
                        kept.push_str(&rest[..b]);
                        rest = &rest[b + 2..];
                        in_block = true;
                    }
                    _ => {
                        kept.push_str(rest);
                        break;
                    }
                }
            }
        }
        if kept.trim_start().starts_with("mod tests") && code.trim_end().ends_with("#[cfg(test)]") {
            code.truncate(code.trim_end().len() - "#[cfg(test)]".len());
            break;
        }
        code.push_str(&kept);
        code.push('\n');
    }
    code
}

/// `a::{b, c::{d, e as f}}` → `a::b`, `a::c::d`, `a::c::e` (the names as imported; `*` kept).
fn expand_use(path: &str) -> Vec<String> {
    let Some(open) = path.find('{') else { return vec![path.split(" as ").next().unwrap().trim().to_string()] };
    let (prefix, inner) = (&path[..open], &path[open + 1..path.len() - 1]);
    let (mut parts, mut depth, mut cur) = (Vec::new(), 0, String::new());
    for ch in inner.chars() {
        match ch {
            '{' => depth += 1,
            '}' => depth -= 1,
            _ => {}
        }
        if ch == ',' && depth == 0 {
            parts.push(std::mem::take(&mut cur));
        } else {
            cur.push(ch);
        }
    }
    parts.push(cur);
    parts.iter().map(|p| p.trim()).filter(|p| !p.is_empty()).flat_map(|p| expand_use(&format!("{prefix}{p}"))).collect()
}

/// The paths a file names: `(path, whether a `pub use` names it)`.
fn named_paths(code: &str, children: &BTreeSet<String>) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let bytes: Vec<char> = code.chars().collect();
    let text: String = bytes.iter().collect();
    // `use` statements, with their groups.
    let mut rest_code = String::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts_use = text[char_offset(&text, i)..].starts_with("use ")
            && (i == 0 || !ident(bytes[i - 1]))
            && bytes[..i].iter().rev().find(|c| !c.is_whitespace()).is_none_or(|c| ";{}])".contains(*c) || *c == 'b');
        if starts_use {
            let end = bytes[i..].iter().position(|&c| c == ';').map_or(bytes.len(), |e| i + e);
            let words: String = bytes[i + 4..end].iter().collect();
            let mut statement = words.split_whitespace().collect::<Vec<_>>().join(" ");
            for sep in ["::", "{", "}", ","] {
                statement = statement.replace(&format!(" {sep}"), sep).replace(&format!("{sep} "), sep);
            }
            let before: String = bytes[..i].iter().collect();
            let is_pub = before.trim_end().ends_with("pub") || before.trim_end().ends_with(')');
            out.extend(expand_use(&statement).into_iter().map(|p| (p, is_pub)));
            i = end + 1;
            continue;
        }
        rest_code.push(bytes[i]);
        i += 1;
    }
    // Paths in the code.
    let chars: Vec<char> = rest_code.chars().collect();
    for start in 0..chars.len() {
        if start > 0 && (ident(chars[start - 1]) || chars[start - 1] == ':') {
            continue;
        }
        let mut end = start;
        while end < chars.len() && (ident(chars[end]) || (chars[end] == ':' && chars.get(end + 1) == Some(&':'))) {
            end += if chars[end] == ':' { 2 } else { 1 };
        }
        let path: String = chars[start..end].iter().collect();
        let head = path.split("::").next().unwrap_or("");
        if path.contains("::") && (matches!(head, "crate" | "super" | "self") || children.contains(head)) {
            out.push((path.trim_end_matches(':').to_string(), false));
        }
    }
    out
}

fn char_offset(text: &str, chars: usize) -> usize {
    text.char_indices().nth(chars).map_or(text.len(), |(i, _)| i)
}

/// A named path made absolute from the file `at` (a `mod.rs` when `is_mod`).
fn absolute(at: &ModPath, is_mod: bool, path: &str, children: &BTreeSet<String>) -> Option<ModPath> {
    let segs: Vec<String> = path.split("::").filter(|s| !s.is_empty()).map(String::from).collect();
    let (mut base, mut rest): (ModPath, &[String]) = match segs.first()?.as_str() {
        "crate" => (Vec::new(), &segs[1..]),
        "self" => (at.clone(), &segs[1..]),
        "super" => (at[..at.len().saturating_sub(1)].to_vec(), &segs[1..]),
        head if is_mod && children.contains(head) => (at.clone(), &segs[..]),
        _ => return None,
    };
    while rest.first().is_some_and(|s| s == "super") {
        base.pop();
        rest = &rest[1..];
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

#[test]
fn files_of_a_module_have_no_cycles() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = module_files(&src);
    let children = |m: &ModPath| -> BTreeSet<String> {
        files.keys().filter(|k| k.len() == m.len() + 1 && k.starts_with(m)).map(|k| k.last().unwrap().clone()).collect()
    };
    let longest = |path: &ModPath| (1..=path.len()).rev().map(|k| path[..k].to_vec()).find(|p| files.contains_key(p));
    let named: BTreeMap<ModPath, Vec<(String, bool)>> =
        files.iter().map(|(m, (p, _))| (m.clone(), named_paths(&code_of(p), &children(m)))).collect();
    // What each `mod.rs` re-exports, by (module, name): the file that defines it.
    let mut reexports: BTreeMap<(ModPath, String), ModPath> = BTreeMap::new();
    for (m, (_, is_mod)) in &files {
        for (path, is_pub) in &named[m] {
            let Some(abs) = absolute(m, *is_mod, path, &children(m)).filter(|_| *is_mod && *is_pub) else { continue };
            if let Some(target) = longest(&abs).filter(|t| t != m && abs.len() > m.len()) {
                reexports.insert((m.clone(), abs.last().unwrap().clone()), target);
            }
        }
    }
    let mut deps: BTreeMap<ModPath, BTreeSet<ModPath>> = files.keys().map(|m| (m.clone(), BTreeSet::new())).collect();
    for (m, (_, is_mod)) in &files {
        for (path, is_pub) in &named[m] {
            if *is_mod && *is_pub {
                continue; // a module's re-export is its interface, not a dependency
            }
            let Some(abs) = absolute(m, *is_mod, path, &children(m)) else { continue };
            let Some(node) = longest(&abs) else { continue };
            let target = abs.get(node.len()).and_then(|name| reexports.get(&(node.clone(), name.clone())));
            let target = target.cloned().unwrap_or(node);
            if target != *m && target[0] == m[0] && target.len() > 1 && m.len() > 1 {
                deps.get_mut(m).unwrap().insert(target);
            }
        }
    }
    if let Some(cycle) = find_cycle(&deps) {
        let names: Vec<String> = cycle.iter().map(|p| p.join("::")).collect();
        panic!("import cycle between files of one module: {}", names.join(" → "));
    }
    // The rule sees references it must: a sibling named through a `use` group and by a path.
    assert!(deps[&vec!["compare".to_string(), "plan".into()]].contains(&vec!["compare".to_string(), "record".into()]));
    assert!(deps[&vec!["compare".to_string(), "cluster".into()]].contains(&vec!["compare".to_string(), "child".into()]));
}
