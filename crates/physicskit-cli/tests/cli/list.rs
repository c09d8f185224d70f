//! `list` and `list --json` show every catalogue entry with its methods, parameters and
//! defaults, and `simulate SYSTEM --help` offers every parameter as a flag. The expected
//! content is read from the catalogue itself, so a new entry is checked without editing this
//! file.

use crate::common::{run_in, scratch, stdout};
use physicskit::classical::catalog::SYSTEMS;
use physicskit::classical::model::entry::{Default, Literal, ParamKind};
use physicskit::classical::Method;
use serde_json::{json, Value as Json};

#[test]
fn list_mentions_every_system_with_methods_and_defaults() {
    let dir = scratch();
    let out = run_in(dir.path(), &["list"]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    let headers: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("  [") && !l.starts_with(' '))
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    let names: Vec<&str> = SYSTEMS.iter().map(|e| e.name).collect();
    assert_eq!(
        headers, names,
        "one header per entry, in the catalogue's order"
    );
    assert_eq!(
        text.matches("(default)").count(),
        SYSTEMS.len(),
        "every system marks one default method"
    );
    assert_eq!(text.matches("  methods: ").count(), SYSTEMS.len());
    for entry in SYSTEMS {
        for p in entry.params {
            assert!(
                text.contains(&format!("    --{} ", p.name)),
                "{}: --{} not listed",
                entry.name,
                p.name
            );
        }
    }
    // The methods table: one row per method, with its order.
    for m in Method::ALL {
        let row = text
            .lines()
            .find(|l| l.split_whitespace().next() == Some(m.name()))
            .unwrap_or_else(|| panic!("no methods row for {m}"));
        assert_eq!(
            row.split_whitespace().nth(1),
            Some(m.order().to_string().as_str())
        );
    }
}

/// Every entry's `--help` offers each parameter as a flag and the entry's methods, with the
/// catalogue's default method.
#[test]
fn simulate_help_is_generated_from_the_catalogue() {
    let dir = scratch();
    for entry in SYSTEMS {
        let out = run_in(dir.path(), &["simulate", entry.name, "--help"]);
        assert_eq!(out.status.code(), Some(0), "simulate {} --help", entry.name);
        let help = stdout(&out);
        for p in entry.params {
            assert!(
                help.contains(&format!("--{} ", p.name)),
                "{}: --{} missing:\n{help}",
                entry.name,
                p.name
            );
        }
        let methods: Vec<&str> = entry.methods().map(Method::name).collect();
        let expected = format!(
            "integrator: {} (default {})",
            methods.join(", "),
            entry.default_method
        );
        assert!(help.contains(&expected), "{}:\n{help}", entry.name);
    }
}

/// The default as `list --json` must print it.
fn default_json(default: Default) -> (Json, &'static str) {
    let literal = |l| match l {
        Literal::Scalar(x) => json!(x),
        Literal::Integer(n) => json!(n),
        Literal::Vector(v) => json!(v),
        Literal::Choice(w) => json!(w),
    };
    match default {
        Default::Required => (Json::Null, "required"),
        Default::Value(l) => (literal(l), "spec"),
        Default::Absent => (Json::Null, "spec"),
        Default::Demo(l) => (literal(l), "demo"),
        Default::DemoAbsent => (Json::Null, "demo"),
    }
}

#[test]
fn list_json_holds_the_whole_catalogue() {
    let dir = scratch();
    let out = run_in(dir.path(), &["list", "--json"]);
    assert_eq!(out.status.code(), Some(0));
    let doc: Json = serde_json::from_slice(&out.stdout).expect("list --json is valid JSON");
    let systems = doc["systems"].as_array().expect("a `systems` array");
    assert_eq!(systems.len(), SYSTEMS.len());
    for (entry, s) in SYSTEMS.iter().zip(systems) {
        let name = entry.name;
        assert_eq!(s["name"], json!(name));
        assert_eq!(s["python"], json!(entry.python), "{name}");
        assert_eq!(s["summary"], json!(entry.summary), "{name}");
        assert_eq!(s["family"], json!(entry.family.name()), "{name}");
        assert_eq!(s["separable"], json!(entry.separable), "{name}");
        let methods: Vec<&str> = entry.methods().map(Method::name).collect();
        assert_eq!(s["methods"], json!(methods), "{name}");
        assert_eq!(
            s["default_method"],
            json!(entry.default_method.name()),
            "{name}"
        );
        assert_eq!(s["note"], json!(entry.note), "{name}");
        assert_eq!(s["physics"], json!(entry.physics), "{name}");
        let shown = &s["presentation"];
        let p = &entry.presentation;
        assert_eq!(shown["symbols"], json!(p.symbols), "{name}");
        assert_eq!(shown["time_unit"], json!(p.time_unit), "{name}");
        assert_eq!(
            shown["state_units"],
            json!(p.state_units.map(|(q, p)| [q, p])),
            "{name}"
        );
        assert_eq!(shown["drawing"]["kind"], json!(p.drawing.name()), "{name}");
        assert!(s["capabilities"].is_array(), "{name}");
        let params = s["params"].as_array().expect("a `params` array");
        assert_eq!(params.len(), entry.params.len(), "{name}");
        for (spec, p) in entry.params.iter().zip(params) {
            let what = format!("{name} {}", spec.name);
            assert_eq!(p["name"], json!(spec.name), "{what}");
            assert_eq!(p["kind"], json!(spec.kind.name()), "{what}");
            assert_eq!(p["unit"], json!(spec.unit), "{what}");
            assert_eq!(p["help"], json!(spec.help), "{what}");
            assert_eq!(p["initial_state"], json!(spec.initial_state), "{what}");
            let (default, origin) = default_json(spec.default);
            assert_eq!(p["default"], default, "{what}");
            assert_eq!(p["default_origin"], json!(origin), "{what}");
            // Integers stay integers: a tool must be able to tell `n: 32` from a real.
            if let Default::Value(Literal::Integer(_)) | Default::Demo(Literal::Integer(_)) =
                spec.default
            {
                assert!(p["default"].is_i64(), "{what}");
            }
            let ranged = matches!(spec.kind, ParamKind::Scalar | ParamKind::Integer);
            assert_eq!(p["range"].is_object(), ranged, "{what}");
            assert_eq!(
                p["length"].is_object(),
                matches!(spec.kind, ParamKind::Vector(_)),
                "{what}"
            );
        }
    }
    let methods = doc["methods"].as_array().expect("a `methods` array");
    let table = physicskit::classical::methods();
    assert_eq!(methods.len(), table.len());
    for (m, row) in table.iter().zip(methods) {
        assert_eq!(row["name"], json!(m.name));
        assert_eq!(row["label"], json!(m.label));
        assert_eq!(row["order"], json!(m.order));
        assert_eq!(row["symplectic"], json!(m.symplectic));
        assert_eq!(row["separable_only"], json!(m.separable_only));
        assert_eq!(row["adaptive"], json!(m.is_adaptive()));
        assert_eq!(row["needs_taylor_form"], json!(m.needs_taylor_form()));
        assert_eq!(row["evaluations_per_step"], json!(m.evaluations_per_step));
        assert_eq!(row["reference"], json!(m.reference));
    }
}

