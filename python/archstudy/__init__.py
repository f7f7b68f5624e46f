"""archstudy: limit analysis of masonry arches with finite Coulomb friction, from Python.

The same engine as the ``archstudy`` command line, with no external solver:

* :func:`solve` answers one question about one scene (``archstudy solve``) as a
  :class:`Solution`, drawn in Jupyter as the arch with its line of thrust;
* :func:`thresholds` gives the four critical values of an arch under self-weight;
* :func:`solve_many` solves many scenes at once, in parallel, as a :class:`Table`;
* :func:`run` runs a study manifest (a path or a dict) as ``archstudy run`` does, and
  :func:`open` reads a finished run directory as a :class:`Run`.

Tables cross as Arrow data (the Arrow PyCapsule stream interface): ``pyarrow.table(t)``,
``polars.DataFrame(t)`` and pandas (through pyarrow) read them without a copy through
Python objects.
"""

from __future__ import annotations

import csv
import html
import json
import math
import os
import pathlib
import tempfile
from dataclasses import dataclass, fields
from typing import Any, Mapping, NamedTuple, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _archstudy

__version__: str = _archstudy.__version__

__all__ = [
    "Hinge",
    "ManifestError",
    "Run",
    "SlidingJoint",
    "Solution",
    "Table",
    "Thresholds",
    "open",
    "run",
    "solve",
    "solve_many",
    "thresholds",
]

ArrayLike = Union[float, int, Sequence[float], "npt.NDArray[Any]", None]
"""A number, a sequence or a NumPy array of numbers (``None``: not given)."""


class ManifestError(ValueError):
    """A study manifest that cannot be read or is not valid, as ``archstudy run`` reports
    it: ``str(e)`` is the line the command line prints (``file:line:column: key `k`:
    message``).

    Attributes:
        file: The manifest file (for a dict, the temporary manifest.yaml it was written to).
        line: 1-based line, when known.
        column: 1-based column, when known.
        key: The key at fault (dotted path), when known.
        value: The value given (as written in the manifest, quotes dropped), when the
            error is about a value; for an unknown key, the key.
        allowed: What is allowed there (all of ``message`` when it names no value).
        message: What is wrong, with the value given and what is allowed, in one sentence.
    """

    def __init__(self, text: str, file: str, line: int | None, column: int | None,
                 key: str | None, value: str | None, allowed: str, message: str) -> None:
        super().__init__(text)
        self.file = file
        self.line = line
        self.column = column
        self.key = key
        self.value = value
        self.allowed = allowed
        self.message = message


class Hinge(NamedTuple):
    """A hinge of a state: the joint's angle from the crown (degrees, positive to the
    right) and the face it turns about (``"intrados"`` or ``"extrados"``)."""

    angle_deg: float
    face: str


class SlidingJoint(NamedTuple):
    """A sliding joint of a state: its angle from the crown (degrees) and the sense in which
    the part nearer the crown slides (``"outward"`` or ``"inward"``)."""

    angle_deg: float
    sense: str


class Thresholds(NamedTuple):
    """The four critical values of an arch under self-weight (``find="thresholds"``)."""

    k_c_rotational: float | None
    """Collapse thickness K_c at μ = ∞."""
    mu_rotational_mixed: float | None
    """μ of the rotational/mixed bifurcation: the critical friction at K_c."""
    mu_min: float | None
    """μ_min: below it no thickness stands."""
    k_mixed_sliding: float | None
    """K of the mixed/sliding bifurcation: the collapse thickness at μ_min."""


_HINGE_KEYS = {"hinges", "hinges_min", "hinges_max", "collapse_hinges"}
_SLIDING_KEYS = {
    "sliding_joints",
    "sliding_joints_min",
    "sliding_joints_max",
    "collapse_sliding_joints",
}


