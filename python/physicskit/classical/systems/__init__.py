"""The built-in systems of :mod:`physicskit.classical`."""

from .chains import FPUTChain, HarmonicChain, SineGordonChain
from .hamiltonian import HenonHeilesSystem, PendulumSwarm, pendulum_action_angle
from .lagrangian import BeadOnRotatingHoop, CoupledOscillators, DoublePendulum
from .newtonian import KeplerSystem, ProjectileMotion
from .rotations import (
    EulerTop,
    HeavySymmetricTop,
    effective_potential_symmetric_top,
    find_theta_equilibrium,
    nutation_frequency,
    precession_frequency,
)

__all__ = [
    "ProjectileMotion", "KeplerSystem", "DoublePendulum", "BeadOnRotatingHoop",
    "CoupledOscillators", "HenonHeilesSystem", "PendulumSwarm", "pendulum_action_angle",
    "HarmonicChain", "FPUTChain", "SineGordonChain", "EulerTop", "HeavySymmetricTop",
    "effective_potential_symmetric_top", "find_theta_equilibrium", "nutation_frequency",
    "precession_frequency",
]
