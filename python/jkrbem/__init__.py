"""jkrbem from Python: JKR-type adhesive contact of a rigid indenter with an elastic half-space,
by the FFT-based boundary element method with the Pohrt–Popov detachment criterion.

Units: give lengths in any unit L, the effective modulus ``e_star`` in F/L² and the work of
adhesion ``work_of_adhesion`` in F/L; dimensional results come out in L and F. Normalised
results (suffix ``_bar``) use Re = √(R1 R2) and c_r = (9π Re² Δγ / (4E*))^(1/3):
c̄ = c/c_r, F̄ = F/(3π Re Δγ), d̄ = d·Re/c_r². For a sphere JKR gives |min F̄| = 1/2.

>>> import jkrbem
>>> r = jkrbem.simulate(ratio=1, grid=64, backend="cpu")
>>> round(r.adhesive_force, 2)
0.5
"""

from __future__ import annotations

import inspect
import json
import math
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _check, _jkrbem, _request
from ._jkrbem import InputError, SolveError

__version__ = _jkrbem.__version__

__all__ = [
    "simulate",
    "batch",
    "pulloff",
    "plan",
    "sweep",
    "sweep_results",
    "crossed",
    "theory",
    "reference_table",
    "devices",
    "Result",
    "Fields",
    "InputError",
    "SolveError",
    "STATE_COLUMNS",
]

#: The columns of :attr:`Result.states`, as in the CLI's states CSV (without ``onsets``).
STATE_COLUMNS: Tuple[Tuple[str, str], ...] = (
    ("step", "i8"),
    ("phase", "U8"),
    ("d", "f8"),
    ("force", "f8"),
    ("area", "f8"),
    ("mean_radius", "f8"),
    ("a_axis", "f8"),
    ("b_axis", "f8"),
    ("n_contact", "i8"),
    ("cg_iterations", "i8"),
    ("detach_sweeps", "i8"),
    ("d_bar", "f8"),
    ("f_bar", "f8"),
    ("c_bar", "f8"),
    ("a_bar", "f8"),
    ("b_bar", "f8"),
    ("cg_residual", "f8"),
    ("dx", "f8"),
)


def _states_array(states: List[Dict[str, Any]]) -> np.ndarray:
    """The states (dicts from the solver) as a numpy structured array."""
    dtype = np.dtype(list(STATE_COLUMNS))
    rows = [
        tuple(
            (s[name].lower() if isinstance(s[name], str) else s[name])
            if s.get(name) is not None
            else (math.nan if kind == "f8" else -1)
            for name, kind in STATE_COLUMNS
        )
        for s in states
    ]
    return np.array(rows, dtype=dtype)


@dataclass
class Run:
    """One grid's pull-off: its grid, element side and states."""

    #: Elements along x and y.
    grid: Tuple[int, int]
    #: Element side Δx at the start (length).
    dx: float
    #: Whether it reached its end (or its confirmed force minimum).
    complete: bool
    #: Every recorded state, a structured array with :data:`STATE_COLUMNS`.
    states: np.ndarray


