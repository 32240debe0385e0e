//! The layers of `docs/architecture.md`, checked on the source: no file imports from a layer
//! above its own, and no two files import each other, directly or round a longer loop.
//!
//! An import is any `crate::…` or `super::…` path in a file's code (comments left out). A path
//! that names a module file is an edge to that file; one that names an item is an edge to
//! the file of the module it is named through.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, lowest first, and what each may import: the table in `docs/architecture.md`.
const LAYERS: [(&str, &[&str]); 9] = [
    ("error", &[]),
    ("model", &["error"]),
    ("methods", &["error", "model"]),
    ("run", &["error", "model", "methods"]),
    ("plan", &["error", "model", "methods", "run"]),
    ("recording", &["error", "model", "run"]),
    ("study", &["error", "model", "methods", "run", "plan"]),
    (
        "cli",
        &[
            "error",
            "model",
            "methods",
            "run",
            "plan",
            "recording",
            "study",
        ],
    ),
    (
        "service",
        &[
            "error",
            "model",
            "methods",
            "run",
            "plan",
            "recording",
            "study",
            "cli",
        ],
    ),
];

/// Every `.rs` file of the library under `src/`, as its module path (`["methods", "seed"]`),
/// with its code (comment lines, `//` tails and `#[cfg(test)]` modules dropped). `main.rs` is
/// the binary, above all.
fn library_files() -> BTreeMap<Vec<String>, String> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("src/ is readable") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut paths = Vec::new();
    walk(&src, &mut paths);
    paths
        .into_iter()
        .filter(|p| !p.ends_with("main.rs") && !p.ends_with("lib.rs"))
        .map(|p| {
            let relative = p.strip_prefix(&src).unwrap().with_extension("");
            let mut module: Vec<String> = relative
                .iter()
                .map(|c| c.to_string_lossy().into_owned())
                .collect();
            if module.last().is_some_and(|m| m == "mod") {
                module.pop();
            }
            let text = std::fs::read_to_string(&p).unwrap();
            // A file's own tests may reach anywhere; what counts is the code they test.
            let text = text.split("#[cfg(test)]").next().unwrap_or("");
            let code: String = text
                .lines()
                .map(|line| line.split("//").next().unwrap_or(""))
                .collect::<Vec<_>>()
                .join("\n");
            (module, code)
        })
        .collect()
}

/// The module paths a file's code names, resolved against `module` (for `super::`), each
/// cut to the longest prefix that is a file of the library.
fn imports(
    module: &[String],
    code: &str,
    files: &BTreeMap<Vec<String>, String>,
) -> BTreeSet<Vec<String>> {
    let is_dir_module = |m: &[String]| files.keys().any(|k| k.len() > m.len() && k.starts_with(m));
    let mut found = BTreeSet::new();
    let bytes = code.as_bytes();
    for (start, keyword) in code
        .match_indices("crate::")
        .chain(code.match_indices("super::"))
    {
        let before = start.checked_sub(1).map(|i| bytes[i] as char);
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
            continue; // `rerun::…::crate::` or a `super::super::` tail
        }
        let rest = &code[start + keyword.len()..];
        let segments: Vec<String> = rest
            .split("::")
            .map(|s| {
                s.chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect::<String>()
            })
            .take_while(|s| !s.is_empty())
            .collect();
        // `super` of a file is its parent module, of a folder's mod.rs its grandparent.
        let path: Vec<String> = if keyword == "crate::" {
            Vec::new()
        } else if is_dir_module(module) {
            module[..module.len().saturating_sub(1)].to_vec()
        } else {
            module[..module.len() - 1].to_vec()
        };
        // `use super::{a, b}` names siblings through the parent; take each name.
        let braced = rest.starts_with('{');
        let names: Vec<Vec<String>> = if braced {
            let inner = &rest[1..rest.find('}').unwrap_or(rest.len())];
            inner
                .split(',')
                .map(|name| {
                    name.trim()
                        .split("::")
                        .next()
                        .unwrap_or("")
                        .trim()
                        .to_owned()
                })
                .filter(|n| !n.is_empty() && n != "self")
                .map(|n| vec![n])
                .collect()
        } else {
            vec![segments]
        };
        for name in names {
            let mut full = path.clone();
            full.extend(name);
            while !full.is_empty() && !files.contains_key(&full) {
                full.pop();
            }
            if !full.is_empty() && full != module {
                found.insert(full);
            }
        }
    }
    // A folder's mod.rs names its own files bare (`grid::Row`, `pub use grid::…`).
    if is_dir_module(module) {
        for child in files
            .keys()
            .filter(|k| k.len() == module.len() + 1 && k.starts_with(module))
        {
            let name = format!("{}::", child[module.len()]);
            let named = code.match_indices(&name).any(|(at, _)| {
                let before = at.checked_sub(1).map(|i| bytes[i] as char);
                !before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':')
            });
            if named {
                found.insert(child.clone());
            }
        }
    }
    found
}

