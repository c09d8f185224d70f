//! The catalogue (`src/classical/catalog.rs`) against the systems it builds: names unique,
//! every entry built from its defaults with the methods it lists and no other, its parameter
//! ranges the constructors' own, and values checked once with clear errors.

use physicskit::classical::catalog::{find, SYSTEMS};
use physicskit::classical::model::entry::{Bound, Default, Length, ParamKind, Value};
use physicskit::classical::{Error, IntegrateOptions, Method};

#[test]
fn names_are_unique() {
    let mut seen = std::collections::BTreeSet::new();
    for entry in SYSTEMS {
        assert!(seen.insert(entry.name), "duplicate system {}", entry.name);
        let mut params = std::collections::BTreeSet::new();
        for p in entry.params {
            assert!(
                params.insert(p.name),
                "{}: duplicate {}",
                entry.name,
                p.name
            );
        }
    }
}

/// Every entry builds from its defaults, its declared default method is the built
/// system's, and the methods it lists are exactly those the built system accepts (one
/// step with each: a method it refuses must fail with `UnsupportedMethod`).
#[test]
fn entries_build_and_agree_with_their_systems() {
    for entry in SYSTEMS {
        let mut system = entry
            .build_from([])
            .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        assert_eq!(system.family(), entry.family, "{}", entry.name);
        assert_eq!(
            system.default_method(),
            entry.default_method,
            "{}",
            entry.name
        );
        let listed: Vec<Method> = entry.methods().collect();
        let state = system.dynamical().state().to_vec();
        for method in Method::ALL {
            system.reset(Some(&state), 0.0).unwrap();
            let run = system.integrate((0.0, 1e-3), 1e-3, method, IntegrateOptions::default());
            match run {
                Ok(_) => assert!(listed.contains(&method), "{}: {method} ran", entry.name),
                Err(Error::UnsupportedMethod { .. }) => {
                    assert!(
                        !listed.contains(&method),
                        "{}: {method} refused",
                        entry.name
                    )
                }
                Err(e) => panic!("{}: {method}: {e}", entry.name),
            }
        }
    }
}

/// The catalogue's ranges are the constructors' own: at each finite bound, the value the
/// catalogue accepts builds and the value it refuses is refused by the constructor too
/// (fed past the catalogue's check).
#[test]
fn ranges_agree_with_the_constructors() {
    for entry in SYSTEMS {
        let defaults = entry.values([]).unwrap();
        // The way past the checks refuses an index past the entry's parameters.
        let past = defaults.clone().set_unchecked(entry.params.len(), None);
        assert!(
            matches!(past, Err(Error::InvalidArgument { .. })),
            "{}",
            entry.name
        );
        for (index, spec) in entry.params.iter().enumerate() {
            // A count that fixes another parameter's length (coupled oscillators' `n`)
            // cannot move alone: the default vectors would no longer fit it.
            let counts_a_vector = entry
                .params
                .iter()
                .any(|p| p.kind == ParamKind::Vector(Length::Count(spec.name)));
            if counts_a_vector {
                continue;
            }
            let bounds = [(spec.range.min, -1.0), (spec.range.max, 1.0)];
            for (bound, outward) in bounds {
                let (edge, inclusive) = match bound {
                    Bound::Unbounded => continue,
                    Bound::Inclusive(x) => (x, true),
                    Bound::Exclusive(x) => (x, false),
                };
                // The edge itself, and for an inclusive bound the next value outside.
                let outside = match spec.kind {
                    ParamKind::Integer => edge + outward,
                    _ => edge + outward * f64::EPSILON * edge.abs().max(1.0),
                };
                let mut cases = vec![(edge, inclusive)];
                if inclusive {
                    cases.push((outside, false));
                }
                for (x, accepted) in cases {
                    let value = match spec.kind {
                        ParamKind::Integer => Value::Integer(x as i64),
                        _ => Value::Scalar(x),
                    };
                    assert_eq!(
                        spec.check(&value).is_ok(),
                        accepted,
                        "{} {} = {x}",
                        entry.name,
                        spec.name
                    );
                    let mut values = defaults.clone();
                    values.set_unchecked(index, Some(value)).unwrap();
                    let built = (entry.build)(&values);
                    // An accepted boundary value may still be refused for another reason
                    // only if the entry says so: none does today.
                    assert_eq!(
                        built.is_ok(),
                        accepted,
                        "{} {} = {x}: constructor {}",
                        entry.name,
                        spec.name,
                        built.err().map_or("accepts".into(), |e| e.to_string())
                    );
                }
            }
        }
    }
}

