//! The crate's layers (docs/architecture.md): the top-level modules of `src/` import one
//! another in one direction only, and no model family imports another family's folder.
//!
//! The test reads the sources, not the compiled crate: for every file of `src/` that is not
//! test code it collects the `crate::` paths (in `use` lists too, nested braces expanded, and
//! `super::` chains that climb to the crate root), maps each to the top-level module it names,
//! and checks that the graph of those edges has no cycle (Tarjan's strongly connected
//! components). Test code is left out: a file named `tests.rs`, `*_tests.rs`, `test_support.rs`
//! or `*_test_support.rs`, a module declared under `#[cfg(test)]` (with everything under it),
//! an inline `#[cfg(test)] mod` block, and comments (doc examples are the public API's
//! users, not its layers). When the graph has a cycle, the message lists every edge inside it
//! with the files that make it, so the import that runs back up is named.
//!
//! What it cannot see: a path spelled through a macro that builds it from pieces, or a glob
//! `use` of a module that re-exports another (both are absent from the sources today).
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One source file: its module path (`["model", "rigid_body", "problem"]`), its text with
/// comments and inline test modules removed, and whether it is test code.
struct Source {
    module: Vec<String>,
    path: PathBuf,
    code: String,
    test: bool,
}

/// The module path of `file` under `src/` (`mod.rs` names its folder).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// Every `.rs` file under `dir`, sorted.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// `text` without comments (line and block) and string literals' contents.
fn strip_comments(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if b[i] == b'"' {
            out.push('"');
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            out.push('"');
            i += 1;
        } else if b[i] == b'\'' && b.get(i + 2) == Some(&b'\'') {
            i += 3;
        } else {
            out.push(b[i] as char);
            i += 1;
        }
    }
    out
}

/// `code` with every inline `#[cfg(test)] mod name { ... }` block removed, and the names of
/// the modules it declares under `#[cfg(test)]` as files (`#[cfg(test)] mod name;`).
fn strip_test_modules(code: &str) -> (String, Vec<String>) {
    let mut out = String::with_capacity(code.len());
    let mut test_files = vec![];
    let mut rest = code;
    while let Some(at) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..at]);
        let after = &rest[at + "#[cfg(test)]".len()..];
        let trimmed = after.trim_start();
        let decl = trimmed
            .strip_prefix("pub(crate) mod ")
            .or_else(|| trimmed.strip_prefix("pub mod "))
            .or_else(|| trimmed.strip_prefix("mod "));
        let Some(decl) = decl else {
            // A test-only item other than a module: skip the attribute, keep the item.
            rest = after;
            continue;
        };
        let name: String = decl
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let tail = &decl[name.len()..];
        let tail_trim = tail.trim_start();
        if let Some(after_decl) = tail_trim.strip_prefix(';') {
            test_files.push(name);
            rest = after_decl;
        } else if tail_trim.starts_with('{') {
            let mut depth = 0usize;
            let mut end = tail_trim.len();
            for (i, ch) in tail_trim.char_indices() {
                match ch {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            end = i + 1;
                            break;
                        }
                    }
                    _ => {}
                }
            }
            rest = &tail_trim[end..];
        } else {
            rest = after;
        }
    }
    out.push_str(rest);
    (out, test_files)
}

/// Whether a file is test code by its name.
fn test_by_name(path: &Path) -> bool {
    let stem = path.file_stem().unwrap().to_string_lossy();
    stem == "tests" || stem.ends_with("_tests") || stem.ends_with("test_support")
}

/// The sources of `src/`, with test code marked.
fn sources(src: &Path) -> Vec<Source> {
    let mut paths = vec![];
    files(src, &mut paths);
    let mut out: Vec<Source> = vec![];
    let mut test_modules: BTreeSet<Vec<String>> = BTreeSet::new();
    for path in paths {
        let module = module_of(src, &path);
        let text = std::fs::read_to_string(&path).unwrap();
        let (code, tests) = strip_test_modules(&strip_comments(&text));
        // Modules declared here live under this module (`lib.rs` declares the crate root's).
        let parent: Vec<String> = if module == ["lib"] || module == ["main"] {
            vec![]
        } else {
            module.clone()
        };
        for t in tests {
            let mut m = parent.clone();
            m.push(t);
            test_modules.insert(m);
        }
        let test = test_by_name(&path);
        out.push(Source {
            module,
            path,
            code,
            test,
        });
    }
    for s in &mut out {
        if test_modules
            .iter()
            .any(|t| s.module.len() >= t.len() && s.module[..t.len()] == t[..])
        {
            s.test = true;
        }
    }
    out
}

