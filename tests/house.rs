//! The order of the source, checked: the top-level modules of the core and of the scene crate
//! import each other in one direction only (no cycle), no core file passes 900 lines and no
//! core function 120 (in-file tests aside; the narrowphase kernels, which read as the
//! algorithm's cases, excepted), and `docs/architecture.md` names every source file of the
//! core and the layer each top-level module stands on. Each checker is also run on a small made-up crate, to show it catches what it looks
//! for.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest a core file may be, in lines, in-file tests left out.
const FILE_LINES: usize = 900;
/// The longest a core function may be, in lines.
const FUNCTION_LINES: usize = 120;
/// The functions allowed past [`FUNCTION_LINES`], as `file:function`: the narrowphase kernels,
/// one case after another as Box2D writes them, where a split would hide the algorithm.
const LONG_KERNELS: &[&str] = &[
    "geometry/query/manifold.rs:collide_polygons",
    "geometry/query/chain_segment.rs:collide_polygon",
];

/// A source file: its path below `src/`, with `/` between folders, and its text.
struct Source {
    path: String,
    text: String,
}

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the tests package sits in the workspace")
        .to_path_buf()
}

/// Every `.rs` file under `src`, in path order.
fn sources(src: &Path) -> Vec<Source> {
    fn walk(dir: &Path, src: &Path, out: &mut Vec<Source>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
            .map(|entry| entry.expect("a directory entry").path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                walk(&path, src, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path.strip_prefix(src).expect("below src");
                let parts: Vec<_> = relative
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                out.push(Source {
                    path: parts.join("/"),
                    text: std::fs::read_to_string(&path)
                        .unwrap_or_else(|e| panic!("reading {}: {e}", path.display())),
                });
            }
        }
    }
    let mut out = Vec::new();
    walk(src, src, &mut out);
    out
}

/// Whether the file holds only tests (a `tests.rs`, or a name ending in `_tests.rs`).
fn is_test_file(path: &str) -> bool {
    let name = path.rsplit('/').next().unwrap_or(path);
    name == "tests.rs" || name.ends_with("_tests.rs")
}

/// The text before the file's in-file tests (`#[cfg(test)]` followed by `mod tests`).
fn without_tests(text: &str) -> &str {
    let mut from = 0;
    while let Some(at) = text[from..].find("#[cfg(test)]") {
        let start = from + at;
        let after = text[start + "#[cfg(test)]".len()..].trim_start();
        if after.starts_with("mod tests") && (start == 0 || text[..start].ends_with('\n')) {
            return &text[..start];
        }
        from = start + 1;
    }
    text
}

/// The crate's top-level module a file belongs to (`None` for `lib.rs` and `main.rs`).
fn top_module(path: &str) -> Option<&str> {
    match path.split_once('/') {
        Some((folder, _)) => Some(folder),
        None if path == "lib.rs" || path == "main.rs" => None,
        None => path.strip_suffix(".rs"),
    }
}

/// The top-level modules each top-level module names through `crate::`.
fn module_graph(files: &[Source]) -> BTreeMap<String, BTreeSet<String>> {
    let modules: BTreeSet<&str> = files.iter().filter_map(|f| top_module(&f.path)).collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = modules
        .iter()
        .map(|m| (m.to_string(), BTreeSet::new()))
        .collect();
    for file in files.iter().filter(|f| !is_test_file(&f.path)) {
        let Some(from) = top_module(&file.path) else {
            continue;
        };
        let code = without_tests(&file.text);
        for (at, _) in code.match_indices("crate::") {
            let rest = &code[at + "crate::".len()..];
            // `crate::{a, b::c}` names each of its top-level items.
            let names: Vec<&str> = match rest.strip_prefix('{') {
                Some(group) => {
                    let group = &group[..group.find('}').unwrap_or(group.len())];
                    group.split(',').map(str::trim).collect()
                }
                None => vec![rest],
            };
            for name in names {
                let end = name
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(name.len());
                let target = &name[..end];
                if target != from && modules.contains(target) {
                    graph
                        .get_mut(from)
                        .expect("every module is a key")
                        .insert(target.to_string());
                }
            }
        }
    }
    graph
}

