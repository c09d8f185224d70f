//! The catalogue's vocabulary: how a built-in system and its parameters are described as data.
//!
//! Every front end (the Python extension, the `physicskit` command, the browser lab, the
//! ensemble engine) builds systems by name from a [`SystemEntry`]: the system's name, summary
//! and family, its typed parameters ([`ParamSpec`]: kind, default, unit, valid range, help),
//! whether the splitting methods apply, its default method, and a `build` function into the
//! type-erased [`DynSystem`](super::erased::DynSystem). The entries themselves live next to
//! each system (`systems/*.rs`), and the one list of them is
//! [`catalog::SYSTEMS`](crate::classical::catalog::SYSTEMS).
//!
//! Front ends turn their own input (Python objects, command-line text, JSON) into [`Value`]s
//! of the declared kind and hand them to [`SystemEntry::values`], which is where every value is
//! checked: unknown and missing names, the kind, vector lengths, finiteness and the range. The
//! constructors the entry's `build` calls check again for users of the Rust API, and a test
//! checks that both agree at every range boundary.

use std::fmt;

use crate::classical::core::error::{Error, Result};
pub use crate::classical::integrators::Family;
use crate::classical::integrators::Method;

/// How front ends show a system: its title, the symbols of its coordinates, its unit of time,
/// the picture an animation draws and how an animation paces it. Python's plots and
/// animations read it from `catalog()`, the command line and the lab from `list --json`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Presentation {
    /// The system's name as a title for people, with its proper names and dashes
    /// (`"Hénon–Heiles"`, `"Foucault pendulum"`): menus, figure titles.
    pub title: &'static str,
    /// The coordinates' symbols in TeX math (`\theta_1`): one per coordinate, or a single one
    /// for every coordinate of a chain or a swarm (shown as `q_i`, `\theta_i`); empty when the
    /// state is not `[q, p]` (front ends then write `q_i` or the state's own names).
    pub symbols: &'static [&'static str],
    /// The unit of time: `"s"`, `"time"` where lengths and masses are in the user's own
    /// units, `""` for dimensionless time.
    pub time_unit: &'static str,
    /// Units of a coordinate and of a momentum (Hamiltonian) or velocity (Lagrangian), for an
    /// entry with no initial-state parameters; otherwise `None`, and those parameters'
    /// units ([`ParamSpec::initial_state`]) are the state's.
    pub state_units: Option<(&'static str, &'static str)>,
    /// The picture an animation draws.
    pub drawing: Drawing,
    /// How an animation run frame by frame steps the system.
    pub pace: Pace,
    /// The Poincaré section (`q_2 = 0`, `p_2 > 0`) is the picture that matters (bounded and
    /// chaotic at the default energy: islands in a chaotic sea), so a front end that can show
    /// one shows it from the start.
    pub section_first: bool,
    /// The equations conserve the system's `energy`, so front ends show its relative error as
    /// a check of the integration. False for the reduced models whose `energy` is dissipated
    /// by their damping (the reduced rattleback) or is not an energy (the reduced Euler's disk
    /// returns its tilt θ, as the peer does): front ends show no energy error for them.
    pub energy_conserved: bool,
}

/// How an animation that runs frame by frame (the lab, 60 frames a second) steps a system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pace {
    /// The front end's own step and steps a frame, with the entry's default method.
    Own,
    /// This fixed-step method, step and number of steps a frame. For a system whose default
    /// method is adaptive (a front end opens it with a step it can pace) and whose motion is fast
    /// against the front end's own step. The relative energy error of a run of
    /// [`PACE_CHECK_FRAMES`] frames from the defaults stays below `energy_error` (the
    /// catalogue's tests run it).
    Fixed {
        /// The method.
        method: Method,
        /// The step.
        dt: f64,
        /// Steps a frame.
        steps_per_frame: u32,
        /// The bound on the relative energy error that the front end may state.
        energy_error: f64,
    },
    /// Real time would show nothing (the effect builds up over hours): a time-lapse is offered
    /// at this step and number of steps a frame, the physics unchanged.
    TimeLapse {
        /// The step.
        dt: f64,
        /// Steps a frame.
        steps_per_frame: u32,
    },
}

/// Frames of a [`Pace::Fixed`] run over which its `energy_error` is checked: a minute at 60
/// frames a second.
pub const PACE_CHECK_FRAMES: u32 = 3600;

