//! The gallery: the demonstrations ([`demo_count`] of them), each a set of figures and a
//! one-paragraph explanation of the physics, and [`render_gallery`], which renders them all and
//! writes `index.html`.
//!
//! Every demonstration module has a `render(&Ctx) -> Result<Demo>` function and declares its
//! paragraph, `EXPLANATION` (an [`Explanation`]: its physics and what its figures show), which
//! [`explanations`] lists without rendering. `quick` mode
//! (used by tests and `physicskit gallery --quick`) runs fewer orbits, shorter times and fewer
//! animation frames, rendered at the figure's size rather than twice it, so the whole gallery
//! renders in well under a minute on two cores.
//!
//! A demonstration's number is its place in the list below: `Ctx` numbers its title
//! (`"17. Work–precision"`) and prefixes its files (`17_work_precision_1.svg`), so no page
//! types its own number.

use std::path::{Path, PathBuf};
use std::time::Instant;

use physicskit::classical::model::{SystemEntry, Value};
use physicskit::classical::Method;

use crate::error::{Result, VizError};

mod chains;
mod common;
mod double_pendulum;
mod double_pendulum_lyapunov;
mod double_pendulum_plane;
mod elastic_pendulum;
mod euler_top;
mod flip_fractal;
mod foucault;
mod fput;
mod heavy_top;
mod henon_heiles;
mod henon_heiles_regular;
mod henon_heiles_sali;
mod henon_heiles_starts;
mod hoop;
mod hoop_pitchfork;
mod integrators;
mod kepler;
mod kepler_precession;
mod projectile;
mod rattleback;
mod sine_gordon;
mod swarm;
mod toda;
mod work_precision;

/// A demonstration's paragraph, declared by its page: the physics, then what its figures show.
///
/// A demonstration of a system opens with that system's physics, which its catalogue entry
/// holds ([`SystemEntry::physics`], written next to the system and shown by the lab and
/// `list --json` too); a demonstration of a method or of an analysis across systems has a
/// paragraph of its own. The figure part says what the gallery's figures show (their
/// parameters, grid sizes, run times and panels), which only the gallery prints: the physics
/// holds for any parameters and states no number of the figure part (`tests/explanations.rs`).
#[derive(Debug, Clone, Copy)]
pub struct Explanation {
    /// The demonstration's anchor name in `index.html`, e.g. `"double-pendulum"`.
    pub slug: &'static str,
    /// The physics part: a system's, or the demonstration's own.
    pub text: Physics,
    /// What the gallery's figures show: their parameters, grid sizes, run times and panels
    /// (never empty). The gallery prints it after the physics; the lab, which starts from the
    /// catalogue's defaults, does not.
    pub figure: &'static str,
}

/// Where a demonstration's physics paragraph comes from.
#[derive(Debug, Clone, Copy)]
pub enum Physics {
    /// The physics of the catalogue system the demonstration shows.
    OfSystem(&'static SystemEntry),
    /// A paragraph of the demonstration's own (a method, or an analysis across systems).
    Own(&'static str),
}

impl Explanation {
    /// The physics paragraph (plain text, Unicode), true whatever the parameters.
    pub fn text(&self) -> &'static str {
        match self.text {
            Physics::OfSystem(entry) => entry.physics.unwrap_or(""),
            Physics::Own(text) => text,
        }
    }

    /// The catalogue system whose physics opens the paragraph, if any.
    pub fn system(&self) -> Option<&'static SystemEntry> {
        match self.text {
            Physics::OfSystem(entry) => Some(entry),
            Physics::Own(_) => None,
        }
    }
}

/// One file written by the gallery.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GalleryFile {
    /// Where it was written.
    pub path: PathBuf,
    /// One line saying what it shows.
    pub description: String,
}

