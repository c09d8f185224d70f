//! The registry's entries: one [`SystemSpec`] per system the command line can simulate.
//!
//! Names and defaults follow the spec's constructors (`physicskit-classical-api.txt`). Systems
//! with an alternate constructor the spec documents (`from_orbital_elements`, `from_box`,
//! `from_launch`, `kink`) are registered under the name people use for the demonstration and
//! take that constructor's parameters; the plain-state constructor is registered next to it.

use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::Method;

use crate::registry::{Family, Kind, ParamSpec, SystemSpec};
use crate::simulation::Hamiltonian;

const ALL_METHODS: &[Method] = &Method::ALL;

const fn real(name: &'static str, default: &'static str, help: &'static str) -> ParamSpec {
    ParamSpec {
        name,
        kind: Kind::Real,
        default: Some(default),
        help,
    }
}

/// Every registered system, in the order `list` shows them.
pub static REGISTRY: &[SystemSpec] = &[
    SystemSpec {
        name: "pendulum",
        summary: "simple pendulum H = p^2/2 - (g/l) cos q (examples::Pendulum)",
        family: Family::Hamiltonian,
        params: &[
            real("q0", "1.0", "initial angle [rad]"),
            real("p0", "0.0", "initial momentum [rad/s, unit m l^2]"),
            real("g_over_l", "1.0", "g / l [1/s^2], > 0"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            Ok(Box::new(Hamiltonian(Pendulum::new(
                v.real("q0")?,
                v.real("p0")?,
                v.real("g_over_l")?,
            )?)))
        },
    },
    SystemSpec {
        name: "harmonic-oscillator",
        summary: "harmonic oscillator H = p^2/(2m) + k q^2/2 (examples::HarmonicOscillator)",
        family: Family::Hamiltonian,
        params: &[
            real("q0", "1.0", "initial position [m]"),
            real("p0", "0.0", "initial momentum [kg m/s]"),
            real("m", "1.0", "mass [kg], > 0"),
            real("k", "1.0", "spring constant [N/m], > 0"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            Ok(Box::new(Hamiltonian(HarmonicOscillator::new(
                v.real("q0")?,
                v.real("p0")?,
                v.real("m")?,
                v.real("k")?,
            )?)))
        },
    },
];