impl Pace {
    /// The kind's name, as front ends read it (`"fixed"`).
    pub fn name(self) -> &'static str {
        match self {
            Pace::Own => "own",
            Pace::Fixed { .. } => "fixed",
            Pace::TimeLapse { .. } => "time_lapse",
        }
    }

    /// The kind's fields by name, as front ends read them (`[("dt", Number(0.02)), ..]`).
    pub fn attributes(self) -> Vec<(&'static str, Attribute)> {
        match self {
            Pace::Own => Vec::new(),
            Pace::Fixed {
                method,
                dt,
                steps_per_frame,
                energy_error,
            } => vec![
                ("method", Attribute::Word(method.name())),
                ("dt", Attribute::Number(dt)),
                (
                    "steps_per_frame",
                    Attribute::Number(f64::from(steps_per_frame)),
                ),
                ("energy_error", Attribute::Number(energy_error)),
            ],
            Pace::TimeLapse {
                dt,
                steps_per_frame,
            } => vec![
                ("dt", Attribute::Number(dt)),
                (
                    "steps_per_frame",
                    Attribute::Number(f64::from(steps_per_frame)),
                ),
            ],
        }
    }
}

/// The ends of a chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ends {
    /// Held by walls.
    Fixed,
    /// Free.
    Free,
    /// Joined: the last site's neighbour is the first (a ring).
    Periodic,
}

impl Ends {
    /// The word front ends read (`"fixed"`).
    pub fn name(self) -> &'static str {
        match self {
            Ends::Fixed => "fixed",
            Ends::Free => "free",
            Ends::Periodic => "periodic",
        }
    }
}

/// The shape of a body rolling on a plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// An ellipsoid of semi-axes `a`, `b`, `c` whose centre is `h` above the centre of mass
    /// (the entry's parameters of those names).
    Ellipsoid,
    /// A thin disk of radius `a`.
    Disk,
}

impl Shape {
    /// The word front ends read (`"disk"`).
    pub fn name(self) -> &'static str {
        match self {
            Shape::Ellipsoid => "ellipsoid",
            Shape::Disk => "disk",
        }
    }
}

/// One attribute of a [`Drawing`] or a [`Pace`], as front ends read it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Attribute {
    /// A yes or no.
    Flag(bool),
    /// One word from a fixed set.
    Word(&'static str),
    /// A number.
    Number(f64),
}

/// The picture of a system in an animation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drawing {
    /// Bobs from a fixed pivot, at the system's `positions`, each hung from the last.
    Bobs {
        /// On springs (drawn as coils), not rigid rods.
        springs: bool,
        /// A length of the system's own that its `positions` are in units of, as a TeX
        /// symbol (`l`: a simple pendulum's are those of a unit rod; front ends write the
        /// axes `x / l`); `None` where they are in its parameters' unit of length.
        scale: Option<&'static str>,
    },
    /// A bead on a hoop that turns about its vertical diameter.
    Hoop,
    /// The members as points in their common phase plane, with the separatrix.
    Swarm,
    /// Masses along a line, each displaced across it (to scale with the spacing).
    Chain {
        /// The chain's ends.
        ends: Ends,
    },
    /// A field on the sites of a lattice: each site's value against the site (the
    /// sine–Gordon angles, whose kinks are the picture).
    Field,
    /// A body moving in the plane of its first two coordinates, with a trail.
    Orbit {
        /// A central body at the origin (a central force).
        central_body: bool,
        /// Level ground at `y = 0`, with the flight's apex and range (a projectile).
        ground: bool,
    },
    /// A rigid body as the box of its principal moments, turned by its rotation matrix.
    InertiaBox,
    /// A top's symmetry axis from its pivot, the tip tracing the unit sphere.
    TopAxis,
    /// A pendulum bob's horizontal path seen from above (Foucault's rosette).
    Swing,
    /// A disk's contact point seen from above as it tilts and precesses.
    ContactSpiral,
    /// A body's vertical spin against time (a reversal crosses zero).
    Spin,
    /// A body rolling without slipping on a plane, in 3-D, with its contact path and its
    /// spin about the vertical.
    Rolling {
        /// The body's shape.
        shape: Shape,
    },
    /// No picture beyond the plots of the state.
    Plots,
}

