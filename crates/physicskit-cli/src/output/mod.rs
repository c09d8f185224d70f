//! Writing a trajectory to `.npz`, `.csv` or `.json`, chosen by the file's extension; an
//! analysis's named arrays likewise ([`Arrays`]).
//!
//! Every format holds the same content: the sample times `t`; `q` and `p` (for Lagrangian
//! systems `p` holds `qdot`, as in the spec), or the raw state `y` for general ODE systems;
//! the `energy`; and the run's settings (system, family, method, `t0`, `t1`, `dt`) and every
//! parameter value used, defaults included (CSV, being one numeric table, keeps only the
//! numeric ones). Numbers are written so that they read back to the same bits.
//!
//! A file is never left half-written: [`Pending::create`] opens a temporary file next to the
//! destination before the (possibly long) integration starts, so an unwritable path fails
//! early, and [`Pending::commit`] renames it over the destination only after everything is
//! written and flushed. If anything fails, the temporary file is deleted when dropped.

mod analysis;
pub mod arrays;
mod csv;
mod json;
mod npy;
mod npz;
pub mod number;

pub use analysis::{Arrays, Named};

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use ndarray::{Array1, ArrayView2};
use physicskit::classical::integrators::Family;
use physicskit::classical::model::Values;
use physicskit::classical::SimulationResult;

/// An output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// A numpy `.npz` archive of NPY v1.0 arrays (uncompressed).
    Npz,
    /// Comma-separated values: a header row, one row per sample; the numeric settings and
    /// parameters as constant trailing columns.
    Csv,
    /// One JSON object.
    Json,
}

impl Format {
    /// The format named by `path`'s extension (case-insensitive).
    ///
    /// # Errors
    /// Missing or unknown extensions.
    pub fn from_path(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        Ok(match ext.as_deref() {
            Some("npz") => Format::Npz,
            Some("csv") => Format::Csv,
            Some("json") => Format::Json,
            Some(other) => bail!(
                "unknown output extension `.{other}` in `{}`; use .npz, .csv or .json",
                path.display()
            ),
            None => bail!(
                "output file `{}` has no extension; use .npz, .csv or .json",
                path.display()
            ),
        })
    }
}

/// Everything written about one run.
#[derive(Debug)]
pub struct Record<'a> {
    /// Catalogue name of the system.
    pub system: &'a str,
    /// Its family, from the catalogue entry.
    pub family: Family,
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t1: f64,
    /// Step.
    pub dt: f64,
    /// Every parameter with the value used.
    pub params: &'a Values,
    /// The library's result.
    pub result: &'a SimulationResult,
}

impl Record<'_> {
    /// The state arrays to write, by name: `q` and `p`, or `y` when the result has no split.
    pub fn state_arrays(&self) -> Vec<(&'static str, ArrayView2<'_, f64>)> {
        match (self.result.q(), self.result.p()) {
            (Some(q), Some(p)) => vec![("q", q), ("p", p)],
            _ => vec![("y", self.result.y.view())],
        }
    }

    /// The energy, if the run computed it.
    pub fn energy(&self) -> Option<&Array1<f64>> {
        self.result.energy.as_ref()
    }

    /// Scalar run settings, by name.
    pub fn settings(&self) -> [(&'static str, f64); 3] {
        [("t0", self.t0), ("t1", self.t1), ("dt", self.dt)]
    }
}

/// A temporary file next to the destination, renamed over it by [`commit`](Self::commit).
#[derive(Debug)]
pub struct Pending {
    format: Format,
    path: PathBuf,
    temp: tempfile::NamedTempFile,
}

impl Pending {
    /// Checks the extension and opens the temporary file in the destination's directory.
    ///
    /// # Errors
    /// Unknown extensions, a destination that is a directory, or a directory that does not
    /// exist or cannot be written.
    pub fn create(path: &Path) -> Result<Self> {
        let format = Format::from_path(path)?;
        if path.is_dir() {
            bail!("output path `{}` is a directory", path.display());
        }
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        if !dir.is_dir() {
            bail!(
                "cannot write `{}`: directory `{}` does not exist",
                path.display(),
                dir.display()
            );
        }
        let temp = tempfile::Builder::new()
            .prefix(".physicskit-")
            .suffix(".tmp")
            .tempfile_in(dir)
            // tempfile's message names the temporary file, which means nothing to the user.
            .map_err(|e| match e.raw_os_error() {
                Some(code) => std::io::Error::from_raw_os_error(code),
                None => std::io::Error::from(e.kind()),
            })
            .with_context(|| format!("cannot write `{}`", path.display()))?;
        Ok(Self {
            format,
            path: path.to_path_buf(),
            temp,
        })
    }

    /// Writes `record`, flushes it to disk and renames the file into place.
    ///
    /// # Errors
    /// I/O failures; the temporary file is then removed and the destination left untouched.
    pub fn commit(self, record: &Record<'_>) -> Result<()> {
        self.commit_with(|format, file| match format {
            Format::Npz => npz::write(file, record),
            Format::Csv => write_buffered(file, |w| csv::write(w, record)),
            Format::Json => write_buffered(file, |w| json::write(w, record)),
        })
    }

    /// The output format, from the destination's extension.
    pub fn is_npz(&self) -> bool {
        self.format == Format::Npz
    }

    /// Writes an analysis's named arrays, as [`commit`](Self::commit).
    ///
    /// # Errors
    /// As [`commit`](Self::commit).
    pub fn commit_arrays(self, record: &Arrays<'_>) -> Result<()> {
        self.commit_with(|format, file| match format {
            Format::Npz => analysis::write_npz(file, record),
            Format::Csv => write_buffered(file, |w| analysis::write_csv(w, record)),
            Format::Json => write_buffered(file, |w| analysis::write_json(w, record)),
        })
    }

    /// Writes the file with `write` (given the format), flushes it to disk and renames it into
    /// place.
    ///
    /// # Errors
    /// As [`commit`](Self::commit).
    pub fn commit_with(
        self,
        write: impl FnOnce(Format, &File) -> std::io::Result<()>,
    ) -> Result<()> {
        let context = || format!("cannot write `{}`", self.path.display());
        let file: &File = self.temp.as_file();
        write(self.format, file).with_context(context)?;
        file.sync_all().with_context(context)?;
        make_readable(file);
        self.temp
            .persist(&self.path)
            .map_err(|e| e.error)
            .with_context(context)?;
        Ok(())
    }
}

fn write_buffered(
    file: &File,
    body: impl FnOnce(&mut BufWriter<&File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut w = BufWriter::new(file);
    body(&mut w)?;
    w.flush()
}

/// The temporary file is created private (0600); the output is an ordinary data file.
#[cfg(unix)]
fn make_readable(file: &File) {
    use std::os::unix::fs::PermissionsExt;
    // Best effort: failing to widen the mode leaves a private but complete file.
    let _ = file.set_permissions(std::fs::Permissions::from_mode(0o644));
}

#[cfg(not(unix))]
fn make_readable(_file: &File) {}
