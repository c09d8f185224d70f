//! [`Method`]: the integrators, by the spec's names.

use std::fmt;
use std::str::FromStr;

use super::error::Error;

/// A fixed-step integrator, named as in the spec.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Classical 4th-order Runge–Kutta (`"rk4"`); not symplectic.
    Rk4,
    /// Störmer–Verlet kick–drift–kick (`"verlet"`); order 2, symplectic, separable only.
    Verlet,
    /// Yoshida's 4th-order triple-jump composition of Verlet (`"yoshida4"`); separable only.
    Yoshida4,
    /// Implicit midpoint rule (`"implicit_midpoint"`); order 2, symplectic for any
    /// Hamiltonian, conserves every quadratic invariant.
    ImplicitMidpoint,
}

impl Method {
    /// Every method, in the order they are listed to users.
    pub const ALL: [Method; 4] = [
        Method::Rk4,
        Method::Verlet,
        Method::Yoshida4,
        Method::ImplicitMidpoint,
    ];

    /// The spec's name of the method.
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "rk4",
            Method::Verlet => "verlet",
            Method::Yoshida4 => "yoshida4",
            Method::ImplicitMidpoint => "implicit_midpoint",
        }
    }

    /// Order of accuracy of the global error.
    pub fn order(self) -> u32 {
        match self {
            Method::Rk4 | Method::Yoshida4 => 4,
            Method::Verlet | Method::ImplicitMidpoint => 2,
        }
    }

    /// True for the splitting methods that need `H = T(p) + V(q)` and conservative forces.
    pub fn needs_separable(self) -> bool {
        matches!(self, Method::Verlet | Method::Yoshida4)
    }

    /// True if the method is symplectic (on the systems it accepts).
    pub fn is_symplectic(self) -> bool {
        !matches!(self, Method::Rk4)
    }

    /// Comma-separated list of valid names, for messages.
    pub fn valid_names() -> String {
        Self::ALL.map(Method::name).join(", ")
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = Error;

    /// Parses a spec name such as `"yoshida4"`.
    ///
    /// # Errors
    /// [`Error::UnknownMethod`] listing the valid names.
    fn from_str(name: &str) -> Result<Self, Error> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == name)
            .ok_or_else(|| Error::UnknownMethod {
                name: name.to_string(),
                valid: Self::valid_names(),
            })
    }
}
