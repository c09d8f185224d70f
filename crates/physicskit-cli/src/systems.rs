//! The registry's entries: one [`SystemSpec`] per system the command line can simulate.
//!
//! Parameter names and the defaults the spec gives follow its constructors
//! (`physicskit-classical-api.txt`). Where the spec has no default (initial conditions,
//! launch speed), the default is the demonstration the issues use, so that
//! `physicskit simulate SYSTEM --dt .. --t1 .. --out ..` always runs something meaningful.
//! Systems with an alternate constructor (`from_orbital_elements`, `from_box`, `from_launch`,
//! `kink`) are registered under the demonstration's name with that constructor's parameters;
//! the plain-state constructor is registered next to them as `*-state`.

use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::systems::{
    BeadOnRotatingHoop, CoupledOscillators, CoupledOscillatorsParams, DoublePendulum,
    DoublePendulumParams, EulerTop, EulerTopParams, FPUTChain, HarmonicChain, HeavySymmetricTop,
    HenonHeilesSystem, HoopParams, KeplerPerturbations, KeplerSystem, PendulumSwarm,
    ProjectileMotion, SineGordonChain, SymmetricTopParams,
};
use physicskit::classical::Method;

use crate::registry::{Family, Kind, ParamSpec, SystemSpec, Values};
use crate::simulation::{Hamiltonian, Lagrangian, Ode, Simulation};

const ALL_METHODS: &[Method] = &Method::ALL;
/// Non-separable and non-Hamiltonian systems: the splitting methods do not apply.
const GENERAL_METHODS: &[Method] = &[Method::Rk4, Method::ImplicitMidpoint];

const fn real(name: &'static str, default: &'static str, help: &'static str) -> ParamSpec {
    ParamSpec {
        name,
        kind: Kind::Real,
        default: Some(default),
        help,
    }
}

const fn count(name: &'static str, default: &'static str, help: &'static str) -> ParamSpec {
    ParamSpec {
        name,
        kind: Kind::Count,
        default: Some(default),
        help,
    }
}

const fn list(
    name: &'static str,
    len: Option<usize>,
    default: Option<&'static str>,
    help: &'static str,
) -> ParamSpec {
    ParamSpec {
        name,
        kind: Kind::List(len),
        default,
        help,
    }
}

const fn choice(
    name: &'static str,
    words: &'static [&'static str],
    default: &'static str,
    help: &'static str,
) -> ParamSpec {
    ParamSpec {
        name,
        kind: Kind::Choice(words),
        default: Some(default),
        help,
    }
}

type Built = anyhow::Result<Box<dyn Simulation>>;

fn kepler_perturbations(v: &Values) -> anyhow::Result<KeplerPerturbations> {
    Ok(KeplerPerturbations::none()
        .with_power_law(v.real("eps")?, v.real("c_eps")?)
        .with_post_newtonian(v.real("c_pn")?)
        .with_softening(v.real("softening")?))
}

const KEPLER_PERTURBATIONS: [ParamSpec; 4] = [
    real("eps", "0.0", "exponent of the c_eps / r^(1+eps) term"),
    real("c_eps", "0.0", "coefficient of the c_eps / r^(1+eps) term"),
    real(
        "c_pn",
        "0.0",
        "coefficient of the post-Newtonian c_pn / r^3 term",
    ),
    real("softening", "0.0", "Plummer softening length, >= 0"),
];

/// `p0` given, or zeros as long as `q0`.
fn momenta_or_zeros(v: &Values, name: &str, q0: &[f64]) -> anyhow::Result<Vec<f64>> {
    Ok(v.opt_list(name)?
        .map_or_else(|| vec![0.0; q0.len()], <[f64]>::to_vec))
}