/// One demonstration: its title, the physics it shows and its files.
#[derive(Debug, Clone, PartialEq)]
pub struct Demo {
    /// Anchor name in `index.html`, e.g. `"double-pendulum"`.
    pub slug: String,
    /// Section title, numbered (`"17. Work–precision"`).
    pub title: String,
    /// One paragraph of physics ([`Explanation::text`]; a system's is its catalogue entry's
    /// `physics`, the lab's caption).
    pub explanation: String,
    /// What this demonstration's figures show: their parameters and panels
    /// ([`Explanation::figure`]).
    pub figure: String,
    /// Figures and animations, in display order.
    pub files: Vec<GalleryFile>,
    /// The lab's share link of the demonstration's main run, if the lab can run it.
    pub lab: Option<LabLink>,
}

/// A link that opens the browser lab (`lab/index.html`) on a demonstration's setup, in the
/// lab's share-link format: `#system=NAME&method=M&dt=DT&params=JSON`, optionally `&state=...`
/// (comma-separated numbers), each value percent-encoded (`web/lab.js`, `applyHash`).
#[derive(Debug, Clone, PartialEq)]
pub struct LabLink {
    /// The URL fragment, from `#`.
    pub hash: String,
    /// What the link sets up, in words.
    pub what: String,
    /// The setup the fragment encodes, for tests to read the fragment back against.
    pub setup: LabSetup,
}

/// A run of a catalogue system as the lab sets it up: what a [`LabLink`] encodes.
#[derive(Debug, Clone, PartialEq)]
pub struct LabSetup {
    /// The catalogue entry's name.
    pub system: String,
    /// Parameter values given (the others stay at the entry's defaults).
    pub params: Vec<(String, Value)>,
    /// The integration method.
    pub method: Method,
    /// The step.
    pub dt: f64,
    /// The initial state the link carries: `None` when the entry built from `params` already
    /// starts there.
    pub state: Option<Vec<f64>>,
    /// The initial state of the demonstration's own run, which the link reproduces bit for bit.
    pub start: Vec<f64>,
}

/// Percent-encodes everything but unreserved characters (what `URLSearchParams` decodes).
fn url_encode(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            out.push(char::from(b));
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// A catalogue value as JSON (numbers in Rust's shortest round-trip form, as the lab writes
/// them).
fn json(v: &Value) -> String {
    match v {
        Value::Scalar(x) => format!("{x:?}"),
        Value::Integer(i) => i.to_string(),
        Value::Vector(xs) => format!(
            "[{}]",
            xs.iter()
                .map(|x| format!("{x:?}"))
                .collect::<Vec<_>>()
                .join(",")
        ),
        Value::Choice(c) => format!("\"{}\"", c.replace('\\', "\\\\").replace('"', "\\\"")),
    }
}

/// What [`render_gallery`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct GalleryReport {
    /// The demonstrations, in order.
    pub demos: Vec<Demo>,
    /// Every file written (all demo files, then `index.html`), each with a one-line
    /// description.
    pub files: Vec<GalleryFile>,
    /// The `index.html` page.
    pub index: PathBuf,
    /// Wall-clock rendering time in seconds.
    pub seconds: f64,
}

/// Rendering settings of one demonstration.
pub(crate) struct Ctx<'a> {
    out_dir: &'a Path,
    /// Fewer orbits and frames.
    pub quick: bool,
    /// The demonstration's number (its place in [`PAGES`], from 1).
    number: usize,
    /// The page's paragraph.
    explanation: &'static Explanation,
}