/// The groups of more than one module that reach each other (Tarjan's strongly connected
/// components), each sorted.
fn cycles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct Search<'a> {
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        found: Vec<Vec<String>>,
    }
    impl<'a> Search<'a> {
        fn visit(&mut self, v: &'a str) {
            let n = self.index.len();
            self.index.insert(v, n);
            self.low.insert(v, n);
            self.stack.push(v);
            self.on_stack.insert(v);
            for w in &self.graph[v] {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut group = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    group.push(w.to_string());
                    if w == v {
                        break;
                    }
                }
                if group.len() > 1 {
                    group.sort();
                    self.found.push(group);
                }
            }
        }
    }
    let mut search = Search {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for v in graph.keys() {
        if !search.index.contains_key(v.as_str()) {
            search.visit(v);
        }
    }
    search.found
}

/// Each cycle, with the files that make its edges, for the failure message.
fn describe_cycles(files: &[Source]) -> Vec<String> {
    let graph = module_graph(files);
    cycles(&graph)
        .into_iter()
        .map(|group| {
            let edges: Vec<String> = group
                .iter()
                .flat_map(|a| {
                    graph[a]
                        .iter()
                        .filter(|b| group.contains(b))
                        .map(move |b| format!("{a} -> {b}"))
                })
                .collect();
            format!("{} ({})", group.join(", "), edges.join("; "))
        })
        .collect()
}

/// The layers of the map's "core's layers" table: each module's layer.
fn layers(map: &str) -> BTreeMap<String, usize> {
    let table = map
        .split("## The core's layers")
        .nth(1)
        .and_then(|rest| rest.split("\n## ").next())
        .unwrap_or("");
    let mut layers = BTreeMap::new();
    for row in table.lines().filter(|l| l.starts_with("| ")) {
        let cells: Vec<&str> = row.split(" | ").collect();
        let Ok(layer) = cells[0].trim_start_matches("| ").parse::<usize>() else {
            continue;
        };
        for (i, name) in cells.get(1).unwrap_or(&"").split('`').enumerate() {
            if i % 2 == 1 {
                layers.insert(name.to_string(), layer);
            }
        }
    }
    layers
}

/// What is wrong with `layers` for `graph`: a module with no layer or on two, one named that
/// does not exist, or an import that points up a layer.
fn layer_faults(
    graph: &BTreeMap<String, BTreeSet<String>>,
    layers: &BTreeMap<String, usize>,
) -> Vec<String> {
    let mut faults: Vec<String> = graph
        .keys()
        .filter(|m| !layers.contains_key(*m))
        .map(|m| format!("{m} is on no layer"))
        .collect();
    faults.extend(
        layers
            .keys()
            .filter(|m| !graph.contains_key(*m))
            .map(|m| format!("{m} is on a layer but is not a module")),
    );
    for (from, targets) in graph {
        for to in targets {
            if let (Some(a), Some(b)) = (layers.get(from), layers.get(to))
                && b > a
            {
                faults.push(format!("{from} (layer {a}) uses {to} (layer {b})"));
            }
        }
    }
    faults
}

/// The line's code with its comment, string contents and character literals left out, so that
/// only the braces of the code are counted.
fn code_of(line: &str) -> String {
    let mut out = String::new();
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => break,
            '"' => {
                while let Some(d) = chars.next() {
                    match d {
                        '\\' => {
                            chars.next();
                        }
                        '"' => break,
                        _ => {}
                    }
                }
            }
            // A character literal ('{', '\n'); a lifetime ('a) has no closing quote nearby.
            '\'' => {
                let ahead: String = chars.clone().take(3).collect();
                if let Some(escaped) = ahead.strip_prefix('\\') {
                    let close = escaped.find('\'').map_or(0, |i| i + 2);
                    for _ in 0..close {
                        chars.next();
                    }
                } else if ahead.chars().nth(1) == Some('\'') {
                    chars.next();
                    chars.next();
                }
            }
            _ => out.push(c),
        }
    }
    out
}