impl Drawing {
    /// The kind's name, as front ends read it (`"chain"`).
    pub fn name(self) -> &'static str {
        match self {
            Drawing::Bobs { .. } => "bobs",
            Drawing::Hoop => "hoop",
            Drawing::Swarm => "swarm",
            Drawing::Chain { .. } => "chain",
            Drawing::Field => "field",
            Drawing::Orbit { .. } => "orbit",
            Drawing::InertiaBox => "inertia_box",
            Drawing::TopAxis => "top_axis",
            Drawing::Swing => "swing",
            Drawing::ContactSpiral => "contact_spiral",
            Drawing::Spin => "spin",
            Drawing::Rolling { .. } => "rolling",
            Drawing::Plots => "plots",
        }
    }

    /// The kind's attributes by name, as front ends read them (`[("ends", Word("fixed"))]`).
    pub fn attributes(self) -> Vec<(&'static str, Attribute)> {
        match self {
            Drawing::Bobs { springs, scale } => {
                let mut attributes = vec![("springs", Attribute::Flag(springs))];
                attributes.extend(scale.map(|l| ("scale", Attribute::Word(l))));
                attributes
            }
            Drawing::Chain { ends } => vec![("ends", Attribute::Word(ends.name()))],
            Drawing::Orbit {
                central_body,
                ground,
            } => vec![
                ("central_body", Attribute::Flag(central_body)),
                ("ground", Attribute::Flag(ground)),
            ],
            Drawing::Rolling { shape } => vec![("shape", Attribute::Word(shape.name()))],
            _ => Vec::new(),
        }
    }
}

/// The length of a vector parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Length {
    /// Exactly this many entries.
    Fixed(usize),
    /// Any length from 1 on.
    Any,
    /// As long as the vector parameter of this name.
    SameAs(&'static str),
    /// As many entries as the value of the integer parameter of this name (e.g. `n`).
    Count(&'static str),
}

/// What kind of value a parameter takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamKind {
    /// A real number.
    Scalar,
    /// An integer (a count, a mode number, a seed, a sign).
    Integer,
    /// A vector of real numbers.
    Vector(Length),
    /// One word from a fixed set.
    Choice(&'static [&'static str]),
}

impl ParamKind {
    /// Lower-case name of the kind, for messages and `list --json`.
    pub fn name(self) -> &'static str {
        match self {
            ParamKind::Scalar => "scalar",
            ParamKind::Integer => "integer",
            ParamKind::Vector(_) => "vector",
            ParamKind::Choice(_) => "choice",
        }
    }
}

/// A constant value in a [`ParamSpec`] (a default), written in the entry's source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Literal {
    /// A real number.
    Scalar(f64),
    /// An integer.
    Integer(i64),
    /// A vector of real numbers.
    Vector(&'static [f64]),
    /// A word of a [`ParamKind::Choice`].
    Choice(&'static str),
}

impl Literal {
    /// The literal as an owned [`Value`].
    pub fn to_value(self) -> Value {
        match self {
            Literal::Scalar(x) => Value::Scalar(x),
            Literal::Integer(n) => Value::Integer(n),
            Literal::Vector(v) => Value::Vector(v.to_vec()),
            Literal::Choice(w) => Value::Choice(w.to_string()),
        }
    }
}

/// The default of a parameter, and whether the spec's Python signature carries it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Default {
    /// No default anywhere: every front end must give a value.
    Required,
    /// The spec's default value (the Python signature has it).
    Value(Literal),
    /// The spec's default is `None`: the parameter may be left out and the constructor decides
    /// (the help says what it does).
    Absent,
    /// The spec has no default (Python requires the value); front ends without required
    /// arguments (the command line, the lab) start from this demonstration value.
    Demo(Literal),
    /// The spec has no default; other front ends may leave it out and the entry's builder
    /// decides (the help says what it does, e.g. zeros).
    DemoAbsent,
}

impl Default {
    /// The spec's default real number.
    pub const fn scalar(x: f64) -> Self {
        Default::Value(Literal::Scalar(x))
    }

    /// The spec's default integer.
    pub const fn integer(n: i64) -> Self {
        Default::Value(Literal::Integer(n))
    }

    /// A demonstration real number (the spec has no default).
    pub const fn demo_scalar(x: f64) -> Self {
        Default::Demo(Literal::Scalar(x))
    }

    /// A demonstration vector (the spec has no default).
    pub const fn demo_vector(v: &'static [f64]) -> Self {
        Default::Demo(Literal::Vector(v))
    }
}

