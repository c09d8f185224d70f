"""The built-in systems of :mod:`physicskit.classical`.

The public names are those of the submodules' ``__all__`` lists, in this order; nothing is
listed twice.
"""

from . import chains, hamiltonian, lagrangian, newtonian, rolling, rotations
from .chains import *  # noqa: F401,F403
from .hamiltonian import *  # noqa: F401,F403
from .lagrangian import *  # noqa: F401,F403
from .newtonian import *  # noqa: F401,F403
from .rolling import *  # noqa: F401,F403
from .rotations import *  # noqa: F401,F403

# `+=` of each submodule's list (not one literal list of names) so that type checkers expand
# it as the interpreter does.
__all__: list[str] = []
__all__ += newtonian.__all__
__all__ += lagrangian.__all__
__all__ += hamiltonian.__all__
__all__ += chains.__all__
__all__ += rotations.__all__
__all__ += rolling.__all__