/// Every function with a body longer than `limit` lines, as (`file:function`, lines).
fn long_functions(files: &[Source], limit: usize) -> Vec<(String, usize)> {
    let mut long = Vec::new();
    for file in files.iter().filter(|f| !is_test_file(&f.path)) {
        let lines: Vec<String> = without_tests(&file.text).lines().map(code_of).collect();
        for (start, line) in lines.iter().enumerate() {
            let Some(name) = function_name(line) else {
                continue;
            };
            // The body runs from the first `{` to the brace that closes it; a `;` first means
            // a declaration without one.
            let mut depth = 0usize;
            let mut opened = false;
            let mut end = None;
            'lines: for (i, line) in lines.iter().enumerate().skip(start) {
                for c in line.chars() {
                    match c {
                        '{' => {
                            depth += 1;
                            opened = true;
                        }
                        '}' => depth = depth.saturating_sub(1),
                        ';' if !opened => break 'lines,
                        _ => {}
                    }
                    if opened && depth == 0 {
                        end = Some(i);
                        break 'lines;
                    }
                }
            }
            if let Some(end) = end {
                let length = end - start + 1;
                if length > limit {
                    long.push((format!("{}:{name}", file.path), length));
                }
            }
        }
    }
    long
}

/// The function a line declares, if it starts one.
fn function_name(line: &str) -> Option<&str> {
    let mut words = line.split_whitespace().peekable();
    while let Some(word) = words.next() {
        let qualifier = word.starts_with("pub")
            || matches!(word, "const" | "unsafe" | "async" | "extern" | "\"C\"");
        if word == "fn" {
            let name = words.next()?;
            let end = name
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(name.len());
            return Some(&name[..end]);
        }
        if !qualifier {
            return None;
        }
    }
    None
}

/// Every file longer than `limit` lines, in-file tests left out, as (path, lines).
fn long_files(files: &[Source], limit: usize) -> Vec<(String, usize)> {
    files
        .iter()
        .filter(|f| !is_test_file(&f.path))
        .map(|f| (f.path.clone(), without_tests(&f.text).lines().count()))
        .filter(|&(_, lines)| lines > limit)
        .collect()
}

/// The source files (below `prefix`, which ends in `src/`) that the map's table does not name.
///
/// A row names the paths in backticks at the start of its first cell: the first in full, any
/// after it beside the first (`crates/carom/src/math.rs`, `error.rs`). A file is named by its
/// row, or by the row of the deepest folder holding it, when that row's text names the file
/// and every folder between (`shape/` and `saved.rs` in the row of `geometry/`); a folder's
/// `mod.rs` is named by its folder.
fn unmapped(map: &str, prefix: &str, files: &[&str]) -> Vec<String> {
    let mut rows: Vec<(Vec<String>, &str)> = Vec::new();
    for line in map.lines().filter(|l| l.starts_with("| `")) {
        let first_cell = line[1..].split(" | ").next().unwrap_or("");
        let mut paths: Vec<String> = Vec::new();
        for (i, piece) in first_cell.split('`').enumerate() {
            if i % 2 == 0 {
                continue;
            }
            match paths.first() {
                None => paths.push(piece.to_string()),
                Some(first) if !piece.contains('/') || piece.ends_with('/') => {
                    let folder = &first[..first.rfind('/').map_or(0, |i| i + 1)];
                    paths.push(format!("{folder}{piece}"));
                }
                Some(_) => paths.push(piece.to_string()),
            }
        }
        rows.push((paths, line));
    }
    let mut missing = Vec::new();
    for file in files {
        let full = format!("{prefix}{file}");
        // A folder's row (`crates/carom/src/geometry/`), or a package's (`crates/carom-scene`),
        // which stands for its `src/`: how deep the folder is and the file's path below it.
        let folder_of = |path: &str| {
            let folder = match path {
                _ if path.ends_with('/') => path.to_string(),
                _ if path.ends_with(".rs") => return None,
                _ => format!("{path}/src/"),
            };
            let rest = full.strip_prefix(folder.as_str())?;
            Some((folder.len(), rest.to_string()))
        };
        if rows.iter().any(|(paths, _)| paths.contains(&full)) {
            continue;
        }
        // The deepest folder row holding the file, and the rest of its path below it.
        let best = rows
            .iter()
            .flat_map(|(paths, text)| {
                paths
                    .iter()
                    .filter_map(move |p| folder_of(p).map(|(depth, rest)| (depth, rest, *text)))
            })
            .max_by_key(|&(depth, _, _)| depth);
        let named = best.is_some_and(|(_, rest, text)| {
            let parts: Vec<&str> = rest.split('/').collect();
            let (name, folders) = parts.split_last().expect("a file name");
            let folders_named = folders.iter().all(|f| text.contains(&format!("`{f}/")));
            let name_named = *name == "mod.rs" || text.contains(&format!("`{name}`"));
            // A file that is its folder's only concern may be named as `folder/file.rs`.
            let joined = text.contains(&format!("`{rest}`"));
            (folders_named && name_named) || joined
        });
        if !named {
            missing.push(file.to_string());
        }
    }
    missing
}