@dataclass(frozen=True, repr=False)
class Solution:
    """The answer to one scene: every key of ``archstudy solve --json`` as an attribute
    (``None`` where a value does not exist), hinges and sliding joints as :class:`Hinge` and
    :class:`SlidingJoint` records, kinds (find, regime, mechanism, outcome) as strings.

    ``to_dict()`` gives the JSON object itself; in Jupyter the solution draws itself
    (``_repr_svg_``): the arch to scale with its line of thrust, hinges and sliding joints.
    The meaning of every key is in the README (``archstudy solve``).
    """

    find: str
    k: float | None
    t_over_r: float | None
    mu: float | None
    mu_infinite: bool
    half_angle_deg: float
    weight: str
    voussoirs: int | None
    shape: str
    eccentricity: float | None
    joints: str
    keystone: bool
    load: str
    at_deg: float | None
    at_x: float | None
    load_width: float | None
    lambda_: float | None
    outcome: str | None
    regime: str | None
    thrust_r_min: float | None
    thrust_r_max: float | None
    thrust_s_min: float | None
    thrust_s_max: float | None
    k_crit: float | None
    t_over_r_crit: float | None
    k_windows: list[tuple[float, float | None]]
    k_windows_scanned_to: float | None
    k_windows_resolution: float | None
    mu_crit: float | None
    mechanism: str | None
    thrust_over_half_weight: float | None
    crown_moment: float | None
    crown_shear: float | None
    load_factor: float | None
    load_factor_unbounded: bool
    hinges: list[Hinge]
    sliding_joints: list[SlidingJoint]
    work_loads: float | None
    work_friction: float | None
    work_residual: float | None
    mechanism_dof: int | None
    mechanism_admissible: bool | None
    gap: str | None
    collapse_value: float | None
    gap_width: float | None
    gap_searched_to: float | None
    collapse_mechanism: str | None
    collapse_hinges: list[Hinge]
    collapse_sliding_joints: list[SlidingJoint]
    collapse_lifted_joints: list[float]
    collapse_thrust_over_half_weight: float | None
    collapse_crown_shear: float | None
    collapse_crown_moment: float | None
    collapse_work_loads: float | None
    collapse_work_friction: float | None
    collapse_work_residual: float | None
    collapse_flow_violation: float | None
    critical_apex_shared: float | None
    k_c_rotational: float | None
    mu_rotational_mixed: float | None
    mu_min: float | None
    k_mixed_sliding: float | None
    thrust_min: float | None
    thrust_max: float | None
    hinges_min: list[Hinge]
    hinges_max: list[Hinge]
    sliding_joints_min: list[SlidingJoint]
    sliding_joints_max: list[SlidingJoint]
    solve_time_us: float
    _json: str
    _svg: Any

    @classmethod
    def _of(cls, text: str, svg: Any) -> Solution:
        data = json.loads(text)
        values: dict[str, Any] = {}
        for f in fields(cls):
            if f.name in ("_json", "_svg"):
                continue
            key = "lambda" if f.name == "lambda_" else f.name
            v = data[key]
            if key in _HINGE_KEYS:
                v = [Hinge(h["angle_deg"], h["face"]) for h in v]
            elif key in _SLIDING_KEYS:
                v = [SlidingJoint(s["angle_deg"], s["sense"]) for s in v]
            elif key == "k_windows":
                v = [(w[0], w[1]) for w in v]
            values[f.name] = v
        return cls(**values, _json=text, _svg=svg)

    def to_dict(self) -> dict[str, Any]:
        """The answer as the JSON object ``archstudy solve --json`` prints (key ``lambda``,
        hinges and sliding joints as objects)."""
        return dict(json.loads(self._json))

    def _repr_svg_(self) -> str:
        """The state drawing of the report: the arch to scale, its line of thrust, hinges
        and sliding joints (for a critical find its limit state, or its collapse, the first
        complete solution, when that comes first; otherwise the scene's state of largest
        margin when it stands)."""
        return str(self._svg())

    def __repr__(self) -> str:
        shown = []
        for f in fields(self):
            if f.name in ("_json", "_svg", "solve_time_us"):
                continue
            v = getattr(self, f.name)
            if v is None or v == [] or v is False and f.name != "mu_infinite":
                continue
            shown.append(f"  {f.name}={v!r},")
        return "Solution(\n" + "\n".join(shown) + "\n)"


def _options(
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
) -> dict[str, Any]:
    if voussoirs is not None and (isinstance(voussoirs, bool) or int(voussoirs) != voussoirs):
        raise ValueError(f"invalid value '{voussoirs}' for 'voussoirs': N must be an integer ≥ 1")
    return dict(
        k=None if k is None else float(k),
        t_over_r=None if t_over_r is None else float(t_over_r),
        mu=float(mu),
        half_angle=float(half_angle),
        weight=str(weight),
        voussoirs=None if voussoirs is None else int(voussoirs),
        find=str(find),
        shape=str(shape),
        eccentricity=None if eccentricity is None else float(eccentricity),
        joints=str(joints),
        keystone=bool(keystone),
        load=str(load),
        at=None if at is None else float(at),
        at_x=None if at_x is None else float(at_x),
        lambda_=None if lambda_ is None else float(lambda_),
        width=None if width is None else float(width),
    )