fn sine_gordon(v: &Values) -> Built {
    let n = v.count("n")?;
    let (m, k) = (v.real("m")?, v.real("k")?);
    let (width, velocity) = (v.real("width")?, v.real("velocity")?);
    // The kink centre defaults to the middle of the chain, which depends on n.
    let center = v.opt_real("center")?.unwrap_or((n as f64 - 1.0) / 2.0);
    let half = v.real("separation")? / 2.0;
    // `velocity` is in sites per unit time, below the wave speed sqrt(k/m); the library
    // returns canonical momenta (m dq/dt).
    // Sizes come from the user: every allocation of size n is the library's, which refuses
    // an n that would not fit in memory before allocating.
    let (q0, p0) = match v.choice("initial")? {
        "kink" => SineGordonChain::boosted_kink(n, m, k, center, width, velocity, 1)?,
        "antikink" => SineGordonChain::boosted_kink(n, m, k, center, width, velocity, -1)?,
        "kink-antikink" => {
            SineGordonChain::kink_antikink(n, m, k, center - half, center + half, width, velocity)?
        }
        _ => {
            return Ok(Box::new(Hamiltonian(SineGordonChain::new(
                n, m, k, None, None,
            )?)))
        }
    };
    Ok(Box::new(Hamiltonian(SineGordonChain::new(
        n,
        m,
        k,
        Some(&q0),
        Some(&p0),
    )?)))
}