#[test]
fn the_core_and_the_scene_crate_have_no_module_cycle() {
    for krate in ["crates/carom/src", "crates/carom-scene/src"] {
        let files = sources(&workspace().join(krate));
        assert!(
            files.len() > 5,
            "{krate}: too few files found ({})",
            files.len()
        );
        let found = describe_cycles(&files);
        assert!(
            found.is_empty(),
            "{krate}: top-level modules import each other in a circle: {found:#?}"
        );
    }
}

#[test]
fn no_core_file_or_function_is_too_long() {
    let files = sources(&workspace().join("crates/carom/src"));
    let files_long = long_files(&files, FILE_LINES);
    assert!(
        files_long.is_empty(),
        "core files over {FILE_LINES} lines (in-file tests left out): {files_long:?}"
    );
    let functions: Vec<_> = long_functions(&files, FUNCTION_LINES)
        .into_iter()
        .filter(|(name, _)| !LONG_KERNELS.contains(&name.as_str()))
        .collect();
    assert!(
        functions.is_empty(),
        "core functions over {FUNCTION_LINES} lines: {functions:?}"
    );
    // The kernels excepted are still there under those names (a rename would let another
    // function through in their place).
    let kernels = long_functions(&files, 0);
    for kernel in LONG_KERNELS {
        assert!(
            kernels.iter().any(|(name, _)| name == kernel),
            "{kernel} is excepted from the length bar but no longer exists"
        );
    }
}

#[test]
fn the_core_s_modules_stand_on_the_map_s_layers() {
    let map = std::fs::read_to_string(workspace().join("docs/architecture.md"))
        .expect("docs/architecture.md");
    let graph = module_graph(&sources(&workspace().join("crates/carom/src")));
    let layers = layers(&map);
    assert!(
        layers.len() > 5,
        "the layers table has too few modules: {layers:?}"
    );
    let faults = layer_faults(&graph, &layers);
    assert!(
        faults.is_empty(),
        "docs/architecture.md's layers and the core's imports disagree: {faults:#?}"
    );
}

#[test]
fn the_layer_check_finds_an_import_that_points_up() {
    let map = "## The core's layers\n\n| Layer | Modules | What |\n|---|---|---|\n\
               | 0 | `math`, `error` | numbers |\n| 1 | `geometry` | shapes |\n| 2 | `ghost` | - |\n\
               \n## Next\n| 9 | `world` | not the table |\n";
    let files = made_up(&[
        ("math.rs", "use crate::error::E;"),
        ("error.rs", "use crate::geometry::Shape;"),
        ("geometry/mod.rs", "use crate::math::Vec2;"),
        ("world.rs", ""),
    ]);
    assert_eq!(
        layer_faults(&module_graph(&files), &layers(map)),
        vec![
            "world is on no layer",
            "ghost is on a layer but is not a module",
            "error (layer 0) uses geometry (layer 1)",
        ]
    );
}

