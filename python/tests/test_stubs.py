"""The hand-written stub ``physicskit/_core.pyi`` against the compiled module.

mypy's stubtest (``bash python/dev.sh stubs``, a step of ``scripts/test``) checks every name,
parameter name, kind and default, class and property. PyO3 exposes no parameter types at run
time, so stubtest cannot check those: here every function of the stub is called with arguments
of the types the stub declares, each alternative of a union in turn. PyO3 reports an argument
it cannot convert as a ``TypeError`` noting "while processing 'name'": the stub's type is wrong;
any other outcome (a result, or a ``ValueError`` for values the function refuses) shows the
types were accepted. When a call returns, its result must have the stub's return type."""

import ast
import pathlib

import numpy as np
import pytest

import physicskit
from physicskit import _core

STUB = pathlib.Path(physicskit.__file__).with_name("_core.pyi")


def stub_functions():
    tree = ast.parse(STUB.read_text())
    return [node for node in tree.body if isinstance(node, ast.FunctionDef)]


def a_system():
    # Any built-in system; functions for another family refuse it with a ValueError.
    return _core.build("henon-heiles", {"q0": np.array([0.1, 0.0]), "p0": np.array([0.0, 0.1])})


def values_of(annotation):
    """One value of each alternative of a stub annotation."""
    samples = {
        "float": lambda: 0.5,
        "int": lambda: 3,
        "bool": lambda: True,
        "str": lambda: "rk4",
        "None": lambda: None,
        "Any": object,
        "_ArrayF64": lambda: np.array([0.1, 0.2, 0.3]),
        "dict[str, Any]": lambda: {},
        "tuple[float, float]": lambda: (0.0, 1.0),
        "list[str]": lambda: ["(* -1 y0)"],
        "NativeSystem": a_system,
        "Callable[[int, int], object]": lambda: (lambda step, n_steps: None),
        "list[NativeSystem]": lambda: [a_system()],
        "_MatrixF64": lambda: np.zeros((1, 4)),
        "list[tuple[str, _ArrayF64]]": lambda: [("q0", np.array([0.1, 0.2]))],
        "list[tuple[int, str, float]]": lambda: [(0, "crosses", 0.0)],
        "Callable[[int, int], Any]": lambda: (lambda done, total: None),
    }
    alternatives = annotation.split(" | ")
    unknown = [a for a in alternatives if a not in samples]
    assert not unknown, f"no sample value for stub type {unknown}: add one to values_of"
    return [samples[a]() for a in alternatives]


def has_type(value, annotation):
    """Whether a returned value has the stub's return type."""
    checks = {
        "float": lambda v: isinstance(v, float),
        "int": lambda v: isinstance(v, int) and not isinstance(v, bool),
        "None": lambda v: v is None,
        "NativeSystem": lambda v: isinstance(v, _core.NativeSystem),
        "_ArrayF64": lambda v: isinstance(v, np.ndarray) and v.dtype == np.float64,
        "list[_SystemInfo]": lambda v: isinstance(v, list) and all(isinstance(x, dict) for x in v),
        "list[_MethodInfo]": lambda v: isinstance(v, list) and all(isinstance(x, dict) for x in v),
        "tuple[float, float]": lambda v: isinstance(v, tuple)
        and len(v) == 2
        and all(isinstance(x, float) for x in v),
        "tuple[_ArrayF64, _ArrayF64]": lambda v: isinstance(v, tuple)
        and len(v) == 2
        and all(isinstance(x, np.ndarray) and x.dtype == np.float64 for x in v),
        "_ResultTuple": lambda v: isinstance(v, tuple) and len(v) == 6,
        "dict[str, Any]": lambda v: isinstance(v, dict),
    }
    assert annotation in checks, f"no check for stub return type {annotation}: add one"
    return checks[annotation](value)


def is_conversion_error(err):
    """Whether PyO3 raised `err` converting an argument: it adds the note "while processing
    'name'" (PyO3 0.30; older versions prefixed the message with "argument 'name': ")."""
    notes = getattr(err, "__notes__", [])
    return str(err).startswith("argument '") or any(
        n.startswith("while processing '") for n in notes
    )


@pytest.mark.parametrize("fn", stub_functions(), ids=lambda fn: fn.name)
def test_stub_parameter_types_are_accepted(fn):
    params = [(a.arg, ast.unparse(a.annotation)) for a in fn.args.args]
    returns = ast.unparse(fn.returns)
    for i, (name, annotation) in enumerate(params):
        for value in values_of(annotation):
            args = [value if j == i else values_of(ann)[0] for j, (_, ann) in enumerate(params)]
            try:
                result = getattr(_core, fn.name)(*args)
            except TypeError as err:
                assert not is_conversion_error(err), (
                    f"{fn.name}: the stub types {name} as {annotation}, "
                    f"the module refuses {value!r}: {err} {getattr(err, '__notes__', '')}"
                )
            except Exception:
                pass
            else:
                assert has_type(result, returns), f"{fn.name} returned {result!r}, stub: {returns}"


def test_py_typed_marker_present():
    assert pathlib.Path(physicskit.__file__).with_name("py.typed").exists()