impl Default {
    /// The value used when the parameter is not given by a front end that has no required
    /// arguments (`None`: absent; `Err`: the parameter is required).
    fn fill(self) -> std::result::Result<Option<Value>, ()> {
        match self {
            Default::Required => Err(()),
            Default::Value(l) | Default::Demo(l) => Ok(Some(l.to_value())),
            Default::Absent | Default::DemoAbsent => Ok(None),
        }
    }

    /// The value used when the parameter is not given by a front end that follows the spec's
    /// signatures (Python): a parameter without a default in the spec is required there, even
    /// if it has a demonstration value.
    fn fill_as_in_spec(self) -> std::result::Result<Option<Value>, ()> {
        match self {
            Default::Value(l) => Ok(Some(l.to_value())),
            Default::Absent => Ok(None),
            Default::Required | Default::Demo(_) | Default::DemoAbsent => Err(()),
        }
    }

    /// True if the spec's signature has a default (a value or `None`).
    pub fn in_spec(self) -> bool {
        matches!(self, Default::Value(_) | Default::Absent)
    }
}

/// One side of a [`Range`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// No limit on this side.
    Unbounded,
    /// The value must be `>=` (or `<=`) this.
    Inclusive(f64),
    /// The value must be `>` (or `<`) this.
    Exclusive(f64),
}

/// The valid range of a scalar or integer parameter (finiteness is always required).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower limit.
    pub min: Bound,
    /// Upper limit.
    pub max: Bound,
}

impl Range {
    /// Any finite value.
    pub const ANY: Range = Range {
        min: Bound::Unbounded,
        max: Bound::Unbounded,
    };
    /// `> 0`.
    pub const POSITIVE: Range = Range {
        min: Bound::Exclusive(0.0),
        max: Bound::Unbounded,
    };
    /// `>= 0`.
    pub const NON_NEGATIVE: Range = Range {
        min: Bound::Inclusive(0.0),
        max: Bound::Unbounded,
    };

    /// `>= min`.
    pub const fn at_least(min: f64) -> Range {
        Range {
            min: Bound::Inclusive(min),
            max: Bound::Unbounded,
        }
    }

    /// `min <= x < max`.
    pub const fn half_open(min: f64, max: f64) -> Range {
        Range {
            min: Bound::Inclusive(min),
            max: Bound::Exclusive(max),
        }
    }

    /// `min < x < max`.
    pub const fn open(min: f64, max: f64) -> Range {
        Range {
            min: Bound::Exclusive(min),
            max: Bound::Exclusive(max),
        }
    }

    /// `min <= x <= max`.
    pub const fn closed(min: f64, max: f64) -> Range {
        Range {
            min: Bound::Inclusive(min),
            max: Bound::Inclusive(max),
        }
    }

    /// Whether `x` (finite) lies in the range.
    pub fn contains(&self, x: f64) -> bool {
        let above = match self.min {
            Bound::Unbounded => true,
            Bound::Inclusive(m) => x >= m,
            Bound::Exclusive(m) => x > m,
        };
        let below = match self.max {
            Bound::Unbounded => true,
            Bound::Inclusive(m) => x <= m,
            Bound::Exclusive(m) => x < m,
        };
        above && below
    }
}

impl fmt::Display for Range {
    /// The range as a condition, e.g. `> 0`, `>= 0 and < 1`, `any finite value`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let lower = match self.min {
            Bound::Unbounded => None,
            Bound::Inclusive(m) => Some(format!(">= {m}")),
            Bound::Exclusive(m) => Some(format!("> {m}")),
        };
        let upper = match self.max {
            Bound::Unbounded => None,
            Bound::Inclusive(m) => Some(format!("<= {m}")),
            Bound::Exclusive(m) => Some(format!("< {m}")),
        };
        match (lower, upper) {
            (None, None) => f.write_str("any finite value"),
            (Some(l), None) => f.write_str(&l),
            (None, Some(u)) => f.write_str(&u),
            (Some(l), Some(u)) => write!(f, "{l} and {u}"),
        }
    }
}