#[test]
fn the_architecture_map_names_every_file_of_the_core_and_the_scene_crate() {
    let map = std::fs::read_to_string(workspace().join("docs/architecture.md"))
        .expect("docs/architecture.md");
    let files = sources(&workspace().join("crates/carom/src"));
    let paths: Vec<&str> = files.iter().map(|f| f.path.as_str()).collect();
    let missing = unmapped(&map, "crates/carom/src/", &paths);
    assert!(
        missing.is_empty(),
        "docs/architecture.md does not name these files of crates/carom/src: {missing:?}"
    );
    let files = sources(&workspace().join("crates/carom-scene/src"));
    let paths: Vec<&str> = files.iter().map(|f| f.path.as_str()).collect();
    let missing = unmapped(&map, "crates/carom-scene/src/", &paths);
    assert!(
        missing.is_empty(),
        "docs/architecture.md does not name these files of crates/carom-scene/src: {missing:?}"
    );
}

fn made_up(files: &[(&str, &str)]) -> Vec<Source> {
    files
        .iter()
        .map(|&(path, text)| Source {
            path: path.into(),
            text: text.into(),
        })
        .collect()
}

#[test]
fn the_cycle_check_finds_a_cycle_and_ignores_tests() {
    let files = made_up(&[
        ("lib.rs", "mod a; mod b; mod c;"),
        ("a/mod.rs", "use crate::b::Thing;"),
        ("b.rs", "use crate::{c, a::Other};"),
        (
            "c.rs",
            "fn f() {}\n#[cfg(test)]\nmod tests {\n    use crate::a;\n}\n",
        ),
        ("c/tests.rs", "use crate::b;"),
    ]);
    assert_eq!(cycles(&module_graph(&files)), vec![vec!["a", "b"]]);
    let acyclic = made_up(&[
        ("a.rs", "use crate::b;"),
        ("b.rs", "use crate::c;"),
        ("c.rs", ""),
    ]);
    assert!(cycles(&module_graph(&acyclic)).is_empty());
}

#[test]
fn the_length_checks_count_code_not_tests_strings_or_comments() {
    let long_body = "    let x = 1;\n".repeat(5);
    let text = format!(
        "pub(crate) fn long() {{\n{long_body}}}\nfn short() {{ let s = \"{{{{\"; }} // }}\n\
         fn declared();\nfn brace() -> char {{ '{{' }}\n#[cfg(test)]\nmod tests {{\n{long_body}}}\n"
    );
    let files = made_up(&[("x.rs", &text)]);
    assert_eq!(
        long_functions(&files, 6),
        vec![("x.rs:long".to_string(), 7)]
    );
    assert!(long_functions(&files, 7).is_empty());
    assert_eq!(long_files(&files, 8), vec![("x.rs".to_string(), 10)]);
    assert!(long_files(&files, 10).is_empty());
}

#[test]
fn the_map_check_reads_rows_folders_and_lists() {
    let map = "| `crates/k/src/lib.rs` | the surface |\n\
               | `crates/s` | scenes: `build.rs` |\n\
               | `crates/k/src/math.rs`, `error.rs` | sums; errors |\n\
               | `crates/k/src/geo/` | `shape/` (`saved.rs`), `aabb.rs`, `tree/mod.rs` |\n";
    let files = [
        "lib.rs",
        "math.rs",
        "error.rs",
        "geo/mod.rs",
        "geo/aabb.rs",
        "geo/shape/mod.rs",
        "geo/shape/saved.rs",
        "geo/tree/mod.rs",
        "geo/ray.rs",
        "geo/hull/saved.rs",
        "stats.rs",
    ];
    assert_eq!(
        unmapped(map, "crates/k/src/", &files),
        vec!["geo/ray.rs", "geo/hull/saved.rs", "stats.rs"]
    );
    // A package's row stands for its src/.
    assert_eq!(
        unmapped(map, "crates/s/src/", &["build.rs", "load.rs"]),
        vec!["load.rs"]
    );
}
