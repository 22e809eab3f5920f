//! Steps scene files and prints each one's state hash: the check that a build for another
//! CPU, another SIMD width or another thread count computes the same bits.
//!
//! ```sh
//! cargo run --release -p carom-scene --example scene_hashes -- --steps 300 demos/*.ron
//! ```
//!
//! Prints one `name hash steps` line a scene, in the order given, so that another build can
//! step each scene as far and compare; a scene that fails to load or step prints
//! `name FAILED: reason` and makes the exit status 1. The hash is the one `carom run` prints
//! after the same steps.

use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let mut steps = 300usize;
    let mut files = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--steps" {
            match args.next().and_then(|n| n.parse().ok()) {
                Some(n) => steps = n,
                None => {
                    eprintln!("--steps takes a whole number");
                    return ExitCode::from(2);
                }
            }
        } else {
            files.push(arg);
        }
    }
    if files.is_empty() {
        eprintln!("usage: scene_hashes [--steps N] SCENE.ron...");
        return ExitCode::from(2);
    }
    let mut status = ExitCode::SUCCESS;
    for file in &files {
        let path = Path::new(file);
        let name = path
            .file_stem()
            .map_or(file.as_str(), |s| s.to_str().unwrap_or(file));
        match hash_after(path, steps) {
            Ok(hash) => println!("{name} {hash:016x} {steps}"),
            Err(reason) => {
                println!("{name} FAILED: {reason}");
                status = ExitCode::FAILURE;
            }
        }
    }
    status
}

/// The scene's state hash after `steps` steps.
fn hash_after(path: &Path, steps: usize) -> Result<u64, String> {
    let mut scene = carom_scene::load(path).map_err(|e| e.to_string())?;
    for _ in 0..steps {
        scene.step().map_err(|e| e.to_string())?;
    }
    Ok(scene.world.state_hash())
}