impl Ctx<'_> {
    /// Path of a gallery file of this demonstration: `name` prefixed with its two-digit number
    /// (`"flip_fractal.svg"` becomes `15_flip_fractal.svg`).
    pub fn path(&self, name: &str) -> PathBuf {
        self.out_dir.join(format!("{:02}_{name}", self.number))
    }

    /// Starts this demonstration's [`Demo`], its title numbered (`"17. Work–precision"`), its
    /// slug and paragraph the page's [`Explanation`].
    pub fn demo(&self, title: &str) -> Demo {
        Demo {
            slug: self.explanation.slug.into(),
            title: format!("{}. {title}", self.number),
            explanation: self.explanation.text().to_owned(),
            figure: self.explanation.figure.to_owned(),
            files: Vec::new(),
            lab: None,
        }
    }

    /// The lab link of the demonstration's run of catalogue system `system` with parameter
    /// values `params` (the values the demonstration itself runs with), fixed-step `method`
    /// and step `dt`, from the run's initial state `start`. The entry builds the system from
    /// `params`, as the lab does; the link carries `start` only if that build starts elsewhere
    /// (a start the entry's parameters do not describe), so the lab always opens on the
    /// figure's first state, bit for bit.
    ///
    /// # Errors
    /// [`VizError::Physics`] if the system is unknown or a value is refused by its entry, or
    /// `start` is not a state of the system; [`VizError::Lab`] if the entry does not take
    /// `method` or the method is adaptive (the lab steps frame by frame).
    pub fn lab_link(
        &self,
        system: &str,
        params: &[(&str, Value)],
        method: Method,
        dt: f64,
        start: &[f64],
    ) -> Result<LabLink> {
        let entry = physicskit::classical::catalog::find(system)?;
        let params: Vec<(String, Value)> = params
            .iter()
            .map(|(k, v)| ((*k).to_string(), v.clone()))
            .collect();
        let mut built = entry.build_from(params.iter().cloned())?;
        if method.is_adaptive() || !entry.methods().any(|m| m == method) {
            return Err(VizError::Lab(format!(
                "the lab cannot run {system} with {}",
                method.name()
            )));
        }
        let same = |a: &[f64], b: &[f64]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
        };
        let state = if same(built.dynamical().state(), start) {
            None
        } else {
            built.reset(Some(start), 0.0)?;
            Some(start.to_vec())
        };
        let object = params
            .iter()
            .map(|(k, v)| format!("\"{k}\":{}", json(v)))
            .collect::<Vec<_>>()
            .join(",");
        let mut hash = format!(
            "#system={}&method={}&dt={}&params={}",
            url_encode(system),
            url_encode(method.name()),
            url_encode(&format!("{dt:?}")),
            url_encode(&format!("{{{object}}}"))
        );
        if let Some(state) = &state {
            let s = state
                .iter()
                .map(|x| format!("{x:?}"))
                .collect::<Vec<_>>()
                .join(",");
            hash.push_str(&format!("&state={}", url_encode(&s)));
        }
        Ok(LabLink {
            hash,
            what: format!(
                "{system} with {}, dt = {dt}{}",
                method.name().replace('_', " "),
                if state.is_some() {
                    ", from the figure's start"
                } else {
                    ""
                }
            ),
            setup: LabSetup {
                system: system.into(),
                params,
                method,
                dt,
                state,
                start: start.to_vec(),
            },
        })
    }

    /// Device pixels per figure pixel of the GIF frames: twice the figure's size for the page
    /// ([`crate::animation::SCALE`], crisp on high-density screens), the figure's size in quick
    /// mode, where rasterizing and quantizing four times the pixels was most of the added time.
    pub fn gif_scale(&self) -> f32 {
        self.pick(1.0, crate::animation::SCALE)
    }

    /// `quick` value in quick mode, `full` otherwise.
    pub fn pick<T>(&self, quick: T, full: T) -> T {
        if self.quick {
            quick
        } else {
            full
        }
    }
}

impl Demo {
    /// Records a written file.
    pub(crate) fn add(&mut self, path: PathBuf, description: &str) {
        self.files.push(GalleryFile {
            path,
            description: description.into(),
        });
    }
}

type Render = fn(&Ctx) -> Result<Demo>;

/// A demonstration as the list holds it: its name for progress messages, its renderer and its
/// paragraph.
struct Page {
    name: &'static str,
    render: Render,
    explanation: &'static Explanation,
}

/// The [`Page`] of gallery module `$module`: its `render` and `EXPLANATION`.
macro_rules! page {
    ($name:literal, $module:ident) => {
        Page {
            name: $name,
            render: $module::render,
            explanation: &$module::EXPLANATION,
        }
    };
}