/// One typed parameter of a system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamSpec {
    /// Name: the spec's Python keyword, and the command line's `--name`.
    pub name: &'static str,
    /// The kind of value.
    pub kind: ParamKind,
    /// The default, and whether the spec has it.
    pub default: Default,
    /// Unit, in plain text (`""` for dimensionless or arbitrary units).
    pub unit: &'static str,
    /// Valid range of a scalar or integer (vectors: every entry finite).
    pub range: Range,
    /// One-line description.
    pub help: &'static str,
    /// Part of the initial state (`q0`, `theta0`, ...), not a constant of the system: its unit
    /// is a state component's, and front ends may accept it in the shapes a state takes.
    pub initial_state: bool,
}

impl ParamSpec {
    /// A real parameter.
    pub const fn scalar(
        name: &'static str,
        default: Default,
        unit: &'static str,
        range: Range,
        help: &'static str,
    ) -> Self {
        Self {
            name,
            kind: ParamKind::Scalar,
            default,
            unit,
            range,
            help,
            initial_state: false,
        }
    }

    /// The same parameter, marked as part of the initial state.
    pub const fn initial_state(self) -> Self {
        Self {
            initial_state: true,
            ..self
        }
    }

    /// An integer parameter.
    pub const fn integer(
        name: &'static str,
        default: Default,
        range: Range,
        help: &'static str,
    ) -> Self {
        Self {
            name,
            kind: ParamKind::Integer,
            default,
            unit: "",
            range,
            help,
            initial_state: false,
        }
    }

    /// A vector parameter.
    pub const fn vector(
        name: &'static str,
        length: Length,
        default: Default,
        unit: &'static str,
        help: &'static str,
    ) -> Self {
        Self {
            name,
            kind: ParamKind::Vector(length),
            default,
            unit,
            range: Range::ANY,
            help,
            initial_state: false,
        }
    }

    /// A choice among `words`.
    pub const fn choice(
        name: &'static str,
        words: &'static [&'static str],
        default: Default,
        help: &'static str,
    ) -> Self {
        Self {
            name,
            kind: ParamKind::Choice(words),
            default,
            unit: "",
            range: Range::ANY,
            help,
            initial_state: false,
        }
    }

    /// The valid values in words, e.g. `a real number > 0`, `3 real numbers`.
    pub fn expectation(&self) -> String {
        match self.kind {
            ParamKind::Scalar => format!("a real number, {}", self.range),
            ParamKind::Integer => format!("an integer, {}", self.range),
            ParamKind::Vector(Length::Fixed(n)) => format!("{n} real numbers"),
            ParamKind::Vector(Length::Any) => "one or more real numbers".into(),
            ParamKind::Vector(Length::SameAs(other)) => {
                format!("real numbers, as many as `{other}`")
            }
            ParamKind::Vector(Length::Count(count)) => format!("`{count}` real numbers"),
            ParamKind::Choice(words) => format!("one of: {}", words.join(", ")),
        }
    }

    fn invalid(&self, reason: impl Into<String>) -> Error {
        Error::InvalidArgument {
            name: self.name.into(),
            reason: reason.into(),
        }
    }

    /// Checks a value given for this parameter: its kind, finiteness and range (lengths that
    /// depend on other parameters are checked by [`SystemEntry::values`]).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the parameter, or [`Error::InvalidParameter`] with
    /// the rejected number for a value out of range.
    pub fn check(&self, value: &Value) -> Result<()> {
        match (self.kind, value) {
            (ParamKind::Scalar, Value::Scalar(x)) => {
                if !x.is_finite() {
                    return Err(Error::invalid(self.name, *x, "must be finite"));
                }
                self.check_range(*x)
            }
            (ParamKind::Integer, Value::Integer(n)) => self.check_range(*n as f64),
            (ParamKind::Vector(length), Value::Vector(v)) => {
                if let Length::Fixed(n) = length {
                    if v.len() != n {
                        return Err(Error::DimensionMismatch {
                            name: self.name.into(),
                            expected: n,
                            found: v.len(),
                        });
                    }
                }
                if v.is_empty() {
                    return Err(self.invalid("must hold at least one number"));
                }
                if v.iter().all(|x| x.is_finite()) {
                    Ok(())
                } else {
                    Err(self.invalid("contains NaN or infinity; pass finite numbers"))
                }
            }
            (ParamKind::Choice(words), Value::Choice(w)) => {
                if words.contains(&w.as_str()) {
                    Ok(())
                } else {
                    Err(self.invalid(format!("`{w}` is not one of: {}", words.join(", "))))
                }
            }
            (_, other) => Err(self.invalid(format!(
                "expected {}, got {}",
                self.expectation(),
                other.kind_name()
            ))),
        }
    }

    fn check_range(&self, x: f64) -> Result<()> {
        if self.range.contains(x) {
            Ok(())
        } else {
            Err(Error::invalid(
                self.name,
                x,
                format!("must be {}", self.range),
            ))
        }
    }
}

