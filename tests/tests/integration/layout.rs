//! The layout rules of docs/architecture (ARCHITECTURE.md): within a crate, no two modules
//! import each other, directly or through others (a module and its own submodules are one
//! room: `codegen/value.rs` may use `codegen/mod.rs` and be used by it); and no source file
//! is longer than [`MAX_LINES`].

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest a source file may be.
const MAX_LINES: usize = 1200;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The workspace's crate directories (those with a `Cargo.toml` and a `src/`).
fn crates() -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(root())
        .expect("workspace root")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("Cargo.toml").is_file() && p.join("src").is_dir())
        .collect();
    out.sort();
    out
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The module path of a file under `src/` (`lib.rs`/`main.rs` → `[]`, `a/mod.rs` and `a.rs` →
/// `[a]`, `a/b.rs` → `[a, b]`).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).expect("file under src");
    let mut parts: Vec<String> = rel.iter().map(|c| c.to_string_lossy().into_owned()).collect();
    let last = parts.pop().expect("file name");
    let stem = last.trim_end_matches(".rs");
    if !(stem == "mod" || (parts.is_empty() && (stem == "lib" || stem == "main"))) {
        parts.push(stem.to_owned());
    }
    parts
}

/// Source without `//` comments (doc links are not imports).
fn strip_comments(text: &str) -> String {
    text.lines().map(|l| l.split_once("//").map_or(l, |(code, _)| code)).collect::<Vec<_>>().join("\n")
}

/// The paths `s` names from its start: `a::b::C` → `[[a, b, C]]`; `a::{b::C, d}` → `[[a, b, C],
/// [a, d]]`.
fn paths(s: &str) -> Vec<Vec<String>> {
    let mut head = Vec::new();
    let mut rest = s;
    loop {
        let n = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
        if n > 0 {
            head.push(rest[..n].to_owned());
            rest = &rest[n..];
        }
        let t = rest.trim_start();
        let next = match t.strip_prefix("::") {
            Some(after) => Some(after.trim_start()),
            None if head.is_empty() && t.starts_with('{') => Some(t),
            None => None,
        };
        if let Some(after) = next {
            if let Some(group) = after.strip_prefix('{') {
                let mut out = Vec::new();
                let (mut depth, mut start) = (0usize, 0usize);
                for (i, c) in group.char_indices() {
                    match c {
                        '{' => depth += 1,
                        '}' if depth == 0 => {
                            out.extend(group_item(&head, &group[start..i]));
                            return out;
                        }
                        '}' => depth -= 1,
                        ',' if depth == 0 => {
                            out.extend(group_item(&head, &group[start..i]));
                            start = i + 1;
                        }
                        _ => {}
                    }
                }
                return out;
            }
            rest = after;
            continue;
        }
        return vec![head];
    }
}

fn group_item(head: &[String], item: &str) -> Vec<Vec<String>> {
    let item = item.trim();
    if item.is_empty() {
        return Vec::new();
    }
    paths(item)
        .into_iter()
        .map(|p| {
            let mut full = head.to_vec();
            full.extend(p.into_iter().filter(|s| s != "self"));
            full
        })
        .collect()
}

/// For each module of the crate in `dir`, the other modules it names (by `crate::` or
/// `super::` paths), leaving out its ancestors and descendants.
fn module_graph(dir: &Path) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let src = dir.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let sources: Vec<(Vec<String>, String)> = files
        .iter()
        .map(|f| (module_of(&src, f), strip_comments(&std::fs::read_to_string(f).expect("read source"))))
        .collect();
    let modules: BTreeSet<Vec<String>> = sources.iter().map(|(m, _)| m.clone()).collect();
    let nested = |a: &[String], b: &[String]| a.starts_with(b) || b.starts_with(a);
    let mut graph = BTreeMap::new();
    for (module, text) in &sources {
        let mut deps = BTreeSet::new();
        for (key, base) in [("crate::", Vec::new()), ("super::", module[..module.len().saturating_sub(1)].to_vec())] {
            let mut at = 0;
            while let Some(i) = text[at..].find(key) {
                let start = at + i;
                at = start + key.len();
                if start > 0 && text[..start].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
                    continue;
                }
                for p in paths(&text[at..]) {
                    let mut full = base.clone();
                    full.extend(p);
                    // The longest prefix that is a module of this crate.
                    let target = (0..=full.len()).rev().map(|k| full[..k].to_vec()).find(|m| modules.contains(m));
                    if let Some(t) = target {
                        if !nested(&t, module) {
                            deps.insert(t);
                        }
                    }
                }
            }
        }
        graph.insert(module.clone(), deps);
    }
    graph
}

