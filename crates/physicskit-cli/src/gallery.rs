//! `physicskit gallery`: the adapter to the plotting crate `physicskit-viz`.
//!
//! The command line owns only the arguments and the progress display; rendering is
//! `physicskit_viz::render_gallery(out_dir, quick, &mut progress)`. Until that crate is part
//! of the workspace this adapter reports that the gallery is not built in.

use std::path::Path;

use anyhow::{bail, Result};

/// Renders the gallery into `out_dir`.
///
/// # Errors
/// Rendering or I/O failures reported by the plotting crate.
pub fn render(out_dir: &Path, quick: bool) -> Result<()> {
    // Wiring once physicskit-viz is merged (see issue 6):
    //     let mut progress = |done, total, name| { ... indicatif bar on a terminal ... };
    //     physicskit_viz::render_gallery(out_dir, quick, &mut progress)?;
    let _ = quick;
    bail!(
        "the gallery is not available in this build (physicskit-viz is not linked yet); \
         nothing was written to `{}`",
        out_dir.display()
    )
}