@dataclass
class Fields:
    """The fields of one state on its grid. 2-D arrays have shape (ny, nx): ``a[j, i]`` is
    the element at ``x[i]``, ``y[j]``. Each field is the state's contact set solved again on
    the CPU (f64) at its approach."""

    #: Which run (0: the first grid run) and which of its states (0: the first press).
    run: int
    index: int
    #: Why it was kept ("force minimum", "state 12").
    label: str
    #: The state (a dict with the states' columns).
    state: Dict[str, Any]
    #: Element centres from the apex (length).
    x: np.ndarray
    y: np.ndarray
    #: Contact pressure p (force/length², compressive positive; 0 off the contact).
    pressure: np.ndarray
    #: Gap g = h − d + u (length; 0 on the contact).
    gap: np.ndarray
    #: The contact set.
    contact: np.ndarray
    #: Element side (length) and detachment stress σ_c (force/length²).
    dx: float
    sigma_c: float

    @property
    def force(self) -> float:
        """Σ p Δx² (force): the state's force."""
        return float(self.pressure.sum() * self.dx * self.dx)

    def plot(self, ax=None):
        """The pressure as a heat map with the contact's outline (needs matplotlib)."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots()
        h = 0.5 * self.dx
        extent = (self.x[0] - h, self.x[-1] + h, self.y[0] - h, self.y[-1] + h)
        scale = float(np.abs(self.pressure).max()) or 1.0
        im = ax.imshow(self.pressure, origin="lower", extent=extent, cmap="bwr",
                       vmin=-scale, vmax=scale)
        ax.contour(self.x, self.y, self.contact.astype(float), levels=[0.5], colors="k", linewidths=0.8)
        ax.set_xlabel("x (length)")
        ax.set_ylabel("y (length)")
        ax.set_aspect("equal")
        ax.figure.colorbar(im, ax=ax, label="p (force/length²)")
        ax.set_title(f"p, {self.label} (state {self.index})")
        return ax


def _fields(raw: List[Dict[str, Any]]) -> List[Fields]:
    out = []
    for d in raw:
        meta = json.loads(d["meta"])
        nx, ny = meta["nx"], meta["ny"]
        grid = lambda key: np.frombuffer(d[key], dtype=np.float64).reshape(ny, nx).copy()
        out.append(
            Fields(
                run=meta["run"],
                index=meta["index"],
                label=meta["label"],
                state=meta["state"],
                x=np.frombuffer(d["x"], dtype=np.float64).copy(),
                y=np.frombuffer(d["y"], dtype=np.float64).copy(),
                pressure=grid("pressure"),
                gap=grid("gap"),
                contact=np.frombuffer(d["contact"], dtype=np.uint8).reshape(ny, nx).astype(bool),
                dx=meta["dx"],
                sigma_c=meta["sigma_c"],
            )
        )
    return out


@dataclass
class Result:
    """A simulation's answer.

    ``adhesive_force`` is |min F̄| (dimensionless; F = F̄·3π Re Δγ) with its ``uncertainty``
    (absolute, same units) where the estimate states one; ``jg`` is Johnson–Greenwood's value
    beside it, a comparison and never the reference (``deviation_from_jg`` is relative).
    """

    #: |min F̄| of the estimate (dimensionless), or None where no run reached the minimum.
    adhesive_force: Optional[float]
    #: Its stated half-width (absolute, dimensionless), where it has one.
    uncertainty: Optional[float]
    #: The estimate's kind ("single-grid", "extrapolated", …).
    estimate: Optional[str]
    #: Johnson–Greenwood's (JKR's for a sphere) |min F̄|, for comparison.
    jg: Optional[float]
    #: (adhesive_force − jg)/jg.
    deviation_from_jg: Optional[float]
    #: c̄ and d̄ at the force minimum (dimensionless).
    c_bar_at_min: Optional[float]
    d_bar_at_min: Optional[float]
    #: Every grid's run, in the order run.
    runs: List[Run]
    #: The summary, the same dict as the CLI's ``--summary`` JSON.
    summary: Dict[str, Any]
    #: What an accuracy plan chose, in words.
    plan: Optional[str] = None
    #: Why the request fell short, if it did.
    failure: Optional[str] = None
    #: Whether Ctrl-C (KeyboardInterrupt) stopped a run; its partial states are kept.
    interrupted: bool = False
    #: Warnings about the answer.
    warnings: List[str] = field(default_factory=list)
    #: The fields kept (``fields=`` of :func:`simulate`), of every run.
    fields: List[Fields] = field(default_factory=list)

    @property
    def field_at_minimum(self) -> Optional[Fields]:
        """The fields of the last run's force minimum, if they were kept."""
        last = len(self.runs) - 1
        for f in self.fields:
            if f.run == last and "force minimum" in f.label:
                return f
        return None

    @property
    def states(self) -> np.ndarray:
        """The states of the run the answer rests on most (the finest grid run)."""
        if not self.runs:
            return _states_array([])
        return self.runs[-1].states

    @property
    def complete(self) -> bool:
        """Whether every run reached its end and nothing fell short."""
        return self.failure is None and all(r.complete for r in self.runs)

    def force_in(self, radius_e: float, work_of_adhesion: float) -> Optional[float]:
        """The adhesive force in the user's force unit: |min F̄|·3π Re Δγ (Re in L, Δγ in F/L)."""
        radius_e = _check.real("radius_e", radius_e, "a radius (length)")
        work_of_adhesion = _check.real("work_of_adhesion", work_of_adhesion, "a work of adhesion (force/length)")
        if self.adhesive_force is None:
            return None
        return self.adhesive_force * 3.0 * math.pi * radius_e * work_of_adhesion

    def plot(self, ax=None):
        """The pull-off curve F̄(d̄) with the force minimum marked (needs matplotlib)."""
        try:
            import matplotlib.pyplot as plt
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Result.plot needs matplotlib: pip install matplotlib") from e
        if ax is None:
            _, ax = plt.subplots()
        s = self.states
        s = s[s["phase"] != "approach"]
        ax.plot(s["d_bar"], s["f_bar"], lw=1, label="jkrbem")
        if self.adhesive_force is not None:
            ax.axhline(-self.adhesive_force, ls=":", c="k", lw=0.8, label="|min F̄|")
        ax.set_xlabel("d̄ = d·Re/c_r²")
        ax.set_ylabel("F̄ = F/(3π Re Δγ)")
        ax.invert_xaxis()
        ax.legend()
        return ax

    def __repr__(self) -> str:
        f = "—" if self.adhesive_force is None else f"{self.adhesive_force:.5f}"
        u = "" if self.uncertainty is None else f" ± {self.uncertainty:.5f}"
        return f"<jkrbem.Result |min F̄| = {f}{u} ({self.estimate}), {len(self.runs)} run(s)>"


