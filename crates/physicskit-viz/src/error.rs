//! [`VizError`]: everything that can go wrong while rendering.

use std::path::PathBuf;

/// An error of the plotting crate.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum VizError {
    /// A simulation behind a figure failed.
    #[error("simulation failed: {0}")]
    Physics(#[from] physicskit::classical::Error),
    /// plotters could not draw or encode a figure.
    #[error("drawing `{path}` failed: {message}")]
    Draw {
        /// The file being drawn.
        path: PathBuf,
        /// plotters' message.
        message: String,
    },
    /// A file or directory could not be written.
    #[error("cannot write `{path}`: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A demonstration's run is not one the browser lab can open (a method it does not
    /// offer for the system).
    #[error("no lab link: {0}")]
    Lab(String),
    /// No demonstration has this number (the first field); they are numbered 1 to the second.
    #[error("no demonstration {0}: they are numbered 1 to {1}")]
    NoDemo(usize, usize),
    /// The bundled font could not be registered with plotters.
    #[error("the bundled DejaVu Sans font could not be loaded")]
    Font,
}

/// Result alias of the plotting crate.
pub type Result<T, E = VizError> = std::result::Result<T, E>;

/// Attaches the file being drawn to a plotters error.
pub(crate) trait DrawContext<T> {
    /// Converts the error into [`VizError::Draw`] naming `path`.
    fn at(self, path: &std::path::Path) -> Result<T>;
}

impl<T, E: std::fmt::Display> DrawContext<T> for std::result::Result<T, E> {
    fn at(self, path: &std::path::Path) -> Result<T> {
        self.map_err(|e| VizError::Draw {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }
}