def solve(
    *,
    k: float | None = None,
    t_over_r: float | None = None,
    mu: float = math.inf,
    find: str = "state",
    half_angle: float = 90.0,
    weight: str = "annular",
    voussoirs: int | None = None,
    shape: str = "circular",
    eccentricity: float | None = None,
    joints: str = "radial",
    keystone: bool = False,
    load: str = "self-weight",
    at: float | None = None,
    at_x: float | None = None,
    lambda_: float | None = None,
    width: float | None = None,
) -> Solution:
    """Analyse one scene, as ``archstudy solve --json`` does.

    Args:
        k: Thickness ratio K = R/r (> 1); 1.35 when neither ``k`` nor ``t_over_r`` is given.
            A ``thickness`` or ``thresholds`` find computes K and refuses it.
        t_over_r: Thickness over centreline radius t/R_c, in (0, 2), instead of ``k``.
        mu: Friction coefficient μ ≥ 0; ``math.inf`` for infinite friction (default).
            A ``friction`` or ``thresholds`` find computes μ and refuses a finite one.
        find: ``"state"``, ``"thickness"``, ``"friction"``, ``"thrust"``, ``"thresholds"``
            or ``"load_factor"``.
        half_angle: Half-embrace angle α in degrees, in (0, 180).
        weight: Weight model, ``"annular"`` or ``"centreline"``.
        voussoirs: Number of voussoirs N ≥ 1 (``None``: the continuum).
        shape: ``"circular"`` or ``"pointed"`` (needs ``eccentricity``).
        eccentricity: e ∈ [0, 0.9999] of a pointed arch (0.5: equilateral).
        joints: Joint planes, ``"radial"`` or ``"vertical"`` (α ≤ 90°).
        keystone: The crown inside one rigid block.
        load: ``"self-weight"``, ``"horizontal"`` (a horizontal body force λ·weight) or
            ``"point"`` (a vertical point load λ·W_total on the extrados).
        at: Position of the point load, degrees from the crown (positive to the right).
        at_x: Position of the point load as x/L ∈ [0, 1], instead of ``at``.
        lambda_: Load factor λ ≥ 0 of the live load, for every find but ``load_factor``.
        width: Spread the point load uniformly over this fraction of the extrados span,
            measured horizontally and centred on its position (a patch load; α ≤ 90°).

    Returns:
        The :class:`Solution`.

    Raises:
        ValueError: A bad value, naming the keyword, the value and what is allowed.
    """
    o = _options(k, t_over_r, mu, half_angle, weight, voussoirs, find, shape, eccentricity,
                 joints, keystone, load, at, at_x, lambda_, width)
    text, svg = _archstudy.solve(*o.values())
    return Solution._of(text, svg)


def thresholds(
    *,
    half_angle: float = 90.0,
    weight: str = "annular",
    voussoirs: int | None = None,
) -> Thresholds:
    """The four critical values of a circular arch with radial joints under self-weight:
    K_c at μ = ∞, the μ of the rotational/mixed bifurcation, μ_min and the K of the
    mixed/sliding bifurcation (``find="thresholds"``).

    Args:
        half_angle: Half-embrace angle α in degrees, in (0, 180).
        weight: ``"annular"`` or ``"centreline"``.
        voussoirs: Number of voussoirs N ≥ 1 (``None``: the continuum).
    """
    s = solve(find="thresholds", half_angle=half_angle, weight=weight, voussoirs=voussoirs)
    return Thresholds(s.k_c_rotational, s.mu_rotational_mixed, s.mu_min, s.k_mixed_sliding)