/// Every registered system, in the order `list` shows them.
pub static REGISTRY: &[SystemSpec] = &[
    SystemSpec {
        name: "pendulum",
        summary: "simple pendulum H = p^2/2 - (g/l) cos q (examples::Pendulum)",
        family: Family::Hamiltonian,
        params: &[
            real("q0", "1.0", "initial angle [rad]"),
            real("p0", "0.0", "initial momentum [rad/s, unit m l^2]"),
            real("g_over_l", "1.0", "g / l [1/s^2], > 0"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            Ok(Box::new(Hamiltonian(Pendulum::new(
                v.real("q0")?,
                v.real("p0")?,
                v.real("g_over_l")?,
            )?)))
        },
    },
    SystemSpec {
        name: "harmonic-oscillator",
        summary: "harmonic oscillator H = p^2/(2m) + k q^2/2 (examples::HarmonicOscillator)",
        family: Family::Hamiltonian,
        params: &[
            real("q0", "1.0", "initial position [m]"),
            real("p0", "0.0", "initial momentum [kg m/s]"),
            real("m", "1.0", "mass [kg], > 0"),
            real("k", "1.0", "spring constant [N/m], > 0"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            Ok(Box::new(Hamiltonian(HarmonicOscillator::new(
                v.real("q0")?,
                v.real("p0")?,
                v.real("m")?,
                v.real("k")?,
            )?)))
        },
    },
    SystemSpec {
        name: "kepler",
        summary: "planar Kepler orbit from its elements, starting at perihelion \
                  (KeplerSystem::from_orbital_elements)",
        family: Family::Hamiltonian,
        params: &[
            real("a", "1.0", "semi-major axis, > 0"),
            real("e", "0.5", "eccentricity, 0 <= e < 1"),
            real("k", "1.0", "coupling k = G M mu, > 0"),
            real("mu", "1.0", "reduced mass, > 0"),
            KEPLER_PERTURBATIONS[0],
            KEPLER_PERTURBATIONS[1],
            KEPLER_PERTURBATIONS[2],
            KEPLER_PERTURBATIONS[3],
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: Some("period 2 pi sqrt(mu a^3 / k); c_pn != 0 makes the orbit precess"),
        build: |v| {
            Ok(Box::new(Hamiltonian(KeplerSystem::from_orbital_elements(
                v.real("a")?,
                v.real("e")?,
                v.real("k")?,
                v.real("mu")?,
                kepler_perturbations(v)?,
            )?)))
        },
    },
    SystemSpec {
        name: "kepler-state",
        summary: "planar Kepler problem from a position and momentum (KeplerSystem::new)",
        family: Family::Hamiltonian,
        params: &[
            list(
                "q0",
                Some(2),
                Some("1,0"),
                "initial relative position (x, y)",
            ),
            list("p0", Some(2), Some("0,1"), "initial momentum (p_x, p_y)"),
            real("k", "1.0", "coupling k = G M mu, > 0"),
            real("mu", "1.0", "reduced mass, > 0"),
            KEPLER_PERTURBATIONS[0],
            KEPLER_PERTURBATIONS[1],
            KEPLER_PERTURBATIONS[2],
            KEPLER_PERTURBATIONS[3],
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            Ok(Box::new(Hamiltonian(KeplerSystem::new(
                v.list("q0")?,
                v.list("p0")?,
                v.real("k")?,
                v.real("mu")?,
                kepler_perturbations(v)?,
            )?)))
        },
    },
    SystemSpec {
        name: "henon-heiles",
        summary: "Henon-Heiles H = |p|^2/2 + (x^2 + y^2)/2 + x^2 y - y^3/3 (HenonHeilesSystem)",
        family: Family::Hamiltonian,
        params: &[
            list("q0", Some(2), Some("0,0.3"), "initial position (x, y)"),
            list("p0", Some(2), Some("0.3,0"), "initial momentum (p_x, p_y)"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: Some("orbits are bounded for E < 1/6"),
        build: |v| {
            Ok(Box::new(Hamiltonian(HenonHeilesSystem::new(
                v.list("q0")?,
                v.list("p0")?,
            )?)))
        },
    },
    SystemSpec {
        name: "pendulum-swarm",
        summary: "n independent pendulums filling a box in phase space \
                  (PendulumSwarm::from_box)",
        family: Family::Hamiltonian,
        params: &[
            real("q_center", "1.0", "centre angle of the box [rad]"),
            real("p_center", "0.0", "centre momentum of the box"),
            real("dq", "0.05", "box width in q, >= 0"),
            real("dp", "0.05", "box height in p, >= 0"),
            count("n", "1000", "number of pendulums, >= 1"),
            real("g_over_l", "1.0", "g / l [1/s^2], > 0"),
            count("seed", "0", "seed of the reproducible uniform fill"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: Some("q and p have one column per pendulum; use --stride for long runs"),
        build: |v| {
            Ok(Box::new(Hamiltonian(PendulumSwarm::from_box(
                v.real("q_center")?,
                v.real("p_center")?,
                v.real("dq")?,
                v.real("dp")?,
                v.count("n")?,
                v.real("g_over_l")?,
                v.count("seed")? as u64,
            )?)))
        },
    },
    SystemSpec {
        name: "pendulum-swarm-state",
        summary: "independent pendulums from explicit angles and momenta (PendulumSwarm::new)",
        family: Family::Hamiltonian,
        params: &[
            list("q0", None, Some("1,1.05,1,1.05"), "initial angles [rad]"),
            list(
                "p0",
                None,
                Some("0,0,0.05,0.05"),
                "initial momenta, same length as q0",
            ),
            real("g_over_l", "1.0", "g / l [1/s^2], > 0"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            Ok(Box::new(Hamiltonian(PendulumSwarm::new(
                v.list("q0")?,
                v.list("p0")?,
                v.real("g_over_l")?,
            )?)))
        },
    },
    SystemSpec {
        name: "projectile",
        summary: "projectile launched from (0, height), optional quadratic drag \
                  (ProjectileMotion::from_launch)",
        family: Family::Hamiltonian,
        params: &[
            real("speed", "20.0", "launch speed [m/s], >= 0"),
            real(
                "angle_deg",
                "45.0",
                "launch angle above the horizontal [deg]",
            ),
            real("m", "1.0", "mass [kg], > 0"),
            real("g", "9.81", "gravitational acceleration [m/s^2], > 0"),
            real(
                "drag_coeff",
                "0.0",
                "quadratic drag coefficient c [kg/m], >= 0",
            ),
            real("height", "0.0", "launch height [m]"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: Some("with drag_coeff > 0 only rk4 (then the default) and implicit_midpoint apply"),
        build: |v| {
            Ok(Box::new(Hamiltonian(ProjectileMotion::from_launch(
                v.real("speed")?,
                v.real("angle_deg")?,
                v.real("m")?,
                v.real("g")?,
                v.real("drag_coeff")?,
                v.real("height")?,
            )?)))
        },
    },
    SystemSpec {
        name: "projectile-state",
        summary: "projectile from a position and momentum (ProjectileMotion::new)",
        family: Family::Hamiltonian,
        params: &[
            list("q0", Some(2), Some("0,0"), "initial position (x, y) [m]"),
            list(
                "p0",
                Some(2),
                Some("10,10"),
                "initial momentum m v [kg m/s]",
            ),
            real("m", "1.0", "mass [kg], > 0"),
            real("g", "9.81", "gravitational acceleration [m/s^2], > 0"),
            real(
                "drag_coeff",
                "0.0",
                "quadratic drag coefficient c [kg/m], >= 0",
            ),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: Some("with drag_coeff > 0 only rk4 (then the default) and implicit_midpoint apply"),
        build: |v| {
            Ok(Box::new(Hamiltonian(ProjectileMotion::new(
                v.list("q0")?,
                v.list("p0")?,
                v.real("m")?,
                v.real("g")?,
                v.real("drag_coeff")?,
            )?)))
        },
    },
    SystemSpec {
        name: "harmonic-chain",
        summary: "masses and linear springs between fixed walls (HarmonicChain)",
        family: Family::Hamiltonian,
        params: &[
            list(
                "q0",
                None,
                Some("0.1,0,0,0,0,0,0,0"),
                "initial displacements; the chain has one mass per entry",
            ),
            list(
                "p0",
                None,
                None,
                "initial momenta, same length as q0 [default: zeros]",
            ),
            real("m", "1.0", "mass of each particle, > 0"),
            real("k", "1.0", "spring constant, > 0"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            let q0 = v.list("q0")?;
            let p0 = momenta_or_zeros(v, "p0", q0)?;
            Ok(Box::new(Hamiltonian(HarmonicChain::new(
                q0,
                &p0,
                v.real("m")?,
                v.real("k")?,
            )?)))
        },
    },
    SystemSpec {
        name: "fput",
        summary: "Fermi-Pasta-Ulam-Tsingou beta chain started in one normal mode (FPUTChain)",
        family: Family::Hamiltonian,
        params: &[
            count("n", "32", "number of masses, >= 1"),
            real("m", "1.0", "mass of each particle, > 0"),
            real("k", "1.0", "linear spring constant, > 0"),
            real(
                "beta",
                "0.0",
                "quartic coupling, V(r) = k r^2/2 + beta r^4/4",
            ),
            count("mode", "1", "initially excited mode, 1..n"),
            real("amplitude", "1.0", "amplitude of the initial mode shape"),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: Some("the recurrence shows with e.g. --beta 0.7 --amplitude 0.5"),
        build: |v| {
            Ok(Box::new(Hamiltonian(FPUTChain::new(
                v.count("n")?,
                v.real("m")?,
                v.real("k")?,
                v.real("beta")?,
                v.count("mode")?,
                v.real("amplitude")?,
            )?)))
        },
    },
    SystemSpec {
        name: "sine-gordon",
        summary: "discrete sine-Gordon chain with kink initial data \
                  (SineGordonChain::kink, free ends)",
        family: Family::Hamiltonian,
        params: &[
            count("n", "200", "number of sites, >= 1"),
            real("m", "1.0", "mass of each site, > 0"),
            real("k", "1.0", "coupling constant, > 0"),
            choice(
                "initial",
                &["kink-antikink", "kink", "antikink", "rest"],
                "kink-antikink",
                "initial data: a colliding kink-antikink pair, one (anti)kink, or rest",
            ),
            list(
                "center",
                Some(1),
                None,
                "centre site [default: the middle, (n-1)/2]",
            ),
            real("separation", "60.0", "kink-antikink distance in sites"),
            real(
                "width",
                "1.0",
                "kink width; sqrt(k) for a true soliton, > 0",
            ),
            real(
                "velocity",
                "0.2",
                "kink speed in sites per unit time, |v| < sqrt(k/m) (the pair approaches)",
            ),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: sine_gordon,
    },
    SystemSpec {
        name: "sine-gordon-state",
        summary: "discrete sine-Gordon chain from explicit displacements (SineGordonChain::new)",
        family: Family::Hamiltonian,
        params: &[
            count("n", "200", "number of sites, >= 1"),
            real("m", "1.0", "mass of each site, > 0"),
            real("k", "1.0", "coupling constant, > 0"),
            list(
                "q0",
                None,
                None,
                "initial displacements, length n [default: zeros]",
            ),
            list(
                "p0",
                None,
                None,
                "initial momenta, length n [default: zeros]",
            ),
        ],
        methods: ALL_METHODS,
        default_method: Method::Yoshida4,
        note: None,
        build: |v| {
            Ok(Box::new(Hamiltonian(SineGordonChain::new(
                v.count("n")?,
                v.real("m")?,
                v.real("k")?,
                v.opt_list("q0")?,
                v.opt_list("p0")?,
            )?)))
        },
    },
    SystemSpec {
        name: "double-pendulum",
        summary: "planar double pendulum, angles from the downward vertical (DoublePendulum)",
        family: Family::Lagrangian,
        params: &[
            list("theta0", Some(2), Some("2.0,1.0"), "initial angles [rad]"),
            list(
                "thetadot0",
                Some(2),
                Some("0.5,-0.3"),
                "initial angular velocities [rad/s]",
            ),
            real("m1", "1.0", "upper mass [kg], > 0"),
            real("m2", "1.0", "lower mass [kg], > 0"),
            real("l1", "1.0", "upper rod length [m], > 0"),
            real("l2", "1.0", "lower rod length [m], > 0"),
            real("g", "9.81", "gravitational acceleration [m/s^2]"),
        ],
        methods: GENERAL_METHODS,
        default_method: Method::ImplicitMidpoint,
        note: Some("p holds thetadot, as in the spec"),
        build: |v| {
            let params = DoublePendulumParams {
                m1: v.real("m1")?,
                m2: v.real("m2")?,
                l1: v.real("l1")?,
                l2: v.real("l2")?,
                g: v.real("g")?,
            };
            Ok(Box::new(Lagrangian(DoublePendulum::new(
                v.list("theta0")?,
                v.list("thetadot0")?,
                params,
            )?)))
        },
    },
    SystemSpec {
        name: "hoop",
        summary: "bead on a hoop rotating about its vertical diameter (BeadOnRotatingHoop)",
        family: Family::Lagrangian,
        params: &[
            real("theta0", "0.3", "initial polar angle on the hoop [rad]"),
            real("thetadot0", "0.0", "initial angular velocity [rad/s]"),
            real("R", "1.0", "hoop radius [m], > 0"),
            real("omega", "2.0", "rotation rate [rad/s]"),
            real("g", "9.81", "gravitational acceleration [m/s^2]"),
        ],
        methods: GENERAL_METHODS,
        default_method: Method::ImplicitMidpoint,
        note: Some("critical speed omega_c = sqrt(g/R); p holds thetadot"),
        build: |v| {
            let params = HoopParams {
                r: v.real("R")?,
                omega: v.real("omega")?,
                g: v.real("g")?,
            };
            Ok(Box::new(Lagrangian(BeadOnRotatingHoop::new(
                v.real("theta0")?,
                v.real("thetadot0")?,
                params,
            )?)))
        },
    },
    SystemSpec {
        name: "coupled-oscillators",
        summary: "n masses and springs between fixed walls, Lagrangian form \
                  (CoupledOscillators)",
        family: Family::Lagrangian,
        params: &[
            list(
                "q0",
                None,
                Some("0.1,-0.2,0.15"),
                "initial displacements, length n",
            ),
            list(
                "qdot0",
                None,
                None,
                "initial velocities, length n [default: zeros]",
            ),
            count("n", "3", "number of masses, >= 1"),
            real("m", "1.0", "mass of each particle, > 0"),
            real("k", "1.0", "spring constant, > 0"),
        ],
        methods: GENERAL_METHODS,
        default_method: Method::ImplicitMidpoint,
        note: Some("p holds qdot, as in the spec"),
        build: |v| {
            let q0 = v.list("q0")?;
            let qdot0 = momenta_or_zeros(v, "qdot0", q0)?;
            let params = CoupledOscillatorsParams {
                n: v.count("n")?,
                m: v.real("m")?,
                k: v.real("k")?,
            };
            Ok(Box::new(Lagrangian(CoupledOscillators::new(
                q0, &qdot0, params,
            )?)))
        },
    },
    SystemSpec {
        name: "heavy-top",
        summary: "heavy symmetric top on a fixed point, Euler angles (phi, theta, psi) \
                  (HeavySymmetricTop)",
        family: Family::Lagrangian,
        params: &[
            list(
                "angles0",
                Some(3),
                Some("0,0.5,0"),
                "initial (phi, theta, psi) [rad]",
            ),
            list(
                "angledots0",
                Some(3),
                Some("0,0,20"),
                "initial rates (phidot, thetadot, psidot) [rad/s]",
            ),
            real(
                "I1",
                "1.0",
                "transverse moment of inertia about the pivot, > 0",
            ),
            real("I3", "0.5", "axial moment of inertia, > 0"),
            real("M", "1.0", "mass [kg], > 0"),
            real("l", "1.0", "pivot to centre of mass [m], > 0"),
            real("g", "9.81", "gravitational acceleration [m/s^2]"),
        ],
        methods: GENERAL_METHODS,
        default_method: Method::ImplicitMidpoint,
        note: Some("p holds the angle rates, as in the spec"),
        build: |v| {
            let params = SymmetricTopParams {
                i1: v.real("I1")?,
                i3: v.real("I3")?,
                m: v.real("M")?,
                l: v.real("l")?,
                g: v.real("g")?,
            };
            Ok(Box::new(Lagrangian(HeavySymmetricTop::new(
                v.list("angles0")?,
                v.list("angledots0")?,
                params,
            )?)))
        },
    },
    SystemSpec {
        name: "euler-top",
        summary: "torque-free rigid body: Euler's equations and the orientation quaternion \
                  (EulerTop)",
        family: Family::Ode,
        params: &[
            list(
                "omega0",
                Some(3),
                Some("0.01,1,0.01"),
                "initial body angular velocity [rad/s]",
            ),
            real("I1", "1.0", "principal moment 1, > 0"),
            real("I2", "2.0", "principal moment 2, > 0"),
            real("I3", "3.0", "principal moment 3, > 0"),
            list(
                "quat0",
                Some(4),
                None,
                "initial orientation (w, x, y, z) [default: identity]",
            ),
        ],
        methods: GENERAL_METHODS,
        default_method: Method::ImplicitMidpoint,
        note: Some("y columns: w1, w2, w3, qw, qx, qy, qz; spin near axis 2 to see the flips"),
        build: |v| {
            let params = EulerTopParams {
                i1: v.real("I1")?,
                i2: v.real("I2")?,
                i3: v.real("I3")?,
            };
            Ok(Box::new(Ode(EulerTop::new(
                v.list("omega0")?,
                params,
                v.opt_list("quat0")?,
            )?)))
        },
    },
];
