//! What [`Method`] tells about itself, from the `INFO` of its file: its name, order and
//! kind, and its spelling in user input (`"yoshida4".parse()`).

use std::fmt;
use std::str::FromStr;

use super::Method;
use crate::classical::core::error::Error;

impl Method {
    /// The spec's name of the method.
    pub fn name(self) -> &'static str {
        self.info().name
    }

    /// Order of accuracy of the global error.
    pub fn order(self) -> u32 {
        self.info().order
    }

    /// True for the splitting methods that need `H = T(p) + V(q)` and conservative forces.
    pub fn needs_separable(self) -> bool {
        self.info().separable_only
    }

    /// True if the method is symplectic (on the systems it accepts).
    pub fn is_symplectic(self) -> bool {
        self.info().symplectic
    }

    /// True if the method adapts its step to tolerances ([`Scheme::Adaptive`](crate::classical::core::Scheme::Adaptive)): `dt` is then
    /// the output spacing (a frame-by-frame session runs it with no end: see
    /// [`model::session`](crate::classical::model::session)).
    pub fn is_adaptive(self) -> bool {
        self.info().is_adaptive()
    }

    /// True if the method runs only on systems with a Taylor form
    /// ([`Scheme::Taylor`](crate::classical::core::Scheme::Taylor)): those defined by
    /// expressions ([`DynamicalSystem::taylor_field`](crate::classical::DynamicalSystem::taylor_field)).
    pub fn needs_taylor_form(self) -> bool {
        self.info().needs_taylor_form()
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
