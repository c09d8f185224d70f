"""physicskit: classical mechanics on fast structure-preserving integrators.

The numerics are written in Rust (the ``physicskit`` crate) and reached through the
extension module ``physicskit._core``; the public API is :mod:`physicskit.classical`.
"""

__version__ = "0.1.0"

__all__ = ["__version__"]