/// The demonstrations in gallery order.
static PAGES: &[Page] = &[
    page!("double pendulum", double_pendulum),
    page!("Hénon–Heiles", henon_heiles),
    page!("pendulum swarm", swarm),
    page!("FPUT recurrence", fput),
    page!("sine-Gordon kinks", sine_gordon),
    page!("harmonic chain and coupled oscillators", chains),
    page!("Kepler orbits", kepler),
    page!("Euler top", euler_top),
    page!("heavy symmetric top", heavy_top),
    page!("bead on a rotating hoop", hoop),
    page!("projectile", projectile),
    page!("integrators compared", integrators),
    page!("Toda lattice", toda),
    page!("elastic pendulum", elastic_pendulum),
    page!("flip-time fractal", flip_fractal),
    page!("Kepler precession against c_pn", kepler_precession),
    page!("work–precision", work_precision),
    page!("Hénon–Heiles SALI map", henon_heiles_sali),
    page!("double pendulum Lyapunov map", double_pendulum_lyapunov),
    page!("hoop pitchfork and Lyapunov exponent", hoop_pitchfork),
    page!("Hénon–Heiles regular fraction", henon_heiles_regular),
    page!("Foucault pendulum", foucault),
    page!("rolling rattleback", rattleback),
];

/// Every demonstration's paragraph, in gallery order, without rendering anything.
pub fn explanations() -> impl Iterator<Item = &'static Explanation> {
    PAGES.iter().map(|p| p.explanation)
}

/// Number of demonstrations [`render_gallery`] renders.
pub fn demo_count() -> usize {
    PAGES.len()
}

/// Renders demonstration `number` (from 1, as [`render_gallery`] numbers them) alone into
/// `out_dir` (created if missing), without the page: for tests of one demonstration.
///
/// # Errors
/// [`VizError::NoDemo`] if there is no such demonstration; otherwise as
/// [`render_gallery`].
pub fn render_demo(out_dir: &Path, number: usize, quick: bool) -> Result<Demo> {
    let Some(page) = number.checked_sub(1).and_then(|i| PAGES.get(i)) else {
        return Err(VizError::NoDemo(number, PAGES.len()));
    };
    std::fs::create_dir_all(out_dir).map_err(|source| VizError::Io {
        path: out_dir.to_path_buf(),
        source,
    })?;
    (page.render)(&Ctx {
        out_dir,
        quick,
        number,
        explanation: page.explanation,
    })
}

/// Renders every demonstration into `out_dir` (created if missing) and writes `index.html`
/// there. `quick` renders smaller versions (fewer orbits, shorter runs, fewer frames).
/// `progress` is told the name of each demonstration as it starts.
///
/// # Errors
/// [`VizError::Io`] if `out_dir` or a file cannot be written, [`VizError::Draw`] if plotters
/// fails, [`VizError::Physics`] if a simulation fails.
pub fn render_gallery(
    out_dir: &Path,
    quick: bool,
    progress: &mut dyn FnMut(&str),
) -> Result<GalleryReport> {
    let start = Instant::now();
    std::fs::create_dir_all(out_dir).map_err(|source| VizError::Io {
        path: out_dir.to_path_buf(),
        source,
    })?;
    let mut rendered = Vec::with_capacity(PAGES.len());
    for (i, page) in PAGES.iter().enumerate() {
        progress(&format!("[{}/{}] {}", i + 1, PAGES.len(), page.name));
        let ctx = Ctx {
            out_dir,
            quick,
            number: i + 1,
            explanation: page.explanation,
        };
        rendered.push((page.render)(&ctx)?);
    }
    let index = out_dir.join("index.html");
    std::fs::write(&index, crate::html::index_html(&rendered, quick)).map_err(|source| {
        VizError::Io {
            path: index.clone(),
            source,
        }
    })?;
    let mut files: Vec<GalleryFile> = rendered
        .iter()
        .flat_map(|d| d.files.iter().cloned())
        .collect();
    files.push(GalleryFile {
        path: index.clone(),
        description: "the gallery page: every figure with its physics explanation (opens offline)"
            .into(),
    });
    Ok(GalleryReport {
        demos: rendered,
        files,
        index,
        seconds: start.elapsed().as_secs_f64(),
    })
}
