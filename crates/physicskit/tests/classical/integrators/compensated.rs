//! Compensated summation in the splitting stepper (`integrators/compensated.rs`): the rounding
//! walk of a long high-order run shrinks to one rounding of the state per step, the spec's
//! methods stay the textbook methods up to rounding, and the tangent map's orbit is the
//! integrator's, bit for bit.

use crate::fixtures::henon_heiles_at;
use physicskit::classical::analysis::lyapunov::lyapunov_spectrum;
use physicskit::classical::model::erased::{DynSystem, Hamiltonian};
use physicskit::classical::systems::HenonHeilesSystem;
use physicskit::classical::{DynamicalSystem, HamiltonianSystem, Method};

/// SciML's Hénon–Heiles case (SciMLBenchmarks, "Hénon–Heiles energy conservation"):
/// `q0 = (0.1, 0)`, `p0 = (0, 0.5)`, `E = 0.13`.
fn sciml_case() -> HenonHeilesSystem {
    HenonHeilesSystem::new(&[0.1, 0.0], &[0.0, 0.5]).unwrap()
}

/// Largest `|E - E0|` over the stored energies.
fn max_energy_error(e: &[f64]) -> f64 {
    e.iter().fold(0.0_f64, |m, v| m.max((v - e[0]).abs()))
}

/// The bound on `kahan_li8`'s energy error in SciML's case: the bar, SciML's own
/// KahanLi8 figure. What is left at dt = 1e-2 is rounding (the truncation error of an
/// eighth-order method is far below it; carried across steps, compensation reaches 2e-16 in a
/// prototype of this loop): with each step rounding `x, y, p_x, p_y` once (half an ulp, at most
/// 2.8e-17 for |p| < 0.5, entering dE through p dp) the walk of 1e6 steps has a spread of about
/// 1e3 times a step's, a few 1e-15. Measured 6.5e-15; the plain sums (35 roundings per
/// coordinate and step) gave 4.4e-14, which fails this bound: the test sees the compensation.
const TOLERANCE: f64 = 3.2e-14;

/// 1e6 steps of `kahan_li8` at dt = 1e-2 (SciML's case, every step stored): see [`TOLERANCE`].
#[test]
fn kahan_li8_holds_scimls_henon_heiles_energy_at_the_rounding_floor() {
    let steps = 1_000_000;
    let dt = 1e-2;
    let result = sciml_case()
        .integrate((0.0, steps as f64 * dt), dt, Method::KahanLi8)
        .unwrap();
    let e = result.energy.unwrap().to_vec();
    let max = max_energy_error(&e);
    println!("kahan_li8, SciML Hénon–Heiles, 1e6 steps: max |dE| = {max:e}");
    assert!(max <= TOLERANCE, "max |dE| = {max:e}");
}

/// The plain (uncompensated) Störmer–Verlet and Yoshida-4 steps, written out here from their
/// definitions (Yoshida 1990: substeps w1, w0, w1 with w1 = 1/(2 - 2^(1/3)), w0 = 1 - 2 w1),
/// on Hénon–Heiles. Returns the state after `steps` steps of `dt`.
fn textbook(yoshida: bool, steps: usize, dt: f64) -> [f64; 4] {
    let force = |q: [f64; 2]| [-q[0] - 2.0 * q[0] * q[1], -q[1] - q[0] * q[0] + q[1] * q[1]];
    let w1 = 1.0 / (2.0 - 2.0_f64.cbrt());
    let substeps: &[f64] = if yoshida {
        &[w1, 1.0 - 2.0 * w1, w1]
    } else {
        &[1.0]
    };
    let (mut q, mut p) = ([0.1, 0.0], [0.0, 0.5]);
    for _ in 0..steps {
        for &w in substeps {
            let h = w * dt;
            let f = force(q);
            for i in 0..2 {
                p[i] += 0.5 * h * f[i];
                q[i] += h * p[i];
            }
            let f = force(q);
            for i in 0..2 {
                p[i] += 0.5 * h * f[i];
            }
        }
    }
    [q[0], q[1], p[0], p[1]]
}

/// Largest state difference allowed between the library and the plain loops below over 1e4
/// steps: rounding only. A yoshida4 step rounds differently in the two (the library merges
/// the half-kicks between substeps; the bound also holds the compensated sums the two methods
/// had before 1a14b4b), a few 1e-17 to 1e-16 per step, and on a regular orbit such differences
/// grow at most linearly (a phase shift): 1e4 steps times 1e-16 is 1e-12; 1e-11 leaves a factor
/// ten (measured: 0 for verlet, 1.7e-13 for yoshida4, whose truncation errors here are 6.7e-5
/// and 2.2e-8; with the compensated sums 5.6e-15 and 1.1e-13). A wrong weight or force would
/// differ at the truncation error.
const ROUNDING: f64 = 1e-11;

/// The spec's `verlet` and `yoshida4` are the textbook methods: their states differ from the
/// plain loop's only by rounding ([`ROUNDING`]), and far inside their truncation error
/// (estimated against the same method at dt/2): unchanged as methods.
#[test]
fn verlet_and_yoshida4_are_the_textbook_methods_to_rounding() {
    let (steps, dt) = (10_000, 1e-2);
    for (method, yoshida) in [(Method::Verlet, false), (Method::Yoshida4, true)] {
        let run = |steps: usize, dt: f64| {
            let mut hh = sciml_case();
            hh.integrate((0.0, steps as f64 * dt), dt, method).unwrap();
            hh.state().to_vec()
        };
        let ours = run(steps, dt);
        let halved = run(2 * steps, dt / 2.0);
        let plain = textbook(yoshida, steps, dt);
        let distance = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        };
        let rounding = distance(&ours, &plain);
        let truncation = distance(&ours, &halved);
        println!("{method}: from the plain loop {rounding:e}, truncation ~{truncation:e}");
        assert!(
            rounding <= ROUNDING,
            "{method}: {rounding:e} from the plain loop"
        );
        assert!(
            rounding <= 1e-3 * truncation,
            "{method}: {rounding:e} is not small against the truncation error {truncation:e}"
        );
    }
}

/// The tangent map's orbit (`Flow::step_tangent`, its own loop over kicks and drifts with the
/// deviation vectors) is the integrator's orbit bit for bit: the same compensated kernels, the
/// corrections folded at the same points. Every splitting method, on a chaotic Hénon–Heiles
/// orbit (where any difference in the last bit would grow by t = 200).
#[test]
fn the_tangent_maps_orbit_is_the_integrators() {
    for method in Method::ALL.into_iter().filter(|m| m.needs_separable()) {
        let start = || henon_heiles_at(1.0 / 6.0, 0.0, 0.0, 0.1);
        let mut a = Hamiltonian(start());
        lyapunov_spectrum(&mut a, (0.0, 200.0), 0.05, Some(method), Some(2), 10).unwrap();
        let mut b = start();
        b.integrate((0.0, 200.0), 0.05, method).unwrap();
        let bits = |s: &[f64]| s.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            bits(a.dynamical().state()),
            bits(b.state()),
            "{method}: the tangent map's orbit differs"
        );
    }
}
