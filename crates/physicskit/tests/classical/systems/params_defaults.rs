//! Each system's `Params::default()` (what a user of the Rust API starts from) holds the
//! defaults its catalogue entry gives every front end. `default()` reads them from the entry
//! through the same mapping of parameter names to fields as the entry's builder; this checks,
//! field by field, that the mapping puts each parameter's default in the field of its name
//! (a swapped `I1`/`I2`, or a field read from another parameter, fails here) and that every
//! field has a catalogue default.
//!
//! A struct's fields are read from its `Debug` text (`Name { a: 1.0, b: 3 }`; `f64`'s `Debug`
//! prints the shortest text that reads back to the same bits), and matched to the entry's
//! parameters by name, ignoring case (`R` is the field `r`).

use physicskit::classical::catalog;
use physicskit::classical::model::entry::{Default, Literal};
use physicskit::classical::systems::{
    CoupledOscillatorsParams, DoublePendulumParams, ElasticPendulumParams, EulerTopParams,
    EulersDiskParams, FoucaultParams, HoopParams, RattlebackParams, RollingDiskParams,
    RollingRattlebackParams, SymmetricTopParams, TriplePendulumParams,
};

/// `(field, value)` of a struct's `Debug` text.
fn fields(debug: &str) -> Vec<(String, f64)> {
    let open = debug.find('{').expect(debug);
    let body = debug[open + 1..].trim_end_matches('}');
    body.split(',')
        .map(str::trim)
        .filter(|f| !f.is_empty())
        .map(|f| {
            let (name, value) = f.split_once(':').expect(f);
            let value = value
                .trim()
                .parse::<f64>()
                .unwrap_or_else(|_| panic!("{debug}: {f}"));
            (name.trim().to_string(), value)
        })
        .collect()
}

/// The entry's default of the parameter called `name` (any case), if it has one.
fn catalogue_default(system: &str, name: &str) -> Option<f64> {
    let entry = catalog::find(system).unwrap();
    let spec = entry
        .params
        .iter()
        .find(|p| p.name.eq_ignore_ascii_case(name))?;
    match spec.default {
        Default::Value(l) | Default::Demo(l) => match l {
            Literal::Scalar(x) => Some(x),
            Literal::Integer(n) => Some(n as f64),
            other => panic!("{system}: {name} has the default {other:?}, not a number"),
        },
        _ => None,
    }
}

#[test]
fn params_defaults_are_the_catalogue_defaults() {
    let cases: Vec<(&[&str], String)> = vec![
        (
            &["double-pendulum"],
            format!("{:?}", DoublePendulumParams::default()),
        ),
        (
            &["triple-pendulum"],
            format!("{:?}", TriplePendulumParams::default()),
        ),
        (&["hoop"], format!("{:?}", HoopParams::default())),
        (
            &["coupled-oscillators"],
            format!("{:?}", CoupledOscillatorsParams::default()),
        ),
        (
            &["heavy-top"],
            format!("{:?}", SymmetricTopParams::default()),
        ),
        (&["euler-top"], format!("{:?}", EulerTopParams::default())),
        (
            &["elastic-pendulum"],
            format!("{:?}", ElasticPendulumParams::default()),
        ),
        (
            &["foucault-pendulum"],
            format!("{:?}", FoucaultParams::default()),
        ),
        (
            &["eulers-disk"],
            format!("{:?}", EulersDiskParams::default()),
        ),
        (
            &["rattleback"],
            format!("{:?}", RattlebackParams::default()),
        ),
        (
            &["rolling-rattleback"],
            format!("{:?}", RollingRattlebackParams::default()),
        ),
        (
            &["rolling-disk", "rolling-disk-steady"],
            format!("{:?}", RollingDiskParams::default()),
        ),
    ];
    let mut mismatches = Vec::new();
    for (systems, debug) in &cases {
        let fields = fields(debug);
        assert!(!fields.is_empty(), "{debug}");
        for system in *systems {
            for (name, value) in &fields {
                match catalogue_default(system, name) {
                    Some(x) if x.to_bits() == value.to_bits() => {}
                    Some(x) => mismatches.push(format!(
                        "{system}: {name} is {value:?} in Params::default(), {x:?} in the catalogue"
                    )),
                    None => mismatches.push(format!(
                        "{system}: the field {name} ({value:?}) has no catalogue default"
                    )),
                }
            }
        }
    }
    assert!(mismatches.is_empty(), "{}", mismatches.join("\n"));
}
