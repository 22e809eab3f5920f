//! Reading scene files.

use crate::error::SceneError;
use crate::scene::Scene;
use std::path::Path;

/// Parses a scene from text; `file` names it in error messages. Optional values may be written
/// bare (`shape: Circle(radius: 0.5)`) or as `Some(...)`.
pub fn parse(text: &str, file: &str) -> Result<Scene, SceneError> {
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    options.from_str(text).map_err(|e| SceneError::Syntax {
        file: file.to_string(),
        line: e.span.start.line,
        column: e.span.start.col,
        message: e.code.to_string(),
    })
}

/// Reads and parses a scene file.
pub fn read(path: &Path) -> Result<Scene, SceneError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
        file: file.clone(),
        source,
    })?;
    parse(&text, &file)
}
