"""physicskit.classical: classical mechanics on structure-preserving integrators.

Newtonian, Lagrangian, Hamiltonian, lattice-chain and rigid-body systems, integrated by the
Rust core (the spec's ``yoshida4``, ``verlet``, ``rk4``, ``implicit_midpoint``, and the
higher-order methods :func:`methods` lists). Every built-in system's
numerics run natively with the GIL released; systems written in Python by subclassing
:class:`HamiltonianSystem`, :class:`LagrangianSystem` or :class:`ODESystem` run on the same
integrators.
"""

from .. import __version__
from .._core import ConvergenceError
from .core import (
    DynamicalSystem,
    HamiltonianSystem,
    LagrangianSystem,
    ODESystem,
    SimulationResult,
)
from .systems.newtonian import *  # noqa: F401,F403
from .systems.lagrangian import *  # noqa: F401,F403
from .systems.hamiltonian import *  # noqa: F401,F403
from .systems.chains import *  # noqa: F401,F403
from .systems.rotations import *  # noqa: F401,F403
from .systems.rolling import *  # noqa: F401,F403
from .listings import catalog, methods
from .ensembles import EnsembleResult, abs_above, crossing, ensemble
from .chaos import *  # noqa: F401,F403
from . import chaos, core, systems, utils  # noqa: E402  (sub-packages importable as attributes)

__all__ = [
    "__version__",
    "DynamicalSystem",
    "ODESystem",
    "HamiltonianSystem",
    "LagrangianSystem",
    "SimulationResult",
]
__all__ += systems.__all__
__all__ += ["ConvergenceError", "methods", "catalog"]
__all__ += chaos.__all__
__all__ += ["ensemble", "EnsembleResult", "crossing", "abs_above"]
