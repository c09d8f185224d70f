"""The public API of ``physicskit.classical`` as the spec (physicskit-classical-api.txt) states
it, transcribed by hand: constructor and function signatures (parameter names and defaults),
base classes, methods with their signatures, properties and class attributes.

``_`` marks a parameter without a default. Kept separate from the tests so that a reviewer
can check it line by line against the spec text.
"""

_ = object()  # "no default"

# name -> (signature, base class name, {method: signature}, properties, {class attr: value},
#          kind of method: "static"/"class" in a separate dict)
CLASSES = {
    "BeadOnRotatingHoop": dict(
        sig=[("theta0", _), ("thetadot0", _), ("R", 1.0), ("omega", 2.0), ("g", 9.81)],
        base="LagrangianSystem",
        methods={"energy": [("state", None)]},
    ),
    "CoupledOscillators": dict(
        sig=[("q0", _), ("qdot0", _), ("n", 3), ("m", 1.0), ("k", 1.0)],
        base="LagrangianSystem",
        methods={"energy": [("state", None)]},
    ),
    "DoublePendulum": dict(
        sig=[("theta0", _), ("thetadot0", _), ("m1", 1.0), ("m2", 1.0), ("l1", 1.0),
             ("l2", 1.0), ("g", 9.81)],
        base="LagrangianSystem",
        methods={"energy": [("state", None)], "positions": [("q", None)]},
    ),
    "DynamicalSystem": dict(
        sig=[("state0", _)],
        base="ABC",
        methods={
            "derivatives": [("t", _), ("state", _)],
            "energy": [("state", None)],
            "integrate": [("t_span", _), ("dt", _), ("method", "rk4")],
            "reset": [("state0", None), ("t0", 0.0)],
        },
        abstract={"derivatives", "energy", "integrate"},
    ),
    "EulerTop": dict(
        sig=[("omega0", _), ("I1", 1.0), ("I2", 2.0), ("I3", 3.0), ("quat0", None)],
        base="ODESystem",
        methods={
            "angular_momentum_squared": [("state", None)],
            "energy": [("state", None)],
            "rotation_matrix": [("state", None)],
        },
        properties={"omega", "quaternion"},
    ),
    "FPUTChain": dict(
        sig=[("n", 32), ("m", 1.0), ("k", 1.0), ("beta", 0.0), ("mode", 1), ("amplitude", 1.0)],
        base="_ChainBase",
        methods={"potential_energy": [("q", _)]},
    ),
    "HamiltonianSystem": dict(
        sig=[("q0", _), ("p0", _)],
        base="DynamicalSystem",
        methods={
            "derivatives": [("t", _), ("state", _)],
            "energy": [("state", None)],
            "force": [("q", _), ("t", 0.0)],
            "integrate": [("t_span", _), ("dt", _), ("method", "yoshida4")],
            "kinetic_energy": [("p", _)],
            "potential_energy": [("q", _)],
        },
        static={"split": [("state", _), ("ndof", _)]},
        properties={"q", "p"},
        attrs={"mass_inv": 1.0, "ndof": 0, "separable": True},
        abstract={"kinetic_energy", "potential_energy"},
    ),
    "HarmonicChain": dict(
        sig=[("q0", _), ("p0", _), ("m", 1.0), ("k", 1.0)],
        base="_ChainBase",
        methods={"potential_energy": [("q", _)]},
    ),
    "HeavySymmetricTop": dict(
        sig=[("angles0", _), ("angledots0", _), ("I1", 1.0), ("I3", 0.5), ("M", 1.0),
             ("l", 1.0), ("g", 9.81)],
        base="LagrangianSystem",
        methods={"energy": [("state", None)], "precession_nutation_rate": [("state", None)]},
    ),
    "HenonHeilesSystem": dict(
        sig=[("q0", _), ("p0", _)],
        base="HamiltonianSystem",
        methods={"kinetic_energy": [("p", _)], "potential_energy": [("q", _)]},
        attrs={"mass_inv": 1.0, "separable": True},
    ),
    "KeplerSystem": dict(
        sig=[("q0", _), ("p0", _), ("k", 1.0), ("mu", 1.0), ("eps", 0.0), ("c_eps", 0.0),
             ("c_pn", 0.0), ("softening", 0.0)],
        base="HamiltonianSystem",
        methods={
            "angular_momentum": [("q", None), ("p", None)],
            "kinetic_energy": [("p", _)],
            "lrl_vector": [("q", None), ("p", None)],
            "potential_energy": [("q", _)],
        },
        classmethods={"from_orbital_elements": [("a", _), ("e", _), ("k", 1.0), ("mu", 1.0),
                                                ("**kwargs", _)]},
        attrs={"separable": True},
    ),
    "LagrangianSystem": dict(
        sig=[("q0", _), ("qdot0", _)],
        base="DynamicalSystem",
        methods={
            "acceleration": [("q", _), ("qdot", _), ("t", _)],
            "derivatives": [("t", _), ("state", _)],
            "energy": [("state", None)],
            "integrate": [("t_span", _), ("dt", _), ("method", "implicit_midpoint")],
            "momentum": [("q", _), ("qdot", _)],
        },
        static={"split": [("state", _), ("ndof", _)]},
        properties={"q", "qdot"},
        attrs={"ndof": 0},
        abstract={"energy"},
    ),
    "ODESystem": dict(
        sig=[("state0", _)],
        base="DynamicalSystem",
        methods={
            "derivatives": [("t", _), ("state", _)],
            "integrate": [("t_span", _), ("dt", _), ("method", "implicit_midpoint")],
        },
    ),
    "PendulumSwarm": dict(
        sig=[("q0", _), ("p0", _), ("g_over_l", 1.0)],
        base="HamiltonianSystem",
        methods={
            "kinetic_energy": [("p", _)],
            "per_particle_energy": [("q", None), ("p", None)],
            "phase_space_area": [("q", None), ("p", None)],
            "potential_energy": [("q", _)],
        },
        classmethods={"from_box": [("q_center", _), ("p_center", _), ("dq", _), ("dp", _),
                                   ("n", 1000), ("g_over_l", 1.0), ("seed", 0)]},
        attrs={"separable": True},
    ),
    "ProjectileMotion": dict(
        sig=[("q0", _), ("p0", _), ("m", 1.0), ("g", 9.81), ("drag_coeff", 0.0)],
        base="HamiltonianSystem",
        methods={
            "integrate": [("t_span", _), ("dt", _), ("method", "yoshida4")],
            "kinetic_energy": [("p", _)],
            "potential_energy": [("q", _)],
        },
        static={
            "analytic_trajectory": [("speed", _), ("angle_deg", _), ("g", _), ("t", _),
                                    ("height", 0.0)],
            "range_and_max_height": [("speed", _), ("angle_deg", _), ("g", _), ("height", 0.0)],
        },
        classmethods={"from_launch": [("speed", _), ("angle_deg", _), ("m", 1.0), ("g", 9.81),
                                      ("drag_coeff", 0.0), ("height", 0.0)]},
        attrs={"separable": True},
    ),
    "SineGordonChain": dict(
        sig=[("n", 200), ("m", 1.0), ("k", 1.0), ("q0", None), ("p0", None)],
        base="_ChainBase",
        methods={"potential_energy": [("q", _)]},
        static={"kink": [("n", _), ("center", _), ("width", 1.0), ("velocity", 0.0),
                         ("polarity", 1)]},
    ),
}

