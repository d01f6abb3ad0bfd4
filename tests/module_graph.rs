//! The module graph has no two-module cycles: no pair of top-level modules (nor of
//! sibling submodules under one parent) names each other in non-test code.
//!
//! The graph is read from the sources, not from the compiler: every `.rs` file under
//! `src/`, `components/` and `systems/` is a module (`src/a/b.rs` and `src/a/b/mod.rs`
//! are `a::b`; `components/x.rs` is `components::x`; `src/main.rs` and `src/cli/` are
//! the binary, counted as the top-level module `cli`). Its `use` trees (braces
//! expanded) and the `crate::…` / `super::…` / child-module paths in its code are
//! resolved to modules; comments, doc comments and `#[cfg(test)]` code are left out.
//! An edge `a → b` joins the first modules where the file's path and the named path
//! part, under their common parent. A pair of edges `a → b`, `b → a` under the same
//! parent is a cycle. A second test holds every ECS `Component` and `Resource` in
//! `components/`. Inside the mesher (`mesh` and everything under it) the test is
//! stricter: no cycle of any length among sibling modules, with names a
//! directory module re-exports (`pub use error::CdtError`, named as
//! `super::CdtError`) followed to the module that defines them.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Module path of a file, e.g. `["mesh", "cdt", "ring"]`.
type ModPath = Vec<String>;

/// The top-level module the binary (`main.rs` and `src/cli/`) counts as.
const BINARY: &str = "cli";

/// Two-module cycles tolerated, as `(parent, a, b)` with `a < b`: none. A new
/// cycle fails the test; so does an entry here that no longer exists.
const ALLOWED: &[(&str, &str, &str)] = &[];

