//! `physicskit gallery`: the adapter to the plotting crate `physicskit-viz`.
//!
//! The command line owns only the arguments and the progress display; rendering is
//! `physicskit_viz::render_gallery(out_dir, quick, &mut progress)`, which calls `progress`
//! with the name of each demonstration as it starts and returns a report of the files
//! written. [`backend::render`] is the single place that calls it.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};

/// What the command line prints after rendering.
#[derive(Debug)]
pub struct Report {
    /// Number of files written (figures, animations, `index.html`).
    pub files: usize,
    /// The gallery page.
    pub index: PathBuf,
    /// Wall-clock seconds spent rendering.
    pub seconds: f64,
}

/// Renders the gallery into `out_dir` and prints where it is.
///
/// # Errors
/// Rendering or I/O failures reported by the plotting crate.
pub fn render(out_dir: &Path, quick: bool) -> Result<()> {
    let spinner = std::io::stderr().is_terminal().then(|| {
        let bar = ProgressBar::new_spinner();
        if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed} {msg}") {
            bar.set_style(style);
        }
        bar.enable_steady_tick(Duration::from_millis(120));
        bar
    });
    let mut progress = |step: &str| match &spinner {
        Some(bar) => bar.set_message(step.to_string()),
        // Logs and pipes get one plain line per demonstration.
        None => eprintln!("{step}"),
    };
    let report = backend::render(out_dir, quick, &mut progress);
    if let Some(bar) = &spinner {
        bar.finish_and_clear();
    }
    let report = report?;
    println!(
        "{} files in {} ({:.1} s); open {}",
        report.files,
        out_dir.display(),
        report.seconds,
        report.index.display()
    );
    Ok(())
}

mod backend {
    use std::path::Path;

    use anyhow::Result;

    use super::Report;

    /// Calls the plotting crate.
    pub fn render(out_dir: &Path, quick: bool, progress: &mut dyn FnMut(&str)) -> Result<Report> {
        let r = physicskit_viz::render_gallery(out_dir, quick, progress)?;
        Ok(Report {
            files: r.files.len(),
            index: r.index,
            seconds: r.seconds,
        })
    }
}