class Table:
    """A table of results, one row per scene or case, with the columns of results.parquet.

    It is Arrow data: ``pyarrow.table(t)``, ``polars.DataFrame(t)`` read it through
    ``__arrow_c_stream__`` (the Arrow PyCapsule stream interface) without a copy through
    Python objects; ``to_pandas()``, ``to_polars()`` and ``to_pyarrow()`` do so when those
    packages are installed (they are not dependencies of archstudy).
    """

    def __init__(self, native: tuple[int, list[str], Any]) -> None:
        self._rows, self._names, self._stream = native

    @property
    def num_rows(self) -> int:
        """The number of rows."""
        return int(self._rows)

    @property
    def column_names(self) -> list[str]:
        """The column names, in order."""
        return list(self._names)

    def __len__(self) -> int:
        return self.num_rows

    def __arrow_c_stream__(self, requested_schema: object | None = None) -> object:
        """An Arrow C stream of the table (a PyCapsule ``arrow_array_stream``)."""
        return self._stream(requested_schema)

    def to_pyarrow(self) -> Any:
        """The table as a ``pyarrow.Table`` (needs pyarrow ≥ 14)."""
        import pyarrow as pa  # type: ignore[import-untyped]

        return pa.table(self)

    def to_pandas(self) -> Any:
        """The table as a ``pandas.DataFrame`` (through pyarrow)."""
        return self.to_pyarrow().to_pandas()

    def to_polars(self) -> Any:
        """The table as a ``polars.DataFrame``."""
        import polars as pl

        return pl.DataFrame(self)

    def column(self, name: str) -> npt.NDArray[Any]:
        """One column as a NumPy array (nulls as NaN in a float column; needs pyarrow)."""
        col = self.to_pyarrow().column(name)
        return np.asarray(col.to_numpy(zero_copy_only=False))

    def __repr__(self) -> str:
        return f"<archstudy.Table: {self.num_rows} rows × {len(self.column_names)} columns>"


_NUMBERS = ("k", "t_over_r", "mu", "half_angle", "voussoirs", "eccentricity", "at", "at_x",
            "lambda_", "width")


def solve_many(
    *,
    k: ArrayLike = None,
    t_over_r: ArrayLike = None,
    mu: ArrayLike = math.inf,
    find: str = "state",
    half_angle: ArrayLike = 90.0,
    weight: str = "annular",
    voussoirs: ArrayLike = None,
    shape: str = "circular",
    eccentricity: ArrayLike = None,
    joints: str = "radial",
    keystone: bool = False,
    load: str = "self-weight",
    at: ArrayLike = None,
    at_x: ArrayLike = None,
    lambda_: ArrayLike = None,
    width: ArrayLike = None,
    jobs: int | None = None,
) -> Table:
    """Solve many scenes at once, in parallel with the GIL released: one row per scene.

    The numeric options take NumPy arrays, sequences or scalars, broadcast together (NumPy's
    rules); NaN in an optional one (``k``, ``t_over_r``, ``voussoirs``, ``eccentricity``,
    ``at``, ``at_x``, ``lambda_``, ``width``) means "not given" for that scene. The kinds (``find``,
    ``weight``, ``shape``, ``joints``, ``keystone``, ``load``) are one for all scenes. Each
    scene is the one :func:`solve` answers for the same values; self-weight ``state`` scenes
    of a circular arch with radial joints share their thrust domains, as in ``archstudy
    run``. Ctrl-C stops it within a second (``KeyboardInterrupt``).

    Args:
        k, t_over_r, mu, half_angle, voussoirs, eccentricity, at, at_x, lambda_, width: As
            in :func:`solve`, one value or one per scene.
        find, weight, shape, joints, keystone, load: As in :func:`solve`, one for all.
        jobs: Worker threads (default: one per core).

    Returns:
        A :class:`Table` with the columns of results.parquet (``case_id`` is the row's
        index in the broadcast shape, flattened in C order).

    Raises:
        ValueError: A bad value, naming the scene (its flat index) and the keyword.
    """
    given = {"k": k, "t_over_r": t_over_r, "mu": mu, "half_angle": half_angle,
             "voussoirs": voussoirs, "eccentricity": eccentricity, "at": at, "at_x": at_x,
             "lambda_": lambda_, "width": width}
    arrays = {n: np.asarray(v, dtype=np.float64) for n, v in given.items() if v is not None}
    dims = np.broadcast_shapes(*(a.shape for a in arrays.values()))
    n = int(np.prod(dims, dtype=np.int64))
    if "voussoirs" in arrays:
        v = arrays["voussoirs"]
        bad = ~np.isnan(v) & (v != np.round(v))
        if bad.any():
            raise ValueError(
                f"invalid value '{v[bad].flat[0]}' for 'voussoirs': N must be an integer ≥ 1")
    numbers = [
        (name, np.ascontiguousarray(np.broadcast_to(a, dims), dtype=np.float64).tobytes())
        for name, a in arrays.items()
    ]
    if jobs is not None and (isinstance(jobs, bool) or int(jobs) != jobs or jobs < 1):
        raise ValueError(f"invalid value '{jobs}' for 'jobs': the number of threads must be "
                         "at least 1")
    native = _archstudy.solve_many(n, numbers, str(find), str(weight), str(shape), str(joints),
                                   bool(keystone), str(load), None if jobs is None else int(jobs))
    return Table(native)