/// A few values spelled out, so that the encoding itself (not only its agreement with the
/// catalogue) is pinned: a spec default, a demonstration vector, a range, a length rule.
#[test]
fn list_json_encodes_defaults_ranges_and_lengths() {
    let dir = scratch();
    let out = run_in(dir.path(), &["list", "--json"]);
    let doc: Json = serde_json::from_slice(&out.stdout).unwrap();
    let system = |name: &str| {
        doc["systems"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == json!(name))
            .unwrap_or_else(|| panic!("{name} missing"))
            .clone()
    };
    let param = |s: &Json, name: &str| {
        s["params"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == json!(name))
            .unwrap_or_else(|| panic!("{name} missing"))
            .clone()
    };
    let dp = system("double-pendulum");
    let m1 = param(&dp, "m1");
    assert_eq!(m1["default"], json!(1.0));
    assert_eq!(m1["default_origin"], json!("spec"));
    assert_eq!(m1["unit"], json!("kg"));
    assert_eq!(
        m1["range"],
        json!({"min": {"value": 0.0, "inclusive": false}, "max": null})
    );
    let theta0 = param(&dp, "theta0");
    assert_eq!(theta0["default"], json!([2.0, 1.0]));
    assert_eq!(theta0["default_origin"], json!("demo"));
    assert_eq!(theta0["length"], json!({"rule": "fixed", "n": 2}));
    assert_eq!(theta0["range"], Json::Null);
    assert_eq!(
        dp["methods"],
        json!([
            "rk4",
            "implicit_midpoint",
            "gauss_legendre4",
            "gauss_legendre6",
            "dop853",
            "taylor"
        ])
    );
    assert!(dp["capabilities"]
        .as_array()
        .unwrap()
        .contains(&json!("positions")));
    let q0 = param(&system("coupled-oscillators"), "q0");
    assert_eq!(q0["length"], json!({"rule": "count", "param": "n"}));
}

/// The tolerance flags of `simulate` and `ensemble` name every adaptive method of the
/// registry, and no fixed-step one (the help once named dop853 alone, after taylor joined).
#[test]
fn tolerance_help_names_the_registrys_adaptive_methods() {
    let adaptive: Vec<&str> = Method::ALL
        .iter()
        .filter(|m| m.is_adaptive())
        .map(|m| m.name())
        .collect();
    assert!(adaptive.len() >= 2, "{adaptive:?}");
    let named = format!("({})", adaptive.join(", "));
    for args in [&["simulate", "kepler"][..], &["ensemble"][..]] {
        let help = crate::common::help(args);
        let lines: Vec<&str> = help.lines().map(str::trim).collect();
        for flag in ["--rtol", "--atol", "--max-steps"] {
            // The flag's line, then its help up to the next flag or blank line.
            let at = lines
                .iter()
                .position(|l| l.starts_with(&format!("{flag} ")))
                .unwrap_or_else(|| panic!("{args:?}: no {flag}:\n{help}"));
            let text = std::iter::once(lines[at])
                .chain(
                    lines[at + 1..]
                        .iter()
                        .take_while(|l| !l.is_empty() && !l.starts_with('-'))
                        .copied(),
                )
                .collect::<Vec<_>>()
                .join(" ");
            assert!(text.contains(&named), "{args:?} {flag}: {text}");
        }
    }
}
