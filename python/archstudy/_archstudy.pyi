"""The native module of archstudy (Rust): use the functions of ``archstudy``.

Its functions take their arguments by position, in the order ``archstudy`` passes them.
"""

from typing import Any, Callable

__all__ = ["solve", "solve_many", "run", "read_table", "__version__"]
__version__: str

_Table = tuple[int, list[str], Callable[..., Any]]

def solve(
    k: float | None,
    t_over_r: float | None,
    mu: float,
    half_angle: float,
    weight: str,
    voussoirs: int | None,
    find: str,
    shape: str,
    eccentricity: float | None,
    joints: str,
    keystone: bool,
    load: str,
    at: float | None,
    at_x: float | None,
    lambda_: float | None,
    width: float | None,
    /,
) -> tuple[str, Callable[[], str]]: ...
def solve_many(
    n: int,
    numbers: list[tuple[str, bytes]],
    find: str,
    weight: str,
    shape: str,
    joints: str,
    keystone: bool,
    load: str,
    jobs: int | None,
    /,
) -> _Table: ...
def run(
    study: str, out: str, jobs: int | None, quiet: bool, command_line: list[str], /
) -> tuple[Any, ...]: ...
def read_table(path: str, /) -> _Table: ...
