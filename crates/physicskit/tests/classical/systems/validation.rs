//! One test per validation error: bad input gives the documented `Error`, never a panic.

use physicskit::classical::analysis::{ellipk, pendulum_action_angle};
use physicskit::classical::systems::{
    FPUTChain, HarmonicChain, HenonHeilesSystem, KeplerPerturbations, KeplerSystem, NormalModes,
    PendulumSwarm, ProjectileMotion, SineGordonChain,
};
use physicskit::classical::Error;

fn invalid(result_err: Error, name: &str) {
    match result_err {
        Error::InvalidParameter { name: n, .. } => assert_eq!(n, name),
        other => panic!("expected InvalidParameter({name}), got {other}"),
    }
}

fn dimension(result_err: Error, name: &str) {
    match result_err {
        Error::DimensionMismatch { name: n, .. } => assert_eq!(n, name),
        other => panic!("expected DimensionMismatch({name}), got {other}"),
    }
}

fn non_finite(result_err: Error) {
    assert!(
        matches!(result_err, Error::NonFinite { .. }),
        "{result_err}"
    );
}

const NONE: KeplerPerturbations = KeplerPerturbations {
    eps: 0.0,
    c_eps: 0.0,
    c_pn: 0.0,
    softening: 0.0,
};

#[test]
fn kepler_wrong_length() {
    dimension(
        KeplerSystem::new(&[1.0], &[0.0, 1.0], 1.0, 1.0, NONE).unwrap_err(),
        "q0",
    );
    dimension(
        KeplerSystem::new(&[1.0, 0.0], &[1.0; 3], 1.0, 1.0, NONE).unwrap_err(),
        "p0",
    );
}

#[test]
fn kepler_non_finite_state() {
    non_finite(KeplerSystem::new(&[f64::NAN, 0.0], &[0.0, 1.0], 1.0, 1.0, NONE).unwrap_err());
}

#[test]
fn kepler_bad_coupling_and_mass() {
    invalid(
        KeplerSystem::new(&[1.0, 0.0], &[0.0, 1.0], 0.0, 1.0, NONE).unwrap_err(),
        "k",
    );
    invalid(
        KeplerSystem::new(&[1.0, 0.0], &[0.0, 1.0], 1.0, -1.0, NONE).unwrap_err(),
        "mu",
    );
}

#[test]
fn kepler_bad_perturbations() {
    let q = [1.0, 0.0];
    let p = [0.0, 1.0];
    let bad = |pert| KeplerSystem::new(&q, &p, 1.0, 1.0, pert).unwrap_err();
    invalid(bad(NONE.with_softening(-0.1)), "softening");
    invalid(bad(NONE.with_power_law(f64::NAN, 1.0)), "eps");
    invalid(bad(NONE.with_power_law(0.0, f64::INFINITY)), "c_eps");
    invalid(bad(NONE.with_post_newtonian(f64::NAN)), "c_pn");
}

#[test]
fn kepler_origin_without_softening() {
    invalid(
        KeplerSystem::new(&[0.0, 0.0], &[0.0, 1.0], 1.0, 1.0, NONE).unwrap_err(),
        "q0",
    );
    // With softening the origin is a regular point.
    assert!(
        KeplerSystem::new(&[0.0, 0.0], &[0.0, 1.0], 1.0, 1.0, NONE.with_softening(0.1)).is_ok()
    );
}

#[test]
fn kepler_bad_orbital_elements() {
    invalid(
        KeplerSystem::from_orbital_elements(-1.0, 0.1, 1.0, 1.0, NONE).unwrap_err(),
        "a",
    );
    invalid(
        KeplerSystem::from_orbital_elements(1.0, 1.0, 1.0, 1.0, NONE).unwrap_err(),
        "e",
    );
    invalid(
        KeplerSystem::from_orbital_elements(1.0, -0.1, 1.0, 1.0, NONE).unwrap_err(),
        "e",
    );
}

#[test]
fn henon_heiles_bad_input() {
    dimension(
        HenonHeilesSystem::new(&[0.0; 3], &[0.0; 2]).unwrap_err(),
        "q0",
    );
    non_finite(HenonHeilesSystem::new(&[0.0, f64::INFINITY], &[0.0; 2]).unwrap_err());
}

#[test]
fn swarm_bad_input() {
    invalid(PendulumSwarm::new(&[], &[], 1.0).unwrap_err(), "n");
    dimension(
        PendulumSwarm::new(&[0.0; 3], &[0.0; 2], 1.0).unwrap_err(),
        "p0",
    );
    invalid(
        PendulumSwarm::new(&[0.0], &[0.0], 0.0).unwrap_err(),
        "g_over_l",
    );
    invalid(
        PendulumSwarm::from_box(0.0, 0.0, -0.1, 0.1, 10, 1.0, 0).unwrap_err(),
        "dq",
    );
    invalid(
        PendulumSwarm::from_box(0.0, 0.0, 0.1, f64::NAN, 10, 1.0, 0).unwrap_err(),
        "dp",
    );
    invalid(
        PendulumSwarm::from_box(0.0, 0.0, 0.1, 0.1, 0, 1.0, 0).unwrap_err(),
        "n",
    );
    invalid(
        PendulumSwarm::from_box(f64::NAN, 0.0, 0.1, 0.1, 5, 1.0, 0).unwrap_err(),
        "q_center",
    );
}