_PROGRESS = "None, True or False (a tqdm bar), or a callable taking an event dict"


def _progress(progress: Union[None, bool, Callable[[dict], Any]]) -> Optional[Callable[[dict], Any]]:
    """The callable that sees a run's events: the user's, a tqdm bar (True), or none."""
    if progress is None:
        return None
    if callable(progress):
        return progress
    if not _check.flag("progress", progress, _PROGRESS):
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        def show(event: dict) -> None:
            if event["event"] in ("note", "warning"):
                print(f"jkrbem: {event['text']}")
        return show
    bars: Dict[str, Any] = {}

    def bar(event: dict) -> None:
        if event["event"] == "start":
            if "bar" in bars:
                bars["bar"].close()
            bars["bar"] = tqdm(total=event["expected_steps"], desc=f"grid {event['grid'][0]}×{event['grid'][1]}")
        elif event["event"] == "state" and "bar" in bars:
            b = bars["bar"]
            b.update(max(0, event["step"] - b.n))
            b.set_postfix(F=f"{event['f_bar']:.4f}", c=f"{event['c_bar']:.3f}")
        elif event["event"] == "end" and "bar" in bars:
            bars.pop("bar").close()
        elif event["event"] in ("note", "warning"):
            tqdm.write(f"jkrbem: {event['text']}")

    return bar


def _result(answer: Dict[str, Any], fields: List[Fields]) -> Result:
    s = answer["summary"]
    runs = [
        Run(grid=tuple(r["grid"]), dx=r["dx"], complete=r["complete"], states=_states_array(r["states"]))
        for r in answer["runs"]
    ]
    jg = s.get("jg_f_ad_bar")
    f = s.get("f_ad_bar")
    return Result(
        adhesive_force=f,
        uncertainty=s.get("f_ad_bar_uncertainty"),
        estimate=s.get("estimate"),
        jg=jg,
        deviation_from_jg=s.get("jg_deviation"),
        c_bar_at_min=s.get("c_bar_at_min"),
        d_bar_at_min=s.get("d_bar_at_min"),
        runs=runs,
        summary=s,
        plan=answer.get("plan"),
        failure=answer.get("failure"),
        interrupted=answer.get("interrupted", False),
        warnings=list(s.get("warnings", [])),
        fields=fields,
    )


