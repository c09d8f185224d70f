//! The text listing: every catalogue entry with its methods and parameters, then the methods
//! table.

use std::io::{self, Write};

use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::model::SystemEntry;

use super::{method_rows, MethodRow};
use crate::params;

/// Writes the listing to `w`.
pub(super) fn write(w: &mut impl Write) -> io::Result<()> {
    for (k, entry) in SYSTEMS.iter().enumerate() {
        if k > 0 {
            writeln!(w)?;
        }
        system(w, entry)?;
    }
    writeln!(w)?;
    methods(w)?;
    writeln!(
        w,
        "\n{}\n\nUsage: physicskit simulate SYSTEM [--PARAM VALUE ...] [--method M] --dt DT \
         --t1 T1 [--t0 T0] [--stride K] --out FILE.npz|.csv|.json",
        params::DEMO_LEGEND
    )
}

fn system(w: &mut impl Write, entry: &SystemEntry) -> io::Result<()> {
    writeln!(w, "{}  [{}]", entry.name, entry.family.name())?;
    writeln!(w, "  {}", entry.summary)?;
    let methods: Vec<String> = entry
        .methods()
        .map(|m| {
            if m == entry.default_method {
                format!("{m} (default)")
            } else {
                m.to_string()
            }
        })
        .collect();
    writeln!(w, "  methods: {}", methods.join(", "))?;
    if let Some(note) = entry.note {
        writeln!(w, "  note: {note}")?;
    }
    let flags: Vec<String> = entry
        .params
        .iter()
        .map(|p| format!("--{} {}", p.name, params::placeholder(p.kind)))
        .collect();
    let width = flags.iter().map(String::len).max().unwrap_or(0);
    for (flag, p) in flags.iter().zip(entry.params) {
        writeln!(w, "    {flag:<width$}  {}", params::help_line(p))?;
    }
    Ok(())
}

fn yes_no(b: bool) -> String {
    if b { "yes" } else { "no" }.to_string()
}

/// A column of the methods table: its header and how a row fills it.
type Column = (&'static str, fn(&MethodRow) -> String);

/// The methods table, one column per [`MethodRow`] field.
fn methods(w: &mut impl Write) -> io::Result<()> {
    let columns: [Column; 6] = [
        ("method", |r| r.name.to_string()),
        ("order", |r| r.order.to_string()),
        ("symplectic", |r| yes_no(r.symplectic)),
        ("separable only", |r| yes_no(r.separable_only)),
        ("evaluations/step", |r| r.evaluations_per_step.to_string()),
        ("reference", |r| r.reference.to_string()),
    ];
    let rows = method_rows();
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| columns.iter().map(|(_, cell)| cell(r)).collect())
        .collect();
    let widths: Vec<usize> = columns
        .iter()
        .enumerate()
        .map(|(j, (header, _))| {
            cells
                .iter()
                .map(|row| row[j].len())
                .chain([header.len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: Vec<&str>| {
        let padded: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, &n)| format!("{c:<n$}"))
            .collect();
        format!("  {}", padded.join("  ").trim_end())
    };
    writeln!(w, "Methods:")?;
    writeln!(w, "{}", line(columns.iter().map(|(h, _)| *h).collect()))?;
    for row in &cells {
        writeln!(w, "{}", line(row.iter().map(String::as_str).collect()))?;
    }
    Ok(())
}