/// A parameter value, as a front end converted it.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A real number.
    Scalar(f64),
    /// An integer.
    Integer(i64),
    /// A vector of real numbers.
    Vector(Vec<f64>),
    /// A word.
    Choice(String),
}

impl Value {
    /// Lower-case name of the value's kind, for messages.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Value::Scalar(_) => "a real number",
            Value::Integer(_) => "an integer",
            Value::Vector(_) => "a vector",
            Value::Choice(_) => "a word",
        }
    }
}

/// Every parameter of one system with its checked value (`None`: left out, where allowed), in
/// the entry's order.
#[derive(Debug, Clone, PartialEq)]
pub struct Values {
    entries: Vec<(&'static str, Option<Value>)>,
}

impl Values {
    /// `(name, value)` pairs in the entry's order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, Option<&Value>)> {
        self.entries.iter().map(|(n, v)| (*n, v.as_ref()))
    }

    /// The value of `name`, `None` if it was left out.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if the entry declares no such parameter (a catalogue bug,
    /// caught by the catalogue's tests, which build every entry).
    pub fn get(&self, name: &str) -> Result<Option<&Value>> {
        self.entries
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v.as_ref())
            .ok_or_else(|| Error::InvalidArgument {
                name: name.into(),
                reason: "internal: the catalogue entry declares no such parameter".into(),
            })
    }

    /// Replaces the value at `index`, bypassing the checks: for the catalogue's tests, which
    /// feed the constructors values the catalogue refuses to show that the constructors refuse
    /// them too. Not API: a front end sets values through [`SystemEntry::values`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if the entry has no parameter at `index`.
    #[doc(hidden)]
    pub fn set_unchecked(&mut self, index: usize, value: Option<Value>) -> Result<()> {
        let len = self.entries.len();
        let entry = self
            .entries
            .get_mut(index)
            .ok_or_else(|| Error::InvalidArgument {
                name: "index".into(),
                reason: format!("{index} is past the entry's {len} parameters"),
            })?;
        entry.1 = value;
        Ok(())
    }

    fn wrong(name: &str, what: &str) -> Error {
        Error::InvalidArgument {
            name: name.into(),
            reason: format!("internal: not {what}"),
        }
    }

    fn required(name: &str) -> Error {
        Error::InvalidArgument {
            name: name.into(),
            reason: "is required".into(),
        }
    }

    /// A real parameter.
    ///
    /// # Errors
    /// Undeclared, absent, or of another kind.
    pub fn scalar(&self, name: &str) -> Result<f64> {
        self.opt_scalar(name)?.ok_or_else(|| Self::required(name))
    }

    /// A real parameter that may be absent.
    ///
    /// # Errors
    /// Undeclared, or of another kind.
    pub fn opt_scalar(&self, name: &str) -> Result<Option<f64>> {
        match self.get(name)? {
            None => Ok(None),
            Some(Value::Scalar(x)) => Ok(Some(*x)),
            Some(_) => Err(Self::wrong(name, "a real number")),
        }
    }

    /// An integer parameter.
    ///
    /// # Errors
    /// Undeclared, absent, or of another kind.
    pub fn integer(&self, name: &str) -> Result<i64> {
        match self.get(name)? {
            None => Err(Self::required(name)),
            Some(Value::Integer(n)) => Ok(*n),
            Some(_) => Err(Self::wrong(name, "an integer")),
        }
    }

    /// A non-negative integer parameter as a count.
    ///
    /// # Errors
    /// As [`integer`](Self::integer), or a negative value (a range missing from the entry).
    pub fn count(&self, name: &str) -> Result<usize> {
        let n = self.integer(name)?;
        usize::try_from(n).map_err(|_| Error::invalid(name, n as f64, "must be >= 0"))
    }

    /// A vector parameter.
    ///
    /// # Errors
    /// Undeclared, absent, or of another kind.
    pub fn vector(&self, name: &str) -> Result<&[f64]> {
        self.opt_vector(name)?.ok_or_else(|| Self::required(name))
    }

    /// A vector parameter that may be absent.
    ///
    /// # Errors
    /// Undeclared, or of another kind.
    pub fn opt_vector(&self, name: &str) -> Result<Option<&[f64]>> {
        match self.get(name)? {
            None => Ok(None),
            Some(Value::Vector(v)) => Ok(Some(v)),
            Some(_) => Err(Self::wrong(name, "a vector")),
        }
    }

    /// A choice parameter.
    ///
    /// # Errors
    /// Undeclared, absent, or of another kind.
    pub fn choice(&self, name: &str) -> Result<&str> {
        match self.get(name)? {
            None => Err(Self::required(name)),
            Some(Value::Choice(w)) => Ok(w),
            Some(_) => Err(Self::wrong(name, "a word")),
        }
    }
}