def simulate(
    ratio: Optional[float] = None,
    *,
    progress: Union[None, bool, Callable[[dict], Any]] = None,
    **params: Any,
) -> Result:
    """Simulate the adhesive pull-off of one scene and estimate its adhesive force.

    The scene: an ellipsoid h = x²/(2 R1) + y²/(2 R2) given by ``ratio`` = R1/R2 (default 5)
    and ``r2`` (length), or by ``r1`` and ``r2``; or ``indenter="flat_punch"`` (``radius``,
    length) or ``"power_law"`` (h = ``scale``·rⁿ, ``exponent`` n; ``scale`` s defaults to 0.5,
    as in the CLI: s = 1/(2R), so n = 2 is the sphere of R = 1). ``e_star`` is E* (F/L²),
    ``work_of_adhesion`` Δγ (F/L). A shape keyword of another indenter is refused.

    What runs: ``accuracy`` ("2%" or 0.02) plans the grids that reach it; ``grid`` (a power of
    two) runs one grid; ``extrapolate`` (True, or a list of grids) runs several and
    extrapolates to Δx → 0. With none of them the run aims at 2 %. ``accuracy`` with ``grid``,
    ``grid_y``, ``steps``, ``onsets``, ``measure`` or ``extrapolate``, and ``extrapolate`` with
    ``grid`` or ``grid_y``, are refused (one would override the other). ``backend`` is "auto",
    "cpu" (f64) or "gpu" (f32). ``time_limit`` (s, at most 30 days) bounds an accuracy run.

    Numbers may be Python's or numpy's (``np.int64(64)``, ``np.float32(2)``); integers
    (``grid``, ``steps``, state indices) must be integers (32.0 is refused), and no bool is
    taken for a number.

    ``fields``: the states whose fields (pressure, gap, contact set as 2-D arrays, with x
    and y) are kept in :attr:`Result.fields`: None (the default), "minimum" (the force
    minimum), ("every", k) or a list of state indices (each also keeps the minimum).

    ``progress``: a callable receiving event dicts (``event`` = "note", "start", "state",
    "end" (a grid's pull-off ended), "warning"; a "state" with ``held`` True was found but is
    recorded later, once the search for the force minimum has gone back to the steps before
    it), or True for a tqdm bar where tqdm is installed. Every event but "state" is
    delivered; of the states, the latest at most every 0.2 s, less often where the callback is
    slow (it may take about a tenth of the run), and each grid's last before its "end". Ctrl-C stops the run, also while it searches: the result then holds the
    states recorded so far, with ``interrupted`` True (and a warning).

    Raises :class:`InputError` (a ValueError) for a bad parameter and :class:`TypeError`
    for one of the wrong type, each naming the keyword, and
    :class:`SolveError` (a RuntimeError) when no run reached the force minimum; its
    ``result`` attribute holds the partial states.
    """
    params["ratio"] = ratio
    request, heights = _request.request(params)
    text, raw_fields = _jkrbem.simulate(request, _progress(progress), heights)
    result = _result(json.loads(text), _fields(raw_fields))
    if result.interrupted:
        warnings.warn(
            "jkrbem: the run was interrupted; the result holds the states computed so far",
            RuntimeWarning,
            stacklevel=2,
        )
        return result
    if result.adhesive_force is None and result.failure is not None:
        error = SolveError(result.failure)
        error.result = result
        raise error
    return result


def _frame_records(frame: Any) -> List[Dict[str, Any]]:
    """A pandas DataFrame's rows as dicts of keywords: an empty (NaN, None, NA) cell is not
    given, and a whole number in a column pandas made float (because of its empty cells) is
    an integer again where the keyword takes one."""
    import pandas as pd

    records = []
    for row in frame.to_dict("records"):
        given: Dict[str, Any] = {}
        for name, value in row.items():
            if pd.api.types.is_scalar(value) and pd.isna(value):
                continue
            kind = _request.BY_NAME.get(name, {}).get("kind", "")
            if isinstance(value, float) and value.is_integer() and kind.startswith(("Count", "PowerOfTwo")):
                value = int(value)
            given[name] = value
        records.append(given)
    return records


def _batch_progress(progress: Union[None, bool, Callable[[dict], Any]]) -> Optional[Callable[[dict], Any]]:
    """The callable that sees a batch's events: the user's, a tqdm bar over the scenes
    (True), or none."""
    if progress is None or callable(progress):
        return progress
    if not _check.flag("progress", progress, _PROGRESS):
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        def show(event: dict) -> None:
            if event["event"] == "scene":
                print(f"jkrbem: scenes[{event['index']}] ended ({event['done']} of {event['total']})")
            elif event["event"] == "warning":
                print(f"jkrbem: {event['text']}")
        return show
    bars: Dict[str, Any] = {}

    def bar(event: dict) -> None:
        if event["event"] == "scene":
            if "bar" not in bars:
                bars["bar"] = tqdm(total=event["total"], desc="scenes")
            bars["bar"].update(1)
            if event["done"] == event["total"]:
                bars.pop("bar").close()
        elif event["event"] == "warning":
            tqdm.write(f"jkrbem: {event['text']}")

    return bar