/// The top-level modules of `src/` (its files and folders, less `lib` and `main`).
fn top_level(src: &Path) -> BTreeSet<String> {
    std::fs::read_dir(src)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter_map(|p| {
            let name = p.file_stem()?.to_string_lossy().into_owned();
            (p.is_dir() || p.extension().is_some_and(|x| x == "rs")).then_some(name)
        })
        .filter(|n| n != "lib" && n != "main")
        .collect()
}

/// The module paths (from the crate root) that `code`, in module `module`, names.
fn paths_named(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut out = vec![];
    let bytes = code.as_bytes();
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    for start in ["crate::", "super::"] {
        let mut from = 0;
        while let Some(k) = code[from..].find(start) {
            let at = from + k;
            from = at + start.len();
            let chained = at >= 2 && &code[at - 2..at] == "::";
            if chained || at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_')
            {
                continue;
            }
            // The module the path starts from, and the text after the `crate::`/`super::`s.
            let (mut base, mut rest): (Vec<String>, &str) = if start == "crate::" {
                (vec![], &code[from..])
            } else {
                let mut b = module.to_vec();
                b.pop();
                (b, &code[from..])
            };
            while let Some(r) = rest.strip_prefix("super::") {
                base.pop();
                rest = r;
            }
            if let Some(group) = rest.strip_prefix('{') {
                for item in split_group(group) {
                    let mut p = base.clone();
                    p.push(ident(item.trim()));
                    out.push(p);
                }
            } else {
                let mut p = base;
                p.push(ident(rest));
                out.push(p);
            }
        }
    }
    out
}