/// The strongly connected components of more than one module (Tarjan).
fn cycles(graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<String>> {
    struct T<'g> {
        graph: &'g BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        index: BTreeMap<&'g [String], (usize, usize)>,
        stack: Vec<&'g [String]>,
        next: usize,
        out: Vec<Vec<String>>,
    }
    fn visit<'g>(t: &mut T<'g>, v: &'g [String]) {
        t.index.insert(v, (t.next, t.next));
        t.next += 1;
        t.stack.push(v);
        for w in &t.graph[v] {
            let w = w.as_slice();
            if !t.index.contains_key(w) {
                visit(t, w);
                let lw = t.index[w].1;
                let e = t.index.get_mut(v).expect("visited");
                e.1 = e.1.min(lw);
            } else if t.stack.contains(&w) {
                let iw = t.index[w].0;
                let e = t.index.get_mut(v).expect("visited");
                e.1 = e.1.min(iw);
            }
        }
        let (i, low) = t.index[v];
        if i == low {
            let mut comp = Vec::new();
            while let Some(w) = t.stack.pop() {
                comp.push(if w.is_empty() { "(crate root)".to_owned() } else { w.join("::") });
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                t.out.push(comp);
            }
        }
    }
    let mut t = T { graph, index: BTreeMap::new(), stack: Vec::new(), next: 0, out: Vec::new() };
    for v in graph.keys() {
        if !t.index.contains_key(v.as_slice()) {
            visit(&mut t, v);
        }
    }
    t.out
}

#[test]
fn no_import_cycles_between_modules() {
    let mut found = Vec::new();
    for dir in crates() {
        let name = dir.file_name().expect("crate dir").to_string_lossy().into_owned();
        for c in cycles(&module_graph(&dir)) {
            found.push(format!("{name}: {}", c.join(" <-> ")));
        }
    }
    assert!(found.is_empty(), "modules that import each other:\n  {}", found.join("\n  "));
}

#[test]
fn the_cycle_finder_finds_cycles() {
    let m = |s: &str| s.split("::").map(str::to_owned).collect::<Vec<_>>();
    let mut g = BTreeMap::new();
    g.insert(m("a"), BTreeSet::from([m("b")]));
    g.insert(m("b"), BTreeSet::from([m("c")]));
    g.insert(m("c"), BTreeSet::from([m("a")]));
    g.insert(m("d"), BTreeSet::from([m("a")]));
    assert_eq!(cycles(&g), vec![vec!["a".to_owned(), "b".to_owned(), "c".to_owned()]]);
    assert_eq!(paths("a::{b::C, d, e::{f, self}} rest"), vec![m("a::b::C"), m("a::d"), m("a::e::f"), m("a::e")]);
    assert_eq!(paths("{x::Y, z}"), vec![m("x::Y"), m("z")]);
}

#[test]
fn no_source_file_is_longer_than_the_limit() {
    let mut long = Vec::new();
    for dir in crates() {
        let mut files = Vec::new();
        for sub in ["src", "tests", "benches", "examples", "build.rs"] {
            let p = dir.join(sub);
            if p.is_file() {
                files.push(p);
            } else {
                rust_files(&p, &mut files);
            }
        }
        for f in files {
            let n = std::fs::read_to_string(&f).expect("read source").lines().count();
            if n > MAX_LINES {
                long.push(format!("{} ({n} lines)", f.strip_prefix(root()).unwrap_or(&f).display()));
            }
        }
    }
    assert!(long.is_empty(), "files over {MAX_LINES} lines (cut them by idea):\n  {}", long.join("\n  "));
}
