"""Shared fixtures: the archstudy command line of the same checkout, for comparisons."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def cli_path() -> pathlib.Path:
    """The `archstudy` binary: $ARCHSTUDY_BIN, else target/release/archstudy."""
    return pathlib.Path(os.environ.get("ARCHSTUDY_BIN", REPO / "target" / "release" / "archstudy"))


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    path = cli_path()
    assert path.is_file(), f"build the command line first (cargo build --release): {path}"
    return path


def cli_json(cli: pathlib.Path, *args: str) -> dict:
    """`archstudy solve ARGS --json` as a dict."""
    out = subprocess.run([str(cli), "solve", *args, "--json"], check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout)