_TABLES = {
    "results": "results.parquet",
    "boundaries": "boundaries.parquet",
    "bifurcations": "bifurcations.parquet",
    "states": "states.parquet",
    "samples": "samples.parquet",
    "estimates": "estimates.parquet",
}


class Run:
    """A finished run directory, as ``archstudy run`` writes it.

    ``results``, ``boundaries``, ``bifurcations`` and ``states`` are its tables as
    :class:`Table` (Arrow data), and for a study of uncertain parameters ``samples`` and
    ``estimates``; ``info`` is its run.json, ``dir`` its path. In Jupyter a run shows its
    name, its case counts and its figures (``_repr_html_``).
    """

    def __init__(self, run_dir: str | os.PathLike[str]) -> None:
        self.dir = pathlib.Path(run_dir)
        run_json = self.dir / "run.json"
        if not run_json.is_file():
            raise ValueError(
                f"invalid value '{self.dir}' for 'run_dir': not a run directory of archstudy "
                "run (it has no run.json)")
        self.info: dict[str, Any] = json.loads(run_json.read_text(encoding="utf-8"))

    @property
    def name(self) -> str:
        """The study's name."""
        return str(self.info["name"])

    def table(self, name: str) -> Table:
        """A stored table by name: ``results``, ``boundaries``, ``bifurcations``,
        ``states``, and for a sampling study ``samples`` and ``estimates``."""
        if name not in _TABLES:
            raise ValueError(
                f"invalid value '{name}' for 'name': one of {', '.join(_TABLES)}")
        path = self.dir / _TABLES[name]
        if not path.is_file():
            raise ValueError(
                f"invalid value '{name}' for 'name': this run has no {_TABLES[name]} "
                "(samples and estimates belong to studies of uncertain parameters)")
        return Table(_archstudy.read_table(str(path)))

    @property
    def results(self) -> Table:
        """results.parquet: one row per case."""
        return self.table("results")

    @property
    def boundaries(self) -> Table:
        """boundaries.parquet: the located regime boundaries."""
        return self.table("boundaries")

    @property
    def bifurcations(self) -> Table:
        """bifurcations.parquet: the bifurcations where boundaries meet."""
        return self.table("bifurcations")

    @property
    def states(self) -> Table:
        """states.parquet: the states the report draws."""
        return self.table("states")

    @property
    def samples(self) -> Table:
        """samples.parquet (a sampling study): every sample's values and answer."""
        return self.table("samples")

    @property
    def estimates(self) -> Table:
        """estimates.parquet (a sampling study): probabilities, fragility curves,
        quantiles and Sobol indices with their intervals."""
        return self.table("estimates")

    def figures(self) -> list[pathlib.Path]:
        """The SVG figures of the run (plots/*.svg), in name order."""
        return sorted((self.dir / "plots").glob("*.svg"))

    def key_results(self) -> list[dict[str, str]]:
        """The report's key results (tables/key-results.csv), one dict per row keyed by the
        column names (``quantity``, ``value``, ``paper``, ``difference``, ``stored in``), as
        printed; empty when the run has no such table."""
        path = self.dir / "tables" / "key-results.csv"
        if not path.is_file():
            return []
        with path.open(encoding="utf-8", newline="") as f:
            return [dict(row) for row in csv.DictReader(f)]

    def _find(self) -> str:
        """What the study computes: its find, or the question of a sampling study."""
        m = self.info.get("manifest", {})
        return str((m.get("sampling") or {}).get("question") or m.get("find"))

    def __repr__(self) -> str:
        c = self.info.get("cases", {})
        return (f"<archstudy.Run {self.name!r}: {c.get('total')} cases "
                f"({c.get('ok')} ok, {c.get('error')} failed) in {str(self.dir)!r}>")

    def _repr_html_(self) -> str:
        c = self.info.get("cases", {})
        parts = [
            f"<h3>archstudy run <code>{html.escape(self.name)}</code></h3>",
            f"<p>{c.get('total')} cases ({c.get('ok')} ok, {c.get('error')} failed); "
            f"find <code>{html.escape(self._find())}</code>; "
            f"directory <code>{html.escape(str(self.dir))}</code></p>",
        ]
        rows = self.key_results()
        if rows:
            columns = [c for c in ("quantity", "value", "paper", "difference") if c in rows[0]]
            head = "".join(f"<th>{html.escape(c)}</th>" for c in columns)
            body = "".join(
                "<tr>" + "".join(f"<td>{html.escape(r.get(c) or '')}</td>" for c in columns)
                + "</tr>" for r in rows[:_KEY_RESULT_ROWS])
            more = (f"<p>{len(rows) - _KEY_RESULT_ROWS} more in "
                    "<code>tables/key-results.csv</code></p>"
                    if len(rows) > _KEY_RESULT_ROWS else "")
            parts.append(f"<h4>Key results</h4><table><tr>{head}</tr>{body}</table>{more}")
        for f in self.figures()[:6]:
            parts.append(f"<figure><figcaption>{html.escape(f.stem)}</figcaption>"
                         f"{f.read_text(encoding='utf-8')}</figure>")
        return "\n".join(parts)