#[test]
fn swarm_area_needs_three_points() {
    let swarm = PendulumSwarm::new(&[0.0, 1.0], &[0.0, 1.0], 1.0).unwrap();
    invalid(
        swarm
            .phase_space_area(&[0.0, 1.0], &[0.0, 1.0])
            .unwrap_err(),
        "n",
    );
    let swarm = PendulumSwarm::new(&[0.0; 4], &[0.0; 4], 1.0).unwrap();
    dimension(
        swarm.phase_space_area(&[0.0; 3], &[0.0; 4]).unwrap_err(),
        "q",
    );
    dimension(
        swarm.per_particle_energy(&[0.0; 4], &[0.0; 5]).unwrap_err(),
        "p",
    );
}

#[test]
fn projectile_bad_input() {
    invalid(
        ProjectileMotion::new(&[0.0; 2], &[0.0; 2], 0.0, 9.81, 0.0).unwrap_err(),
        "m",
    );
    invalid(
        ProjectileMotion::new(&[0.0; 2], &[0.0; 2], 1.0, -1.0, 0.0).unwrap_err(),
        "g",
    );
    invalid(
        ProjectileMotion::new(&[0.0; 2], &[0.0; 2], 1.0, 9.81, -0.1).unwrap_err(),
        "drag_coeff",
    );
    dimension(
        ProjectileMotion::new(&[0.0; 3], &[0.0; 2], 1.0, 9.81, 0.0).unwrap_err(),
        "q0",
    );
    invalid(
        ProjectileMotion::from_launch(-1.0, 45.0, 1.0, 9.81, 0.0, 0.0).unwrap_err(),
        "speed",
    );
    invalid(
        ProjectileMotion::from_launch(1.0, f64::NAN, 1.0, 9.81, 0.0, 0.0).unwrap_err(),
        "angle_deg",
    );
    invalid(
        ProjectileMotion::range_and_max_height(10.0, 45.0, 9.81, -1.0).unwrap_err(),
        "height",
    );
    non_finite(
        ProjectileMotion::analytic_trajectory(10.0, 45.0, 9.81, &[f64::NAN], 0.0).unwrap_err(),
    );
}

#[test]
fn chain_bad_input() {
    invalid(HarmonicChain::new(&[], &[], 1.0, 1.0).unwrap_err(), "n");
    invalid(
        HarmonicChain::new(&[0.0], &[0.0], 0.0, 1.0).unwrap_err(),
        "m",
    );
    invalid(
        HarmonicChain::new(&[0.0], &[0.0], 1.0, -1.0).unwrap_err(),
        "k",
    );
    dimension(
        HarmonicChain::new(&[0.0; 2], &[0.0], 1.0, 1.0).unwrap_err(),
        "p0",
    );
    invalid(FPUTChain::new(0, 1.0, 1.0, 0.7, 1, 0.5).unwrap_err(), "n");
    invalid(
        FPUTChain::new(8, 1.0, 1.0, 0.7, 0, 0.5).unwrap_err(),
        "mode",
    );
    invalid(
        FPUTChain::new(8, 1.0, 1.0, 0.7, 9, 0.5).unwrap_err(),
        "mode",
    );
    invalid(
        FPUTChain::new(8, 1.0, 1.0, f64::NAN, 1, 0.5).unwrap_err(),
        "beta",
    );
    invalid(
        FPUTChain::new(8, 1.0, 1.0, 0.7, 1, f64::INFINITY).unwrap_err(),
        "amplitude",
    );
    dimension(
        SineGordonChain::new(5, 1.0, 1.0, Some(&[0.0; 4]), None).unwrap_err(),
        "q0",
    );
    let chain = HarmonicChain::new(&[0.0; 3], &[0.0; 3], 1.0, 1.0).unwrap();
    dimension(chain.modal_energies(&[0.0; 2], &[0.0; 3]).unwrap_err(), "q");
}

#[test]
fn kink_bad_input() {
    invalid(
        SineGordonChain::kink(50, 25.0, 1.0, 1.0, 1).unwrap_err(),
        "velocity",
    );
    invalid(
        SineGordonChain::kink(50, 25.0, 1.0, -1.2, 1).unwrap_err(),
        "velocity",
    );
    invalid(
        SineGordonChain::kink(50, 25.0, 0.0, 0.2, 1).unwrap_err(),
        "width",
    );
    invalid(
        SineGordonChain::kink(50, 25.0, 1.0, 0.2, 0).unwrap_err(),
        "polarity",
    );
    invalid(
        SineGordonChain::kink(0, 25.0, 1.0, 0.2, 1).unwrap_err(),
        "n",
    );
    invalid(
        SineGordonChain::kink(50, f64::NAN, 1.0, 0.2, 1).unwrap_err(),
        "center",
    );
}

#[test]
fn action_angle_outside_libration() {
    for e in [1.0, -1.0, 2.0, -3.0, f64::NAN] {
        invalid(pendulum_action_angle(e, 1.0).unwrap_err(), "E");
    }
    invalid(pendulum_action_angle(0.0, 0.0).unwrap_err(), "g_over_l");
    invalid(ellipk(1.0).unwrap_err(), "m");
    invalid(ellipk(-0.5).unwrap_err(), "m");
}