def batch(
    scenes: Any,
    processes: int = 1,
    progress: Union[None, bool, Callable[[dict], Any]] = None,
) -> List[Result]:
    """Simulate many scenes: ``scenes`` is a list of dicts of :func:`simulate`'s keywords (one
    scene each), or a pandas DataFrame with a column per keyword (an empty or NaN cell is a
    keyword not given). Every scene is checked before any runs; a refusal names the scene
    (``scenes[i]``) and the keyword. ``processes`` scenes run at a time (1 to 256), each on its
    own backend, in threads of this process; 1 runs them one after another, each using every
    core.

    ``progress``: a callable receiving event dicts (``event`` = "note", "warning", each
    ``text`` naming its scene, and "scene" as each scene ends: ``index``, ``done``, ``total``,
    ``adhesive_force``, ``failure``), or True for a tqdm bar over the scenes.

    Returns the :class:`Result` of each scene, in order. Raises :class:`SolveError` naming
    every scene that has no adhesive force because a run failed; its ``results`` attribute
    holds every scene's :class:`Result` (None for one that could not start) and ``result``
    the first failed one's.
    """
    if hasattr(scenes, "to_dict") and hasattr(scenes, "columns"):
        records: List[Any] = _frame_records(scenes)
    else:
        records = _check.items("scenes", scenes, "a list of dicts of keywords (or a pandas DataFrame)")
    processes = _check.integer("processes", processes, 1, 256, "scenes run at a time, from 1 to 256")
    requests = []
    for i, params in enumerate(records):
        if not isinstance(params, dict):
            raise TypeError(
                f"scenes[{i}] = {_check.shown(params)} is invalid: a dict of keywords is expected, "
                f"not {type(params).__name__}"
            )
        try:
            text, heights = _request.request(params)
        except (TypeError, InputError) as e:
            raise type(e)(f"scenes[{i}]: {e}") from None
        if heights is not None:
            raise InputError(
                f"scenes[{i}]: height_map as an array is not taken by batch: save it to a file "
                "and give its path (with spacing)"
            )
        requests.append(json.loads(text))
    answers = _jkrbem.batch(json.dumps(requests), processes, _batch_progress(progress))
    results: List[Optional[Result]] = []
    failures = []
    for i, (text, raw_fields, error) in enumerate(answers):
        if error is not None:
            kind, message = error
            if kind == "input":
                raise InputError(f"scenes[{i}]: {message}")
            results.append(None)
            failures.append((i, message, None))
            continue
        r = _result(json.loads(text), _fields(raw_fields))
        results.append(r)
        if r.adhesive_force is None and r.failure is not None and not r.interrupted:
            failures.append((i, r.failure, r))
    if any(r is not None and r.interrupted for r in results):
        warnings.warn(
            "jkrbem: the batch was interrupted; the results hold the states computed so far",
            RuntimeWarning,
            stacklevel=2,
        )
    if failures:
        lines = [f"scenes[{i}]: {message}" for i, message, _ in failures]
        error = SolveError(f"{len(failures)} of {len(results)} scene(s) failed:\n  " + "\n  ".join(lines))
        error.results = results
        error.result = next((r for _, _, r in failures if r is not None), None)
        raise error
    return results  # type: ignore[return-value]


def pulloff(
    ratio: Optional[float] = None,
    *,
    grid: int = 128,
    measure: str = "curve",
    onsets: str = "near_minimum",
    **kwargs: Any,
) -> Result:
    """One pull-off on one grid (``grid`` elements along x), no accuracy estimate beyond the
    single grid's: the whole curve (``measure="curve"``) or only up to the confirmed force
    minimum (``measure="adhesive_force"``). Other keywords as :func:`simulate`."""
    return simulate(ratio, grid=grid, measure=measure, onsets=onsets, **kwargs)