fn layer_of(module: &[String]) -> &str {
    module.first().map(String::as_str).unwrap_or("")
}

#[test]
fn no_file_imports_from_a_layer_above_its_own() {
    let files = library_files();
    let mut wrong = Vec::new();
    for (module, code) in &files {
        let layer = layer_of(module);
        let (_, allowed) = LAYERS
            .iter()
            .find(|(name, _)| *name == layer)
            .unwrap_or_else(|| panic!("{module:?} is in no layer of docs/architecture.md"));
        for import in imports(module, code, &files) {
            let target = layer_of(&import);
            if target != layer && !allowed.contains(&target) {
                wrong.push(format!(
                    "{} imports {}",
                    module.join("::"),
                    import.join("::")
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "upward imports:\n{}", wrong.join("\n"));
}

#[test]
fn no_two_files_import_each_other_even_round_a_loop() {
    let files = library_files();
    let graph: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = files
        .iter()
        .map(|(module, code)| (module.clone(), imports(module, code, &files)))
        .collect();
    // Depth-first search for a back edge; the cycle is reported as the path that closes it.
    fn visit(
        node: &Vec<String>,
        graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        done: &mut BTreeSet<Vec<String>>,
        stack: &mut Vec<Vec<String>>,
    ) -> Option<Vec<Vec<String>>> {
        if let Some(at) = stack.iter().position(|n| n == node) {
            let mut cycle = stack[at..].to_vec();
            cycle.push(node.clone());
            return Some(cycle);
        }
        if done.contains(node) {
            return None;
        }
        stack.push(node.clone());
        for next in graph.get(node).into_iter().flatten() {
            if let Some(cycle) = visit(next, graph, done, stack) {
                return Some(cycle);
            }
        }
        stack.pop();
        done.insert(node.clone());
        None
    }
    let mut done = BTreeSet::new();
    for node in graph.keys() {
        if let Some(cycle) = visit(node, &graph, &mut done, &mut Vec::new()) {
            let names: Vec<String> = cycle.iter().map(|m| m.join("::")).collect();
            panic!("import cycle: {}", names.join(" → "));
        }
    }
}

#[test]
fn the_checker_sees_an_upward_import_and_a_cycle() {
    // A file of the model that imports the run layer, and two siblings importing each other.
    let mut files = BTreeMap::new();
    let m = |s: &str| s.split("::").map(str::to_owned).collect::<Vec<_>>();
    files.insert(m("model::a"), "use crate::run::simulate::Frame;".to_owned());
    files.insert(m("run::simulate"), "use super::b::X;".to_owned());
    files.insert(m("run::b"), "use super::simulate;".to_owned());
    files.insert(m("run"), "pub use b::X;".to_owned());
    assert!(imports(&m("model::a"), &files[&m("model::a")], &files).contains(&m("run::simulate")));
    assert!(
        imports(&m("run::simulate"), &files[&m("run::simulate")], &files).contains(&m("run::b"))
    );
    assert!(imports(&m("run::b"), &files[&m("run::b")], &files).contains(&m("run::simulate")));
    assert!(imports(&m("run"), &files[&m("run")], &files).contains(&m("run::b")));
}

/// The binary only parses, dispatches, prints the final error and maps the outcome to an
/// exit code: everything else lives in the library, where tests call it.
#[test]
fn main_is_thin() {
    let main = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/main.rs"))
        .expect("src/main.rs is readable");
    let lines = main.lines().count();
    assert!(
        lines < 80,
        "src/main.rs has {lines} lines; its work belongs in src/service/"
    );
}

/// No file of the library is longer than one sitting's reading, but for the ones named
/// here with why one concept needs more.
#[test]
fn no_file_is_longer_than_a_sitting() {
    const LONGER: &[(&str, &str)] = &[
        (
            "src/recording/logger.rs",
            "the one Rerun sink: when each entity a frame becomes is sent, in full or as a live picture and a history (how each is drawn: shapes.rs, styling.rs, lane_log.rs)",
        ),
        (
            "src/study/charts.rs",
            "the study's figures, one small function each, over the drawing helpers they share",
        ),
        (
            "src/methods/midpoint.rs",
            "one method: its Newton on (Δθ, μ), the projection and the steps that follow the motion",
        ),
    ];
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut long = Vec::new();
    for module in library_files().keys() {
        let mut path = root.join("src");
        for part in module {
            path.push(part);
        }
        let file = if path.is_dir() {
            path.join("mod.rs")
        } else {
            path.with_extension("rs")
        };
        let lines = std::fs::read_to_string(&file)
            .unwrap_or_else(|err| panic!("{}: {err}", file.display()))
            .lines()
            .count();
        let name = file
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if lines > 600 && !LONGER.iter().any(|(n, _)| *n == name) {
            long.push(format!("{name}: {lines} lines"));
        }
    }
    assert!(long.is_empty(), "files past 600 lines: {long:?}");
}