FUNCTIONS = {
    "effective_potential_symmetric_top": [("theta", _), ("p_phi", _), ("p_psi", _), ("I1", _),
                                          ("I3", _), ("Mgl", _)],
    "find_theta_equilibrium": [("p_phi", _), ("p_psi", _), ("I1", _), ("I3", _), ("Mgl", _),
                               ("bracket", (0.001, 3.1405926535897932))],
    "nutation_frequency": [("p_phi", _), ("p_psi", _), ("I1", _), ("I3", _), ("Mgl", _),
                           ("theta_eq", None), ("dtheta", 1e-05)],
    "pendulum_action_angle": [("E", _), ("g_over_l", 1.0)],
    "precession_frequency": [("p_phi", _), ("p_psi", _), ("I1", _), ("theta_eq", _)],
}

# SimulationResult(t, y, q=None, p=None, energy=None, method='', extra=<factory>)
SIMULATION_RESULT = [("t", _), ("y", _), ("q", None), ("p", None), ("energy", None),
                     ("method", ""), ("extra", "<factory>")]

# _ChainBase (documented through its subclasses' bases): methods every chain offers.
CHAIN_BASE_METHODS = {
    "kinetic_energy": [("p", _)],
    "modal_energies": [("q", None), ("p", None)],
    "normal_mode_coords": [("q", None), ("p", None)],
    "normal_mode_frequencies": [],
}
