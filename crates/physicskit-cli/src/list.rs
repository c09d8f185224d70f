//! `physicskit list`: every registered system with its parameters, defaults and methods.

use std::io::{self, Write};

use crate::systems::REGISTRY;

/// Writes the listing to `w`.
///
/// # Errors
/// I/O errors of `w` (a closed pipe).
pub fn print(w: &mut impl Write) -> io::Result<()> {
    for (k, spec) in REGISTRY.iter().enumerate() {
        if k > 0 {
            writeln!(w)?;
        }
        writeln!(w, "{}  [{}]", spec.name, spec.family.name())?;
        writeln!(w, "  {}", spec.summary)?;
        let methods: Vec<String> = spec
            .methods
            .iter()
            .map(|&m| {
                if m == spec.default_method {
                    format!("{m} (default)")
                } else {
                    m.to_string()
                }
            })
            .collect();
        writeln!(w, "  methods: {}", methods.join(", "))?;
        if let Some(note) = spec.note {
            writeln!(w, "  note: {note}")?;
        }
        let width = spec
            .params
            .iter()
            .map(|p| p.name.len() + p.kind.placeholder().len() + 3)
            .max()
            .unwrap_or(0);
        for p in spec.params {
            let flag = format!("--{} {}", p.name, p.kind.placeholder());
            writeln!(w, "    {flag:<width$}  {}", p.help_with_default())?;
        }
    }
    writeln!(
        w,
        "\nUsage: physicskit simulate SYSTEM [--PARAM VALUE ...] [--method M] --dt DT --t1 T1 \
         [--t0 T0] [--stride K] --out FILE.npz|.csv|.json"
    )
}
