//! The catalogue's text for people (`people`, the lab's words): every system's fields are
//! free of code (the browser test's denylist), and the rules do what they say on the
//! catalogue's own kinds of text.

use physicskit::classical::catalog::SYSTEMS;
use physicskit_listing::people;

/// What a person should never meet in the lab: scope paths, flags, ASCII powers, a state
/// column's code name, a note to developers.
const DENYLIST: [&str; 6] = ["::", "--", "^", "->", "thetadot", "as in the spec"];

#[test]
fn every_entry_reads_without_code() {
    for entry in SYSTEMS {
        let mut texts = vec![
            entry.presentation.title.to_string(),
            people::text(entry.summary),
        ];
        texts.extend(entry.note.and_then(people::note));
        for p in entry.params {
            texts.extend([
                people::label(p.name),
                people::text(p.unit),
                people::text(p.help),
            ]);
        }
        for text in &texts {
            for bad in DENYLIST {
                assert!(
                    !text.contains(bad),
                    "{}: {text:?} holds {bad:?}",
                    entry.name
                );
            }
        }
    }
}

/// Every index is in the one markup the lab lowers (`_{..}`): no `_` is left outside it, in
/// any field, the physics paragraphs too.
#[test]
fn every_index_is_marked() {
    for entry in SYSTEMS {
        let mut texts = vec![people::text(entry.summary)];
        texts.extend(entry.note.and_then(people::note));
        texts.extend(entry.physics.map(people::powers));
        for p in entry.params {
            texts.extend([people::label(p.name), people::text(p.help)]);
        }
        for text in &texts {
            let mut rest = text.as_str();
            let mut bare = String::new();
            while let Some(at) = rest.find("_{") {
                bare.push_str(&rest[..at]);
                let close = rest[at..].find('}').map_or(rest.len(), |c| at + c + 1);
                rest = &rest[close..];
            }
            bare.push_str(rest);
            assert!(!bare.contains('_'), "{}: {text:?}", entry.name);
        }
    }
}

#[test]
fn the_rules() {
    assert_eq!(people::label("thetadot0"), "θ\u{307}₀");
    assert_eq!(people::label("m1"), "m₁");
    assert_eq!(people::label("rk4"), "rk4");
    assert_eq!(people::label("decay_rate"), "decay rate");
    assert_eq!(people::text("m/s^2"), "m/s²");
    // Hyphens that are minus signs become minus signs; those in words and numbers stay.
    assert_eq!(
        people::text("(n1, n2, n3) -> (n1, -n2, -n3)"),
        "(n₁, n₂, n₃) → (n₁, −n₂, −n₃)"
    );
    assert_eq!(people::text("x^2 y - y^3/3"), "x² y − y³/3");
    assert_eq!(people::text("spring-like, 1e-8"), "spring-like, 1e-8");
    assert_eq!(people::text("c eps / r^(1+eps)"), "c ε / r¹⁺ᵋ");
    assert_eq!(
        people::text("planar Kepler problem (KeplerSystem::new)"),
        "planar Kepler problem"
    );
    assert_eq!(
        people::text("sine-Gordon chain (SineGordonChain::kink, free ends)"),
        "sine–Gordon chain (free ends)"
    );
    assert_eq!(
        people::note("the recurrence shows with e.g. --beta 0.7 --amplitude 0.5").as_deref(),
        Some("the recurrence shows with e.g. β = 0.7, amplitude = 0.5")
    );
    assert_eq!(people::note("p holds thetadot, as in the spec"), None);
    assert_eq!(
        people::note("critical speed omega_c = sqrt(g/R); p holds thetadot").as_deref(),
        Some("critical speed ω_{c} = √(g/R)")
    );
    assert_eq!(people::note("use --stride for long runs"), None);
    assert_eq!(
        people::powers("error ∝ dt^p, V = e^(−b r)"),
        "error ∝ dtᵖ, V = e⁻ᵇʳ"
    );
    assert_eq!(people::powers("√(a/b) e^(−b r/2)"), "√(a/b) exp(−b r/2)");
    assert_eq!(people::label("omega_earth"), "Ω_{⊕}");
    assert_eq!(people::label("latitude_deg"), "latitude");
    assert_eq!(people::label("angle_deg"), "angle");
    assert_eq!(people::label("c_eps"), "c_{ε}");
    assert_eq!(people::label("eta"), "η");
    assert_eq!(people::label("g_over_l"), "g/l");
    assert_eq!(people::label("angledots0"), "(φ̇, θ̇, ψ̇)₀");
    assert_eq!(
        people::powers("implicit_midpoint keeps V_eff, θ_min, q_{i+1} and Ω_⊕ t"),
        "implicit midpoint keeps V_{eff}, θ_{min}, q_{i+1} and Ω_{⊕} t"
    );
}
