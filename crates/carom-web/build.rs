//! Builds the scene files of `demos/` and the accuracy report into the web build, under the
//! paths they have in the source tree, as `embedded.rs` in `OUT_DIR`. Saved scenes
//! (`*-saved.ron`) are the user's own and stay out.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let demos = root.join("demos");
    println!("cargo::rerun-if-changed={}", demos.display());
    let mut files: Vec<PathBuf> = std::fs::read_dir(&demos)
        .expect("the demos folder")
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| {
            let name = path.file_name().unwrap_or_default().to_string_lossy();
            name.ends_with(".ron") && !name.ends_with("-saved.ron")
        })
        .collect();
    files.sort();
    files.push(root.join("docs/accuracy/accuracy.csv"));
    let mut code = String::from("/// The files built in: (path in the source tree, text).\n");
    code.push_str("pub const FILES: &[(&str, &str)] = &[\n");
    for file in &files {
        println!("cargo::rerun-if-changed={}", file.display());
        let relative = file.strip_prefix(&root).expect("under the root");
        let absolute = file.canonicalize().expect("a file that exists");
        writeln!(
            code,
            "    ({:?}, include_str!({:?})),",
            relative.to_string_lossy(),
            absolute.to_string_lossy()
        )
        .expect("writing to a string");
    }
    code.push_str("];\n");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("embedded.rs"), code).expect("writing embedded.rs");
}
