//! `HamiltonianSystem::force_and_potential`: the splitting integrators store
//! `kinetic_energy(p) + V` with `V` from the step's last force evaluation. That must change
//! nothing: the force is the one `force` writes and every stored energy has the bits of
//! `energy` evaluated on the stored row (the independent definition `T(p) + V(q)`).

use physicskit::classical::examples::Pendulum;
use physicskit::classical::systems::{
    HenonHeilesSystem, KeplerPerturbations, KeplerSystem, PendulumSwarm, SineGordonChain,
};
use physicskit::classical::{HamiltonianSystem, IntegrateOptions, Method, Sampling};

/// A deterministic spread in [-amplitude, amplitude] (Weyl sequence of the golden ratio).
fn spread(n: usize, amplitude: f64, offset: f64) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let u = (i as f64 * 0.618_033_988_749_895 + offset).fract();
            amplitude * (2.0 * u - 1.0)
        })
        .collect()
}

/// Direct check at `q`, then every stored energy of verlet and yoshida4 runs (every step, a
/// stride, and the final state only) against `energy` of its row, bit for bit.
/// `fused`: whether the system supplies its potential with the force (checked, so that a
/// system that stops doing so is noticed rather than compared with itself).
fn check<S: HamiltonianSystem + Clone>(name: &str, system: &S, q: &[f64], fused: bool) {
    let n = system.ndof();
    let (mut f1, mut f2) = (vec![0.0; n], vec![0.0; n]);
    system.force(q, 0.3, &mut f1).unwrap();
    let v = system.force_and_potential(q, 0.3, &mut f2).unwrap();
    assert_eq!(v.is_some(), fused, "{name}");
    assert!(
        f1.iter().zip(&f2).all(|(a, b)| a.to_bits() == b.to_bits()),
        "{name}: the force differs"
    );
    if let Some(v) = v {
        assert_eq!(v.to_bits(), system.potential_energy(q).to_bits(), "{name}");
    }
    for method in [Method::Verlet, Method::Yoshida4] {
        for sampling in [Sampling::All, Sampling::Stride(7), Sampling::FinalOnly] {
            let mut s = system.clone();
            let options = IntegrateOptions {
                sampling,
                ..Default::default()
            };
            let r = s.integrate_with((0.0, 0.5), 0.01, method, options).unwrap();
            let energy = r.energy.as_ref().unwrap();
            for (row, e) in r.y.rows().into_iter().zip(energy) {
                let expected = s.energy(row.as_slice().unwrap());
                assert_eq!(
                    e.to_bits(),
                    expected.to_bits(),
                    "{name}, {method:?}, {sampling:?}: stored {e:e}, energy {expected:e}"
                );
            }
        }
    }
}

#[test]
fn stored_energies_equal_the_energy_of_the_stored_states() {
    // Swarms and chains of every length class of the slice code: below the short sums (1-4),
    // one lane block, remainders, and more than one 128-element cosine block.
    for n in [1, 2, 3, 5, 8, 13, 130, 300] {
        let q = spread(n, 2.5, 0.1);
        let p = spread(n, 0.7, 0.4);
        check("swarm", &PendulumSwarm::new(&q, &p, 1.7).unwrap(), &q, true);
        let chain = SineGordonChain::new(n, 1.3, 2.1, Some(&q), Some(&p)).unwrap();
        check("sine-Gordon", &chain, &q, true);
    }
    // Past the vector path's limit the slices fall back to libm.
    let big = [3.0, 2e6, -1.0];
    check(
        "swarm, libm path",
        &PendulumSwarm::new(&big, &[0.0; 3], 1.0).unwrap(),
        &big,
        true,
    );
    for pert in [
        KeplerPerturbations::none(),
        KeplerPerturbations::none().with_power_law(0.2, 0.05),
        KeplerPerturbations {
            c_pn: 0.01,
            softening: 0.1,
            ..Default::default()
        },
    ] {
        let kepler = KeplerSystem::new(&[1.0, 0.2], &[0.1, 1.1], 1.0, 1.0, pert).unwrap();
        check("Kepler", &kepler, &[0.7, -0.4], true);
    }
    // Systems without a fused potential keep storing `energy`.
    check(
        "Henon-Heiles",
        &HenonHeilesSystem::new(&[0.1, 0.2], &[0.3, 0.1]).unwrap(),
        &[0.1, -0.2],
        false,
    );
    check(
        "pendulum",
        &Pendulum::new(0.4, 0.0, 1.0).unwrap(),
        &[0.4],
        false,
    );
}