#[test]
fn values_are_checked_once_with_clear_errors() {
    let entry = find("double-pendulum").unwrap();
    let err = |given: Vec<(&str, Value)>| {
        entry
            .values(given.into_iter().map(|(n, v)| (n.to_string(), v)))
            .unwrap_err()
            .to_string()
    };
    assert!(err(vec![("m3", Value::Scalar(1.0))]).contains("no such parameter"));
    assert!(err(vec![("m1", Value::Scalar(-1.0))]).contains("must be > 0"));
    assert!(err(vec![("m1", Value::Scalar(f64::NAN))]).contains("finite"));
    assert!(err(vec![("m1", Value::Vector(vec![1.0]))]).contains("expected a real number"));
    assert!(err(vec![("theta0", Value::Vector(vec![1.0]))]).contains("length 1, expected 2"));
    assert!(err(vec![("theta0", Value::Vector(vec![1.0, f64::INFINITY]))]).contains("NaN"));
    assert!(
        err(vec![("m1", Value::Scalar(1.0)), ("m1", Value::Scalar(2.0))]).contains("given twice")
    );
    // Lengths tied to another parameter.
    let chain = find("coupled-oscillators").unwrap();
    let e = chain
        .values([("n".to_string(), Value::Integer(4))])
        .unwrap_err();
    assert!(
        e.to_string().contains("`q0` has length 3, expected 4"),
        "{e}"
    );
    assert!(find("nope")
        .unwrap_err()
        .to_string()
        .contains("double-pendulum"));
    // A required value has no default anywhere.
    let required: Vec<_> = SYSTEMS
        .iter()
        .flat_map(|e| e.params)
        .filter(|p| p.default == Default::Required)
        .collect();
    assert!(required.is_empty(), "{required:?}");
}

/// The spec's signatures: only the spec's defaults are filled in; a demonstration value is
/// not a default there, nor is a `DemoAbsent` parameter optional.
#[test]
fn values_as_in_spec_require_what_the_spec_requires() {
    let entry = find("double-pendulum").unwrap();
    let e = entry.values_as_in_spec([]).unwrap_err().to_string();
    assert!(e.contains("`theta0`: is required"), "{e}");
    let given = [
        ("theta0".to_string(), Value::Vector(vec![0.1, 0.2])),
        ("thetadot0".to_string(), Value::Vector(vec![0.0, 0.0])),
    ];
    let values = entry.values_as_in_spec(given).unwrap();
    assert_eq!(values.get("m1").unwrap(), Some(&Value::Scalar(1.0)));
    // `p0` of the harmonic chain: zeros on the command line, required in Python.
    let chain = find("harmonic-chain").unwrap();
    let q0 = [("q0".to_string(), Value::Vector(vec![0.1]))];
    assert!(chain.values(q0.clone()).is_ok());
    let e = chain.values_as_in_spec(q0).unwrap_err().to_string();
    assert!(e.contains("`p0`: is required"), "{e}");
    // The spec's `None` (Absent) stays optional.
    let top = find("euler-top").unwrap();
    let omega0 = [("omega0".to_string(), Value::Vector(vec![0.0, 1.0, 0.0]))];
    assert_eq!(
        top.values_as_in_spec(omega0).unwrap().get("quat0").unwrap(),
        None
    );
}