# Key results shown in a notebook (the rest stay in the table).
_KEY_RESULT_ROWS = 12


def _yaml_numbers(value: Any) -> Any:
    """A manifest with its infinite numbers written ``inf`` (JSON has no infinity)."""
    if isinstance(value, Mapping):
        return {str(k): _yaml_numbers(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_yaml_numbers(v) for v in value]
    if isinstance(value, float) and math.isinf(value):
        return "inf" if value > 0 else "-inf"
    if isinstance(value, np.generic):
        return value.item()
    return value


def run(
    manifest: str | os.PathLike[str] | Mapping[str, Any],
    *,
    out: str | os.PathLike[str] = "output",
    jobs: int | None = None,
    quiet: bool = True,
) -> Run:
    """Run a study manifest as ``archstudy run`` does: the same run directory
    ``<out>/<name>/`` with the same files, staged and moved into place when complete.

    Args:
        manifest: The path of a YAML manifest, or a dict with the manifest's keys (written
            as JSON, which is YAML, to a temporary manifest.yaml that the run copies).
        out: The directory under which ``<name>/`` is written.
        jobs: Worker threads (default: one per core).
        quiet: No progress lines on standard error.

    Returns:
        The finished :class:`Run`.

    Raises:
        ManifestError: The manifest is not valid (file, line, column, key, value, allowed,
            message).
        ValueError: A bad keyword value.
        KeyboardInterrupt: Ctrl-C; the run stops within a second and leaves no run
            directory behind.
    """
    if jobs is not None and (isinstance(jobs, bool) or int(jobs) != jobs or jobs < 1):
        raise ValueError(f"invalid value '{jobs}' for 'jobs': the number of threads must be "
                         "at least 1")
    argv = ["archstudy.run"]
    if isinstance(manifest, Mapping):
        with tempfile.TemporaryDirectory(prefix="archstudy-") as tmp:
            path = pathlib.Path(tmp) / "manifest.yaml"
            text = json.dumps(_yaml_numbers(dict(manifest)), indent=2, allow_nan=False)
            path.write_text(text + "\n", encoding="utf-8")
            answer = _archstudy.run(str(path), os.fspath(out), jobs, bool(quiet), argv)
    else:
        answer = _archstudy.run(os.fspath(manifest), os.fspath(out), jobs, bool(quiet), argv)
    if answer[0] == "manifest":
        _, file, line, column, key, (value, allowed, message), text = answer
        raise ManifestError(text, file, line, column, key, value, allowed, message)
    return Run(answer[1])


def open(run_dir: str | os.PathLike[str]) -> Run:  # noqa: A001 - the package's own verb
    """Read a finished run directory (``<out>/<name>/`` of ``archstudy run``).

    Raises:
        ValueError: The directory is not a run directory.
    """
    return Run(run_dir)
