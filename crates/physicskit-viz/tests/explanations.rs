//! The gallery's paragraphs, each declared by its page (`physicskit_viz::explanations` lists
//! them without rendering): every demonstration has the physics (`text`, shown by the lab
//! beside a run from any setting) and the figures' setup (`figure`), and the physics states no
//! number of the setup.

use physicskit::classical::catalog;
use physicskit_viz::{explanations, Explanation, Physics};

/// The numbers written in `s`: runs of ASCII digits with inner `.` or `/` (`9.81`, `1/6`),
/// not glued to a preceding letter, digit, subscript or `_` (so `rk4`, `θ₁`, `kahan_li8` are
/// names, not numbers). A superscript exponent ends the run (`10⁻⁸` gives `10`).
fn numbers(s: &str) -> Vec<String> {
    let chars: Vec<char> = s.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let glued = i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
        if !chars[i].is_ascii_digit() || glued {
            i += 1;
            continue;
        }
        let mut token = String::new();
        while i < chars.len() {
            let c = chars[i];
            let inner =
                (c == '.' || c == '/') && chars.get(i + 1).is_some_and(char::is_ascii_digit);
            if !(c.is_ascii_digit() || inner) {
                break;
            }
            token.push(c);
            i += 1;
        }
        out.push(token);
    }
    out
}

#[test]
fn numbers_reads_values_not_names() {
    assert_eq!(
        numbers("g = 9.81 m/s², E = 1/6, rk4 at dt = 0.01, 10⁻⁸, θ₁ (2, 1)."),
        ["9.81", "1/6", "0.01", "10", "2", "1"]
    );
}

/// Every demonstration has both parts. The physics is true for any setting, so no number the
/// setup states (a parameter, a grid size, a run time) appears in it. Single digits are left
/// out: they are the coefficients, orders and labels of formulas (`1 − cos θ`, order 4, axis
/// 2), which a physics text and a setup both use with different meanings.
#[test]
fn the_physics_states_no_number_of_the_setup() {
    assert_eq!(explanations().count(), physicskit_viz::demo_count());
    for e in explanations() {
        assert!(e.text().len() > 200, "{}: text too short", e.slug);
        assert!(!e.figure.is_empty(), "{}: no setup", e.slug);
        let text = numbers(e.text());
        let setup: Vec<String> = numbers(e.figure)
            .into_iter()
            .filter(|n| n.len() > 1)
            .collect();
        for n in &setup {
            assert!(
                !text.contains(n),
                "{}: the physics states the setup's {n}",
                e.slug
            );
        }
    }
}

/// Slugs are unique; a demonstration of a system opens with that system's own physics, which
/// is the catalogue entry's (what the lab and `list --json` show); every system with a
/// paragraph is in the catalogue, and every catalogue system but the harmonic oscillator has
/// one.
#[test]
fn each_system_has_its_physics_and_the_gallery_opens_with_it() {
    let all: Vec<&Explanation> = explanations().collect();
    for (i, e) in all.iter().enumerate() {
        assert!(all[..i].iter().all(|o| o.slug != e.slug), "{}", e.slug);
        if let Physics::OfSystem(entry) = e.text {
            let listed = catalog::find(entry.name).expect("a catalogue system");
            assert!(std::ptr::eq(listed, entry), "{}", entry.name);
            assert_eq!(Some(e.text()), entry.physics, "{}", e.slug);
        }
    }
    let without: Vec<&str> = catalog::SYSTEMS
        .iter()
        .filter(|entry| entry.physics.is_none())
        .map(|entry| entry.name)
        .collect();
    assert_eq!(without, ["harmonic-oscillator"]);
}
