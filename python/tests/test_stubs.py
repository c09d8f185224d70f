"""The hand-written stub ``physicskit/_core.pyi`` matches the compiled module."""

import ast
import inspect
import pathlib

import physicskit
from physicskit import _core


def stub_defs():
    path = pathlib.Path(physicskit.__file__).with_name("_core.pyi")
    tree = ast.parse(path.read_text())
    out = {}
    for node in tree.body:
        # Private names are stub-only typing helpers (the TypedDicts of `catalog()`), not
        # attributes of the module.
        if getattr(node, "name", "").startswith("_"):
            continue
        if isinstance(node, ast.FunctionDef):
            out[node.name] = [a.arg for a in node.args.args]
        elif isinstance(node, ast.ClassDef):
            out[node.name] = None
    return out


def test_stub_names_and_parameters_match_module():
    stubs = stub_defs()
    public = {n for n in dir(_core) if not n.startswith("_")}
    assert set(stubs) == public
    for name, params in stubs.items():
        if params is None:
            continue
        sig = inspect.signature(getattr(_core, name))
        assert list(sig.parameters) == params, name


def test_py_typed_marker_present():
    assert pathlib.Path(physicskit.__file__).with_name("py.typed").exists()