/// One source file: its module path, whether it is a directory module (`mod.rs`,
/// `lib.rs`, `main.rs`) and its non-test code without comments.
struct Source {
    module: ModPath,
    is_dir: bool,
    code: String,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a file relative to the repository, and whether it is a
/// directory module.
fn module_of(relative: &Path) -> (ModPath, bool) {
    let mut parts: Vec<String> = relative
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if parts[0] == "src" {
        parts.remove(0);
    }
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs").to_string();
    match stem.as_str() {
        "mod" => (parts, true),
        "lib" if parts.is_empty() => (parts, true),
        "main" if parts.is_empty() => (vec![BINARY.to_string()], true),
        _ => {
            parts.push(stem);
            (parts, false)
        }
    }
}

/// `text` without comments and string literals' contents (strings are kept as
/// empty quotes so a `//` inside one is not taken for a comment).
fn strip_comments(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        if c == b'/' && bytes.get(i + 1) == Some(&b'/') {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
        } else if c == b'/' && bytes.get(i + 1) == Some(&b'*') {
            let mut depth = 0;
            while i < bytes.len() {
                if bytes[i] == b'/' && bytes.get(i + 1) == Some(&b'*') {
                    depth += 1;
                    i += 2;
                } else if bytes[i] == b'*' && bytes.get(i + 1) == Some(&b'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == b'"' && (i == 0 || !matches!(bytes[i - 1], b'\'' | b'r' | b'#')) {
            // A plain string: skip to its closing quote.
            out.push_str("\"\"");
            i += 1;
            while i < bytes.len() && bytes[i] != b'"' {
                if bytes[i] == b'\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
        } else if c == b'r'
            && matches!(bytes.get(i + 1), Some(b'#' | b'"'))
            && is_raw_start(bytes, i)
        {
            // A raw string r#"…"#: skip to the matching close.
            let mut j = i + 1;
            let mut hashes = 0;
            while bytes.get(j) == Some(&b'#') {
                hashes += 1;
                j += 1;
            }
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            j += 1;
            while j < bytes.len() && !bytes[j..].starts_with(&close) {
                j += 1;
            }
            out.push_str("\"\"");
            i = j + close.len();
        } else if c == b'\'' && bytes.get(i + 2) == Some(&b'\'') {
            // A one-byte character literal such as '"'.
            out.push_str("' '");
            i += 3;
        } else if c == b'\'' && bytes.get(i + 1) == Some(&b'\\') {
            // An escaped character literal such as '\"'.
            let mut j = i + 2;
            while j < bytes.len() && bytes[j] != b'\'' {
                j += 1;
            }
            out.push_str("' '");
            i = j + 1;
        } else {
            let len = utf8_len(c);
            out.push_str(&text[i..i + len]);
            i += len;
        }
    }
    out
}

/// Whether the `r` at `i` opens a raw string (not the end of an identifier).
fn is_raw_start(bytes: &[u8], i: usize) -> bool {
    let before_ok = i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
    let mut j = i + 1;
    while bytes.get(j) == Some(&b'#') {
        j += 1;
    }
    before_ok && bytes.get(j) == Some(&b'"')
}

fn utf8_len(first: u8) -> usize {
    match first {
        0x00..=0x7f => 1,
        0xc0..=0xdf => 2,
        0xe0..=0xef => 3,
        _ => 4,
    }
}

/// `code` without the items under `#[cfg(test)]` (a `mod tests { … }` block or a
/// `mod name;` declaration), and the names of test-only modules it declares.
fn strip_test_code(code: &str) -> (String, Vec<String>) {
    let mut out = String::new();
    let mut test_modules = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..at]);
        let after = &rest[at + "#[cfg(test)]".len()..];
        // The item ends at the first `;` before any `{`, or at the `}` closing the
        // first `{`.
        let semi = after.find(';');
        let brace = after.find('{');
        let end = match (semi, brace) {
            (Some(s), Some(b)) if s < b => s + 1,
            (Some(s), None) => s + 1,
            (_, Some(b)) => {
                let mut depth = 0;
                let mut end = after.len();
                for (k, ch) in after[b..].char_indices() {
                    match ch {
                        '{' => depth += 1,
                        '}' => {
                            depth -= 1;
                            if depth == 0 {
                                end = b + k + 1;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                end
            }
            (None, None) => after.len(),
        };
        let item = &after[..end];
        let words: Vec<&str> = item
            .split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .filter(|w| !w.is_empty())
            .collect();
        if let Some(k) = words.iter().position(|w| *w == "mod")
            && item.trim_end().ends_with(';')
        {
            test_modules.push(words[k + 1].to_string());
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    (out, test_modules)
}

/// The paths of every `use` tree in `code`, braces expanded, with the rest of the
/// code (outside `use` items) returned apart.
fn use_paths(code: &str) -> (Vec<Vec<String>>, String) {
    let mut paths = Vec::new();
    let mut rest = String::new();
    let mut tail = code;
    loop {
        let Some(at) = find_use(tail) else {
            rest.push_str(tail);
            break;
        };
        rest.push_str(&tail[..at]);
        let after = &tail[at + 3..];
        let end = after.find(';').unwrap_or(after.len());
        // Renames (`x as y`) dropped, then the whitespace.
        let mut words = after[..end].split_whitespace();
        let mut tree = String::new();
        while let Some(word) = words.next() {
            if word == "as" {
                let renamed = words.next().unwrap_or("");
                // Keep what follows the new name (`y,` or `y}`).
                tree.extend(
                    renamed
                        .chars()
                        .skip_while(|c| c.is_alphanumeric() || *c == '_'),
                );
            } else {
                tree.push_str(word);
            }
        }
        expand(&tree, &mut Vec::new(), &mut paths);
        tail = &after[(end + 1).min(after.len())..];
    }
    (paths, rest)
}

/// The byte offset of the next `use` keyword that starts an item.
fn find_use(code: &str) -> Option<usize> {
    let bytes = code.as_bytes();
    let mut from = 0;
    while let Some(k) = code[from..].find("use ") {
        let at = from + k;
        let before = if at == 0 { b' ' } else { bytes[at - 1] };
        if !(before.is_ascii_alphanumeric() || before == b'_') {
            return Some(at);
        }
        from = at + 4;
    }
    None
}

/// Expands one use tree (`a::{b, c::{d, e}}`) onto `prefix`.
fn expand(tree: &str, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    let tree = tree.trim_start_matches("::");
    if let Some(open) = tree.find('{') {
        let head = &tree[..open];
        let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
        let pushed: Vec<String> = head
            .split("::")
            .filter(|s| !s.is_empty())
            .map(str::to_string)
            .collect();
        let n = pushed.len();
        prefix.extend(pushed);
        for branch in split_top(inner) {
            expand(branch, prefix, out);
        }
        prefix.truncate(prefix.len() - n);
    } else {
        let mut path = prefix.clone();
        path.extend(
            tree.split("::")
                .filter(|s| !s.is_empty() && *s != "*" && *s != "self")
                .map(str::to_string),
        );
        if !path.is_empty() {
            out.push(path);
        }
    }
}

/// `a, b::{c, d}, e` split at top-level commas.
fn split_top(text: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (k, ch) in text.char_indices() {
        match ch {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&text[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    parts.push(&text[start..]);
    parts.into_iter().filter(|p| !p.is_empty()).collect()
}

/// The `crate::…`, `super::…`, `self::…` (and, in the binary, `vesselcad::…`)
/// paths written in code outside `use`.
fn inline_paths(code: &str) -> Vec<Vec<String>> {
    let bytes = code.as_bytes();
    let mut out = Vec::new();
    for start in ["crate::", "super::", "self::", "vesselcad::"] {
        let mut from = 0;
        while let Some(k) = code[from..].find(start) {
            let at = from + k;
            from = at + start.len();
            if at > 0
                && (bytes[at - 1].is_ascii_alphanumeric()
                    || bytes[at - 1] == b'_'
                    || bytes[at - 1] == b':')
            {
                continue;
            }
            let mut end = at;
            while end < bytes.len()
                && (bytes[end].is_ascii_alphanumeric() || bytes[end] == b'_' || bytes[end] == b':')
            {
                end += 1;
            }
            out.push(
                code[at..end]
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(str::to_string)
                    .collect(),
            );
        }
    }
    out
}

/// Resolves a path named in the module `module` to an absolute module path, or
/// `None` for paths outside the crate. In the binary (`binary`), `crate::x` is
/// `cli::x` and `vesselcad::x` is the library's `x`.
fn resolve(
    path: &[String],
    module: &ModPath,
    is_dir: bool,
    children: &BTreeSet<String>,
    binary: bool,
) -> Option<ModPath> {
    let first = path.first()?;
    let joined = |mut base: ModPath, rest: &[String]| {
        base.extend(rest.iter().cloned());
        Some(base)
    };
    match first.as_str() {
        "crate" if binary => {
            let rest = if path.get(1).is_some_and(|s| s == BINARY) {
                &path[2..]
            } else {
                &path[1..]
            };
            joined(vec![BINARY.to_string()], rest)
        }
        "crate" => joined(vec![], &path[1..]),
        "vesselcad" if binary => joined(vec![], &path[1..]),
        "self" => joined(module.clone(), &path[1..]),
        "super" => {
            let mut base = module.clone();
            let mut rest = path;
            while rest.first().is_some_and(|s| s == "super") {
                if !(binary && base.len() == 1) {
                    base.pop();
                }
                rest = &rest[1..];
            }
            joined(base, rest)
        }
        name if is_dir && children.contains(name) => joined(module.clone(), path),
        _ => None,
    }
}

/// Every module of the crate and the binary.
fn sources() -> Vec<Source> {
    let root = root();
    let mut files = Vec::new();
    for dir in ["src", "components", "systems"] {
        rust_files(&root.join(dir), &mut files);
    }
    let mut test_only: BTreeSet<ModPath> = BTreeSet::new();
    let mut out = Vec::new();
    for file in files {
        let relative = file.strip_prefix(&root).unwrap().to_path_buf();
        let (module, is_dir) = module_of(&relative);
        let text = fs::read_to_string(&file).unwrap();
        let (code, tests) = strip_test_code(&strip_comments(&text));
        if is_dir {
            for t in tests {
                let mut m = module.clone();
                m.push(t);
                test_only.insert(m);
            }
        }
        out.push(Source {
            module,
            is_dir,
            code,
        });
    }
    out.retain(|s| !test_only.iter().any(|t| s.module.starts_with(t)));
    out
}

/// The children of `module` among `modules`.
fn children_of(modules: &BTreeSet<ModPath>, module: &ModPath) -> BTreeSet<String> {
    modules
        .iter()
        .filter(|m| m.len() == module.len() + 1 && m.starts_with(module))
        .map(|m| m.last().unwrap().clone())
        .collect()
}

/// The names each directory module imports from below it (`use error::CdtError`
/// in `mesh::cdt` maps `CdtError` to `mesh::cdt::error`): a child that names
/// `super::CdtError` uses `mesh::cdt::error`. Only imports that resolve to a
/// module under the directory module count.
fn reexports(
    sources: &[Source],
    modules: &BTreeSet<ModPath>,
) -> BTreeMap<ModPath, BTreeMap<String, ModPath>> {
    let mut out: BTreeMap<ModPath, BTreeMap<String, ModPath>> = BTreeMap::new();
    for source in sources.iter().filter(|s| s.is_dir) {
        let binary = source.module.first().is_some_and(|m| m == BINARY);
        let children = children_of(modules, &source.module);
        for path in use_paths(&source.code).0 {
            let Some(target) = resolve(&path, &source.module, true, &children, binary) else {
                continue;
            };
            // `use child::Item` or `use child::grandchild`: the module that holds
            // the name, or the module named.
            let (Some(name), Some(module)) = (target.last(), deepest(modules, &target)) else {
                continue;
            };
            if module.len() + 1 >= target.len()
                && module.len() > source.module.len()
                && module.starts_with(&source.module)
            {
                out.entry(source.module.clone())
                    .or_default()
                    .insert(name.clone(), module);
            }
        }
    }
    out
}

/// The deepest module of `modules` that `path` names (a prefix of it).
fn deepest(modules: &BTreeSet<ModPath>, path: &[String]) -> Option<ModPath> {
    (1..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|m| modules.contains(m))
}

/// Edges `(parent, from, to)`: the module `parent::from` names `parent::to`.
/// With `follow`, a name a directory module imports from below it counts as the
/// module that defines it (see [`reexports`]).
fn edges(follow: bool) -> BTreeSet<(String, String, String)> {
    let sources = sources();
    let modules: BTreeSet<ModPath> = sources.iter().map(|s| s.module.clone()).collect();
    let imported = if follow {
        reexports(&sources, &modules)
    } else {
        BTreeMap::new()
    };
    let mut edges = BTreeSet::new();
    for source in &sources {
        let binary = source.module.first().is_some_and(|m| m == BINARY);
        let children = children_of(&modules, &source.module);
        let (mut paths, rest) = use_paths(&source.code);
        paths.extend(inline_paths(&rest));
        for path in paths {
            let Some(target) = resolve(&path, &source.module, source.is_dir, &children, binary)
            else {
                continue;
            };
            // The deepest module the path names, through imports when followed.
            let Some(mut module) = deepest(&modules, &target) else {
                continue;
            };
            if let Some(inner) = target
                .get(module.len())
                .and_then(|name| imported.get(&module)?.get(name))
            {
                module = inner.clone();
            }
            let target = module;
            let common = source
                .module
                .iter()
                .zip(&target)
                .take_while(|(a, b)| a == b)
                .count();
            if common < source.module.len() && common < target.len() {
                edges.insert((
                    source.module[..common].join("::"),
                    source.module[common].clone(),
                    target[common].clone(),
                ));
            }
        }
    }
    edges
}

#[test]
fn no_two_modules_name_each_other() {
    let edges = edges(false);
    let mut cycles = Vec::new();
    for (parent, a, b) in &edges {
        if a < b && edges.contains(&(parent.clone(), b.clone(), a.clone())) {
            cycles.push((parent.clone(), a.clone(), b.clone()));
        }
    }
    let allowed: BTreeSet<(String, String, String)> = ALLOWED
        .iter()
        .map(|(p, a, b)| (p.to_string(), a.to_string(), b.to_string()))
        .collect();
    let unexpected: Vec<_> = cycles.iter().filter(|c| !allowed.contains(c)).collect();
    assert!(
        unexpected.is_empty(),
        "two-module cycles (parent: a <-> b):\n{}",
        unexpected
            .iter()
            .map(|(p, a, b)| format!("  {}: {a} <-> {b}", if p.is_empty() { "crate" } else { p }))
            .collect::<Vec<_>>()
            .join("\n")
    );
    let found: BTreeSet<_> = cycles.iter().cloned().collect();
    let stale: Vec<_> = allowed.difference(&found).collect();
    assert!(
        stale.is_empty(),
        "allowed cycles that no longer exist: {stale:?}"
    );
}

/// The top-level graph the test reads, printed by `cargo test --test module_graph
/// -- --nocapture print`: the source of ARCHITECTURE.md's module list.
#[test]
fn print_top_level_graph() {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (parent, a, b) in edges(false) {
        if parent.is_empty() {
            graph.entry(a).or_default().insert(b);
        }
    }
    for (module, uses) in &graph {
        println!(
            "{module:<12} → {}",
            uses.iter().cloned().collect::<Vec<_>>().join(", ")
        );
    }
    assert!(graph.contains_key("model"), "the graph was read: {graph:?}");
}

/// The modules under which no cycle of any length is allowed (each parent
/// whose path starts with one of these).
const ACYCLIC: &[&str] = &["mesh"];

/// A cycle in `graph`, as its modules in order, or `None` (a depth-first search;
/// a node on the stack reached again closes a cycle).
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        Open,
        Done,
    }
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        marks: &mut BTreeMap<String, Mark>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        marks.insert(node.to_string(), Mark::Open);
        stack.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            match marks.get(next) {
                Some(Mark::Open) => {
                    let from = stack.iter().position(|m| m == next).unwrap();
                    return Some(stack[from..].to_vec());
                }
                Some(Mark::Done) => {}
                None => {
                    if let Some(cycle) = visit(next, graph, marks, stack) {
                        return Some(cycle);
                    }
                }
            }
        }
        stack.pop();
        marks.insert(node.to_string(), Mark::Done);
        None
    }
    let mut marks = BTreeMap::new();
    for node in graph.keys() {
        if !marks.contains_key(node)
            && let Some(cycle) = visit(node, graph, &mut marks, &mut Vec::new())
        {
            return Some(cycle);
        }
    }
    None
}

/// The cycles among sibling modules under the [`ACYCLIC`] parents, one per
/// parent that has any, as `parent: a -> b -> … -> a`.
fn cycles_under_acyclic_parents(edges: &BTreeSet<(String, String, String)>) -> Vec<String> {
    let mut graphs: BTreeMap<&str, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for (parent, a, b) in edges {
        if ACYCLIC
            .iter()
            .any(|p| parent == p || parent.starts_with(&format!("{p}::")))
        {
            graphs
                .entry(parent)
                .or_default()
                .entry(a.clone())
                .or_default()
                .insert(b.clone());
        }
    }
    graphs
        .iter()
        .filter_map(|(parent, graph)| {
            let mut cycle = find_cycle(graph)?;
            cycle.push(cycle[0].clone());
            Some(format!("{parent}: {}", cycle.join(" -> ")))
        })
        .collect()
}

#[test]
fn no_cycles_inside_the_mesher() {
    let edges = edges(true);
    assert!(
        edges
            .iter()
            .any(|(p, a, b)| p == "mesh::cdt" && a == "mesher" && b == "error"),
        "the mesher's graph was read, its re-exports followed"
    );
    let cycles = cycles_under_acyclic_parents(&edges);
    assert!(
        cycles.is_empty(),
        "module cycles inside the mesher:\n  {}",
        cycles.join("\n  ")
    );
}

/// The cycle search finds a three-module cycle and passes a chain.
#[test]
fn the_cycle_search_finds_a_three_module_cycle() {
    let edge = |p: &str, a: &str, b: &str| (p.to_string(), a.to_string(), b.to_string());
    let mut edges: BTreeSet<_> = [
        edge("mesh::cdt", "structured", "plan"),
        edge("mesh::cdt", "plan", "sector"),
        edge("mesh::cdt", "sector", "patch"),
        edge("crate", "a", "b"),
        edge("crate", "b", "a"),
    ]
    .into_iter()
    .collect();
    assert!(cycles_under_acyclic_parents(&edges).is_empty());
    edges.insert(edge("mesh::cdt", "sector", "structured"));
    assert_eq!(
        cycles_under_acyclic_parents(&edges),
        ["mesh::cdt: plan -> sector -> structured -> plan"]
    );
}

/// Every ECS component and resource is declared in `components/`: no
/// `#[derive(Component)]`, `#[derive(Resource)]` or hand-written impl of either
/// elsewhere in the library's code.
#[test]
fn components_and_resources_live_in_components() {
    let root = root();
    let mut files = Vec::new();
    for dir in ["src", "systems"] {
        rust_files(&root.join(dir), &mut files);
    }
    let mut found = Vec::new();
    for file in files {
        let code = strip_test_code(&strip_comments(&fs::read_to_string(&file).unwrap())).0;
        for line in code.lines() {
            let derives = line.trim_start().starts_with("#[derive(")
                && line
                    .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .any(|w| w == "Component" || w == "Resource");
            let implements =
                line.contains("impl Component for") || line.contains("impl Resource for");
            if derives || implements {
                found.push(format!(
                    "{}: {}",
                    file.strip_prefix(&root).unwrap().display(),
                    line.trim()
                ));
            }
        }
    }
    assert!(
        found.is_empty(),
        "outside components/:\n{}",
        found.join("\n")
    );
}
