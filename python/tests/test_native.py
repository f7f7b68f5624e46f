"""The native module describes its own signatures, so that stubtest compares them with the
stubs (a function without a text signature is skipped by stubtest)."""

from __future__ import annotations

import ast
import inspect
import pathlib

import archstudy
from archstudy import _archstudy


def stub_parameters() -> dict[str, list[str]]:
    path = pathlib.Path(archstudy.__file__).with_name("_archstudy.pyi")
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return {
        f.name: [a.arg for a in f.args.posonlyargs + f.args.args]
        for f in tree.body
        if isinstance(f, ast.FunctionDef)
    }


def test_every_native_function_has_the_signature_of_its_stub():
    stubs = stub_parameters()
    assert set(stubs) == {"solve", "solve_many", "run", "read_table"}
    for name, params in stubs.items():
        sig = inspect.signature(getattr(_archstudy, name))
        assert list(sig.parameters) == params, name
        assert all(p.kind is p.POSITIONAL_ONLY for p in sig.parameters.values()), name