/// Builds a system from checked values.
pub type Builder = fn(&Values) -> Result<Box<dyn super::erased::DynSystem>>;

/// Declares a catalogue entry, or the catalogue's list: a `static` in the library, so that it
/// has one address and its builder is compiled once, here; a `const` in the library's
/// unit-test harness. There a static would be compiled whether or not a test reads it (rustc
/// compiles every static of a crate), and through its builder it would bring in every system
/// with every method, so the harness would compile as much as the library
/// (`benchmarks/README.md`, "Where the build time goes").
macro_rules! catalogue_static {
    ($(#[$attr:meta])* $vis:vis static $name:ident: $ty:ty = $value:expr;) => {
        $(#[$attr])*
        #[cfg(not(test))]
        $vis static $name: $ty = $value;
        $(#[$attr])*
        #[cfg(test)]
        $vis const $name: $ty = $value;
    };
}
pub(crate) use catalogue_static;

/// One built-in system (or one of its constructors) in the catalogue.
#[derive(Clone, Copy)]
pub struct SystemEntry {
    /// Name used by the command line, the lab and `list --json` (kebab-case).
    pub name: &'static str,
    /// The Python class, and for an alternate constructor the classmethod, as
    /// `"KeplerSystem.from_orbital_elements"`; `None` for entries with no Python
    /// counterpart.
    pub python: Option<&'static str>,
    /// One-line description.
    pub summary: &'static str,
    /// The family.
    pub family: Family,
    /// Parameters, in the order of the spec's signature.
    pub params: &'static [ParamSpec],
    /// Whether `H = T(p) + V(q)` with conservative forces for some parameters, so that the
    /// splitting methods apply (the built system has the last word: a projectile with drag
    /// refuses them).
    pub separable: bool,
    /// Whether the system has a Taylor form (its field as expressions, which the `taylor`
    /// method's recurrences are generated from): every Lagrangian system (its generic `L` is
    /// traced), and the Hamiltonians written once over any number type. The catalogue test
    /// runs `taylor` on every entry to check it.
    pub taylor_form: bool,
    /// The method `integrate` uses by default for the default parameters.
    pub default_method: Method,
    /// A remark for listings (which parameters show what).
    pub note: Option<&'static str>,
    /// The physics of the system, true whatever its parameters (plain text, Unicode): the
    /// lab's caption, `list --json`'s and Python `catalog()`'s `physics`, and the opening of
    /// the gallery demonstration that shows it. `None` for a system no page explains.
    pub physics: Option<&'static str>,
    /// How front ends show the system: symbols, unit of time, the picture it is drawn as.
    pub presentation: Presentation,
    /// The constructor.
    pub build: Builder,
}

impl fmt::Debug for SystemEntry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SystemEntry")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

impl SystemEntry {
    /// The parameter called `name`.
    pub fn param(&self, name: &str) -> Option<&'static ParamSpec> {
        self.params.iter().find(|p| p.name == name)
    }

    /// The parameter called `name`, for front ends that convert a value by its kind before
    /// handing it to [`values`](Self::values).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the unknown parameter and listing the valid ones.
    pub fn lookup(&self, name: &str) -> Result<&'static ParamSpec> {
        let params: &'static [ParamSpec] = self.params;
        self.index_of(name).map(|i| &params[i])
    }

    fn index_of(&self, name: &str) -> Result<usize> {
        self.params
            .iter()
            .position(|p| p.name == name)
            .ok_or_else(|| Error::InvalidArgument {
                name: name.into(),
                reason: format!(
                    "`{}` has no such parameter; its parameters are: {}",
                    self.name,
                    self.params
                        .iter()
                        .map(|p| p.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            })
    }

    /// The methods that can integrate this system: every method for separable systems,
    /// otherwise those that do not need `H = T(p) + V(q)`; one that needs a Taylor form
    /// ([`Method::needs_taylor_form`]) only where the entry has one
    /// ([`taylor_form`](Self::taylor_form)). The catalogue test runs every method on every
    /// entry to check the list.
    pub fn methods(&self) -> impl Iterator<Item = Method> + '_ {
        Method::ALL.into_iter().filter(move |m| {
            (self.separable || !m.needs_separable()) && (!m.needs_taylor_form() || self.taylor_form)
        })
    }

    /// What `read` makes of the entry's defaults, nothing given: how a system's
    /// `Params::default()` takes its values from the entry, where they are written once.
    ///
    /// # Panics
    /// If the entry's own defaults do not check or `read` refuses them: a catalogue bug, which
    /// the catalogue's tests (building every entry from its defaults, and every `Params`
    /// default) catch before a release.
    pub(crate) fn defaults<T>(&self, read: fn(&Values) -> Result<T>) -> T {
        match self.values(std::iter::empty()).and_then(|v| read(&v)) {
            Ok(t) => t,
            Err(e) => panic!(
                "`{}`: the catalogue's defaults do not build: {e}",
                self.name
            ),
        }
    }

    /// Checks `given` (parameter name and value) and fills in the defaults.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown or repeated name, a missing required value,
    /// a value of the wrong kind or a vector of the wrong length;
    /// [`Error::InvalidParameter`] for a number out of its range.
    pub fn values(&self, given: impl IntoIterator<Item = (String, Value)>) -> Result<Values> {
        self.checked(given, Default::fill)
    }

    /// As [`values`](Self::values), for front ends that follow the spec's signatures (the
    /// Python classes): only the spec's defaults are filled in, and a parameter the spec gives
    /// no default (a `Demo` or `DemoAbsent` one) must be given.
    ///
    /// # Errors
    /// As [`values`](Self::values).
    pub fn values_as_in_spec(
        &self,
        given: impl IntoIterator<Item = (String, Value)>,
    ) -> Result<Values> {
        self.checked(given, Default::fill_as_in_spec)
    }

    fn checked(
        &self,
        given: impl IntoIterator<Item = (String, Value)>,
        fill: fn(Default) -> std::result::Result<Option<Value>, ()>,
    ) -> Result<Values> {
        let mut slots: Vec<Option<Value>> = vec![None; self.params.len()];
        let mut seen = vec![false; self.params.len()];
        for (name, value) in given {
            let index = self.index_of(&name)?;
            if seen[index] {
                return Err(Error::InvalidArgument {
                    name,
                    reason: "given twice".into(),
                });
            }
            self.params[index].check(&value)?;
            seen[index] = true;
            slots[index] = Some(value);
        }
        for (spec, (slot, given)) in self.params.iter().zip(slots.iter_mut().zip(&seen)) {
            if !given {
                *slot = fill(spec.default).map_err(|()| Values::required(spec.name))?;
            }
        }
        let values = Values {
            entries: self.params.iter().map(|p| p.name).zip(slots).collect(),
        };
        self.check_lengths(&values)?;
        Ok(values)
    }

    /// Vector lengths tied to another parameter.
    fn check_lengths(&self, values: &Values) -> Result<()> {
        for spec in self.params {
            let ParamKind::Vector(length) = spec.kind else {
                continue;
            };
            let Some(v) = values.opt_vector(spec.name)? else {
                continue;
            };
            let expected = match length {
                Length::Fixed(_) | Length::Any => continue,
                Length::SameAs(other) => match values.opt_vector(other)? {
                    Some(o) => o.len(),
                    None => continue,
                },
                Length::Count(count) => values.count(count)?,
            };
            if v.len() != expected {
                return Err(Error::DimensionMismatch {
                    name: spec.name.into(),
                    expected,
                    found: v.len(),
                });
            }
        }
        Ok(())
    }

    /// Checks `given` and builds the system.
    ///
    /// # Errors
    /// As [`values`](Self::values), then whatever the system's constructor refuses.
    pub fn build_from(
        &self,
        given: impl IntoIterator<Item = (String, Value)>,
    ) -> Result<Box<dyn super::erased::DynSystem>> {
        let values = self.values(given)?;
        (self.build)(&values)
    }
}
