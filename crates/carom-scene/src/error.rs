//! What can be wrong with a scene file, said so a user can find and fix it.

/// A scene that could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{file}: cannot read it: {source}")]
    Io {
        /// The file.
        file: String,
        /// Why.
        source: std::io::Error,
    },
    /// The text is not a scene (malformed RON, a misspelt field, an unknown effect...).
    #[error("{file}:{line}:{column}: {message}")]
    Syntax {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What was expected.
        message: String,
    },
    /// The text is a scene, but something in it cannot be built (a non-convex polygon, a
    /// non-positive density, NaN, an event naming no body...).
    #[error("{file}: {what}: {reason}")]
    Invalid {
        /// The file.
        file: String,
        /// Which part: "body 3 (\"lid\")", "generator 1 (pyramid)", "event 0", "world".
        what: String,
        /// Why it cannot be built.
        reason: String,
    },
    /// A scene could not be written.
    #[error("{file}: cannot write it: {reason}")]
    Write {
        /// The file.
        file: String,
        /// Why.
        reason: String,
    },
}