/// The top-level items of a `use` group `a, b::{c, d}, e}` (up to its closing brace).
fn split_group(group: &str) -> Vec<&str> {
    let mut items = vec![];
    let mut depth = 0usize;
    let mut start = 0;
    for (i, ch) in group.char_indices() {
        match ch {
            '{' => depth += 1,
            '}' if depth == 0 => {
                items.push(&group[start..i]);
                return items;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&group[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items
}

/// Edges `from -> to` between the nodes `node_of` gives, with the files that make each.
type Edges = BTreeMap<(String, String), BTreeSet<String>>;

fn edges(src: &Path, node_of: impl Fn(&[String]) -> Option<String>) -> Edges {
    let mut out: Edges = BTreeMap::new();
    for s in sources(src).iter().filter(|s| !s.test) {
        let Some(from) = node_of(&s.module) else {
            continue;
        };
        for p in paths_named(&s.code, &s.module) {
            if let Some(to) = node_of(&p)
                && to != from
            {
                out.entry((from.clone(), to))
                    .or_default()
                    .insert(s.path.strip_prefix(src).unwrap().display().to_string());
            }
        }
    }
    out
}

/// The strongly connected components of more than one node (Tarjan), each sorted.
fn cycles(edges: &Edges) -> Vec<Vec<String>> {
    let nodes: BTreeSet<&String> = edges.keys().flat_map(|(a, b)| [a, b]).collect();
    let succ = |v: &String| -> Vec<&String> {
        edges
            .keys()
            .filter(|(a, _)| a == v)
            .map(|(_, b)| b)
            .collect()
    };
    struct T<'a> {
        index: BTreeMap<&'a String, usize>,
        low: BTreeMap<&'a String, usize>,
        stack: Vec<&'a String>,
        on: BTreeSet<&'a String>,
        next: usize,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(v: &'a String, t: &mut T<'a>, succ: &dyn Fn(&String) -> Vec<&'a String>) {
        t.index.insert(v, t.next);
        t.low.insert(v, t.next);
        t.next += 1;
        t.stack.push(v);
        t.on.insert(v);
        for w in succ(v) {
            if !t.index.contains_key(w) {
                visit(w, t, succ);
                let lw = t.low[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if t.on.contains(w) {
                let iw = t.index[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if t.low[v] == t.index[v] {
            let mut comp = vec![];
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                comp.push(w.clone());
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
    let mut t = T {
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: vec![],
        on: BTreeSet::new(),
        next: 0,
        out: vec![],
    };
    for v in nodes {
        if !t.index.contains_key(v) {
            visit(v, &mut t, &succ);
        }
    }
    t.out
}

/// The message of a failed check: every edge inside each cycle, with its files.
fn explain(edges: &Edges, cycles: &[Vec<String>]) -> String {
    let mut msg = String::new();
    for c in cycles {
        msg.push_str(&format!("cycle of {} modules: {}\n", c.len(), c.join(", ")));
        for ((a, b), files) in edges {
            if c.contains(a) && c.contains(b) {
                let f: Vec<&str> = files.iter().map(String::as_str).collect();
                msg.push_str(&format!("  {a} -> {b}: {}\n", f.join(", ")));
            }
        }
    }
    msg
}

/// Each node's layer: 0 for a module importing none of the others, else one more than the
/// highest layer it imports (defined on an acyclic graph).
fn layers(edges: &Edges, nodes: &BTreeSet<String>) -> BTreeMap<String, usize> {
    let mut layer: BTreeMap<String, usize> = nodes.iter().map(|n| (n.clone(), 0)).collect();
    for _ in 0..nodes.len() {
        for (a, b) in edges.keys() {
            let lb = layer.get(b).copied().unwrap_or(0);
            let la = layer.entry(a.clone()).or_insert(0);
            *la = (*la).max(lb + 1);
        }
    }
    layer
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The top-level modules of `src/` import one another without a cycle; run with
/// `--nocapture` to see the layers.
#[test]
fn top_level_modules_have_no_cycle() {
    let src = src();
    let tops = top_level(&src);
    let e = edges(&src, |m| m.first().filter(|t| tops.contains(*t)).cloned());
    assert!(
        e.len() > 20,
        "the scan found only {} edges: is it reading src/?",
        e.len()
    );
    let c = cycles(&e);
    assert!(c.is_empty(), "imports run back up:\n{}", explain(&e, &c));
    let by_layer = layers(&e, &tops);
    let top = by_layer.values().copied().max().unwrap_or(0);
    for l in 0..=top {
        let names: Vec<&str> = by_layer
            .iter()
            .filter(|(_, k)| **k == l)
            .map(|(n, _)| n.as_str())
            .collect();
        println!("layer {l}: {}", names.join(", "));
    }
}

/// No model family's code imports another family's folder (what two families share lives
/// below `model/`).
#[test]
fn families_do_not_import_each_other() {
    let src = src();
    let e = edges(&src, |m| match m {
        [model, family, ..] if model == "model" => Some(family.clone()),
        _ => None,
    });
    let families: BTreeSet<String> = std::fs::read_dir(src.join("model"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    let crossing: Vec<String> = e
        .iter()
        .filter(|((a, b), _)| families.contains(a) && families.contains(b))
        .map(|((a, b), f)| format!("{a} -> {b}: {f:?}"))
        .collect();
    assert!(
        crossing.is_empty(),
        "families import each other:\n{}",
        crossing.join("\n")
    );
}

/// The scanner itself: a `use` group with nested braces, a `super::` chain to the crate
/// root, a comment and an inline test module are read as they should be.
#[test]
fn scanner_reads_paths_groups_and_test_code() {
    let code = "use crate::{a::X, b::{c, d}, e};\nfn f() { super::super::g::h(); }\n\
                // crate::comment\n#[cfg(test)]\nmod tests { use crate::hidden; }\n";
    let (code, tests) = strip_test_modules(&strip_comments(code));
    assert!(tests.is_empty());
    let m: Vec<String> = ["x", "y"].iter().map(|s| s.to_string()).collect();
    let tops: Vec<String> = paths_named(&code, &m)
        .into_iter()
        .map(|p| p.join("::"))
        .collect();
    assert_eq!(tops, ["a", "b", "e", "g"], "{code}");
    let (_, files) = strip_test_modules("#[cfg(test)]\nmod conformance;\nmod kept;");
    assert_eq!(files, ["conformance"]);
}