def sweep(
    ratios: Sequence[float] = (1, 2, 3, 5, 10, 15, 20, 25),
    **kwargs: Any,
) -> np.ndarray:
    """One :func:`simulate` per axis ratio R1/R2 (other keywords as there, e.g. ``accuracy`` or
    ``grid``): a structured array, one row per ratio, with the adhesive force, its uncertainty,
    the estimate's kind, c̄ and d̄ at the minimum, Johnson–Greenwood and the deviation from it
    (a comparison). :func:`sweep_results` gives the :class:`Result` of each ratio instead."""
    return _table(sweep_results(ratios, **kwargs))


def _ratios(ratios: Sequence[float]) -> List[float]:
    """``ratios``: a non-empty list of axis ratios, each checked before any runs."""
    values = _check.items("ratios", ratios, "a list of axis ratios R1/R2 (e.g. [1, 2, 5])")
    if not values:
        raise InputError("ratios = [] is invalid: at least one axis ratio R1/R2")
    return [_check.ratio("ratios", q) for q in values]


def sweep_results(
    ratios: Sequence[float] = (1, 2, 3, 5, 10, 15, 20, 25),
    *,
    processes: int = 1,
    progress: Union[None, bool, Callable[[dict], Any]] = None,
    **kwargs: Any,
) -> List[Result]:
    """The :class:`Result` of :func:`simulate` for each ratio, in order: one :func:`batch`
    with a scene per ratio (``processes`` of them at a time)."""
    return batch([dict(kwargs, ratio=q) for q in _ratios(ratios)], processes=processes, progress=progress)


def _table(results: List[Result]) -> np.ndarray:
    dtype = [
        ("ratio", "f8"), ("f_ad_bar", "f8"), ("f_ad_bar_uncertainty", "f8"), ("estimate", "U16"),
        ("c_bar_at_min", "f8"), ("d_bar_at_min", "f8"), ("jg_f_ad_bar", "f8"), ("jg_deviation", "f8"),
    ]
    nan = lambda v: math.nan if v is None else v
    rows = [
        (r.summary["ratio"], nan(r.adhesive_force), nan(r.uncertainty), r.estimate or "",
         nan(r.c_bar_at_min), nan(r.d_bar_at_min), nan(r.jg), nan(r.deviation_from_jg))
        for r in results
    ]
    return np.array(rows, dtype=dtype)


def crossed(
    angles: Sequence[float] = (90, 60, 45, 30, 20),
    *,
    radius: float = 0.01,
    young: float = 3e6,
    poisson: float = 0.5,
    work_of_adhesion: float = 0.05,
    **kwargs: Any,
) -> np.ndarray:
    """Two identical elastic cylinders of ``radius`` (m), Young's modulus ``young`` (Pa),
    Poisson's ratio ``poisson``, crossed at each of ``angles`` (degrees; 90 is sphere-like),
    with ``work_of_adhesion`` (J/m²): the adhesive force in newtons with its uncertainty, beside
    Johnson–Greenwood's (a comparison). Other keywords as :func:`simulate` (e.g. ``accuracy``)."""
    values = _check.items("angles", angles, "a list of crossing angles in degrees (e.g. [90, 45])")
    if not values:
        raise InputError("angles = [] is invalid: at least one crossing angle in degrees")
    values = [_check.real("angles", a, "a crossing angle in degrees") for a in values]
    material = (
        _check.real("radius", radius, "a radius (m)"),
        _check.real("young", young, "a Young's modulus (Pa)"),
        _check.real("poisson", poisson, "a Poisson's ratio"),
        _check.real("work_of_adhesion", work_of_adhesion, "a work of adhesion (J/m²)"),
    )
    # Every angle's scene first, so that a bad one is refused before any runs.
    scenes = [(angle, json.loads(_jkrbem.crossed_scene(*material, angle))) for angle in values]
    rows = []
    for angle, eq in scenes:
        r = simulate(r1=eq["r1"], r2=eq["r2"], e_star=eq["e_star"],
                     work_of_adhesion=material[3], **kwargs)
        f = eq["force_scale"]
        nan = lambda v: math.nan if v is None else v
        rows.append((angle, eq["ratio"], nan(r.adhesive_force) * f, nan(r.uncertainty) * f,
                     nan(r.jg) * f, nan(r.deviation_from_jg)))
    dtype = [("angle_deg", "f8"), ("ratio", "f8"), ("force_n", "f8"), ("force_n_uncertainty", "f8"),
             ("jg_force_n", "f8"), ("jg_deviation", "f8")]
    return np.array(rows, dtype=dtype)


