//! Where the demo reads its scenes and reports: files built into the program, then the disk.
//!
//! The web build has no disk. It registers the scene files and the accuracy report it was
//! built with ([`embed`]), under the paths they had in the source tree (`demos/pyramid.ron`),
//! and every read here looks among those first. The native app registers nothing and reads
//! the disk, so editing a scene file shows at once.

use carom_scene::{Scene, SceneError, SceneWorld};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

static EMBEDDED: OnceLock<Vec<(PathBuf, &'static str)>> = OnceLock::new();

/// Registers files built into the program, as (path, text) pairs. The first call counts;
/// false if files were registered before (the new ones are then ignored).
pub fn embed(files: &[(&str, &'static str)]) -> bool {
    let files = files
        .iter()
        .map(|&(path, text)| (PathBuf::from(path), text))
        .collect();
    EMBEDDED.set(files).is_ok()
}

/// The text of an embedded file, if `path` is one.
pub fn embedded(path: &Path) -> Option<&'static str> {
    EMBEDDED
        .get()?
        .iter()
        .find(|(embedded, _)| embedded == path)
        .map(|&(_, text)| text)
}

/// Whether `path` is an embedded file (it cannot be written or change).
pub fn is_embedded(path: &Path) -> bool {
    embedded(path).is_some()
}

/// The text of the file at `path`: the embedded file's, else the disk's.
pub fn read_to_string(path: &Path) -> std::io::Result<String> {
    match embedded(path) {
        Some(text) => Ok(text.to_string()),
        None => std::fs::read_to_string(path),
    }
}

/// The `*.ron` files directly in `folder`, embedded and on disk, sorted, each once.
pub fn scene_files(folder: &Path) -> Vec<PathBuf> {
    let embedded = EMBEDDED.get().into_iter().flatten().map(|(p, _)| p.clone());
    let on_disk = std::fs::read_dir(folder)
        .into_iter()
        .flatten()
        .filter_map(|entry| entry.ok().map(|e| e.path()));
    let mut paths: Vec<PathBuf> = embedded
        .filter(|p| p.parent() == Some(folder))
        .chain(on_disk)
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    paths.dedup();
    paths
}

/// Reads and parses the scene file at `path`.
pub fn read_scene(path: &Path) -> Result<Scene, SceneError> {
    let file = path.display().to_string();
    let text = read_to_string(path).map_err(|source| SceneError::Io {
        file: file.clone(),
        source,
    })?;
    carom_scene::parse(&text, &file)
}

/// Reads, parses and builds the scene file at `path`.
pub fn load_scene(path: &Path) -> Result<SceneWorld, SceneError> {
    carom_scene::build(&read_scene(path)?, &path.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_files_are_read_before_the_disk_and_listed_with_it() {
        let folder = std::env::temp_dir().join(format!("carom-files-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("b.ron"), "on disk").unwrap();
        let a = folder.join("a.ron").display().to_string();
        let b = folder.join("b.ron").display().to_string();
        assert!(embed(&[(&a, "embedded a"), (&b, "embedded b")]));
        assert!(!embed(&[]), "files are registered once");

        assert_eq!(read_to_string(Path::new(&a)).unwrap(), "embedded a");
        assert_eq!(read_to_string(Path::new(&b)).unwrap(), "embedded b");
        assert!(is_embedded(Path::new(&a)));
        assert_eq!(
            scene_files(&folder),
            vec![PathBuf::from(&a), PathBuf::from(&b)]
        );
        assert!(read_to_string(&folder.join("c.ron")).is_err());
        assert!(matches!(
            read_scene(&folder.join("c.ron")),
            Err(SceneError::Io { .. })
        ));
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