def plan(ratio: Optional[float] = None, *, accuracy: Union[str, float] = "2%", **params: Any) -> Dict[str, Any]:
    """What :func:`simulate` with ``accuracy`` would run, without running it: the grids, the
    margin, the measure, the elements across the minor axis at the minimum (``n_d``) and the
    uncertainty it predicts (relative), with a description. Keywords as :func:`simulate`."""
    params.update(ratio=ratio, accuracy=accuracy)
    request, heights = _request.request(params)
    return json.loads(_jkrbem.plan(request, heights))


_MODELS = '"hertz", "jkr" or "jg"'


class _Theory:
    """Closed forms, normalised: Hertz, JKR (sphere) and Johnson–Greenwood (ellipse), for
    R1/R2 in [1, 1000] as in the CLI."""

    def curve(self, model: str = "jg", ratio: float = 1.0, points: int = 200) -> np.ndarray:
        """``points`` points (2 to 1000000) of the closed-form curve, a structured array
        (c_bar, f_bar, d_bar, a_bar, b_bar), by decreasing c̄. ``model``: "hertz", "jkr"
        (ratio 1) or "jg"."""
        most = _check.LIMITS["max_theory_points"]
        pts = json.loads(_jkrbem.theory_curve(
            _check.text("model", model, _MODELS),
            _check.real("ratio", ratio, "an axis ratio R1/R2"),
            _check.integer("points", points, 2, most, f"from 2 to {most} points"),
        ))
        dtype = np.dtype([(k, "f8") for k in ("c_bar", "f_bar", "d_bar", "a_bar", "b_bar")])
        return np.array([tuple(p[k] for k in dtype.names) for p in pts], dtype=dtype)

    def pull_off(self, model: str = "jg", ratio: float = 1.0) -> Dict[str, Dict[str, float]]:
        """The force minimum (``force_min``) and the end of contact (``end_of_contact``)."""
        return json.loads(_jkrbem.theory_pull_off(
            _check.text("model", model, _MODELS), _check.real("ratio", ratio, "an axis ratio R1/R2")
        ))

    def adhesive_force(self, ratio: float = 1.0) -> float:
        """|min F̄| of JKR (ratio 1, exactly 1/2) or Johnson–Greenwood."""
        ratio = _check.real("ratio", ratio, "an axis ratio R1/R2")
        model = "jkr" if ratio == 1 else "jg"
        return -self.pull_off(model, ratio)["force_min"]["f_bar"]


#: The closed forms: ``jkrbem.theory.curve(...)``, ``.pull_off(...)``, ``.adhesive_force(...)``.
theory = _Theory()


def reference_table() -> np.ndarray:
    """The reference table of converged adhesive forces per R1/R2 (|min F̄|, c̄ and d̄ at the
    minimum at Δx → 0, with their uncertainties), as a structured array."""
    import csv
    import io

    rows = list(csv.reader(io.StringIO(_jkrbem.reference_table_csv())))
    header, body = rows[0], [r for r in rows[1:] if r]

    def number(text: str) -> Optional[float]:
        try:
            return float(text)
        except ValueError:
            return None

    dtype = []
    for i, name in enumerate(header):
        column = [r[i] for r in body]
        if all(number(t) is not None or t == "" for t in column):
            dtype.append((name, "f8"))
        else:
            dtype.append((name, f"U{max(len(t) for t in column)}"))
    records = [
        tuple(
            (math.nan if t == "" else float(t)) if kind == "f8" else t
            for t, (_, kind) in zip(r, dtype)
        )
        for r in body
    ]
    return np.array(records, dtype=dtype)


def devices() -> List[Dict[str, Any]]:
    """The GPU adapters wgpu sees, best first (name, device type, API, largest grid)."""
    return json.loads(_jkrbem.devices())


simulate.__signature__ = _request.signature(  # type: ignore[attr-defined]
    extra=(inspect.Parameter("progress", inspect.Parameter.KEYWORD_ONLY, default=None),)
)
simulate.__doc__ = (simulate.__doc__ or "") + "\n" + _request.keyword_docs()
