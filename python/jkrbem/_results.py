"""What a run hands back: :class:`Result` (the answer and every grid's run), :class:`Run` (one
grid's states) and :class:`Fields` (the fields of one state), built from the solver's answer
or from the files the CLI writes (:func:`jkrbem.load`). Nothing here computes physics: the
adhesive force and its uncertainty are the summary's; only the force scale F/F̄ is read off
the states where the summary does not state it."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _check

__all__ = ["STATE_COLUMNS", "Run", "Fields", "Result"]

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

#: The estimate's kind where the answer is the finest grid's own |min F̄| (no estimate at
#: Δx → 0: the flat punch, the power law).
GRID_VALUE = "grid"

#: The longest repr of a result class (characters).
REPR_MAX = 300


def states_array(states: List[Dict[str, Any]]) -> np.ndarray:
    """The states (dicts with the states' columns) as a numpy structured array; a column a
    state lacks reads NaN (floats) or -1 (integers)."""
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


def _short(text: str) -> str:
    """`text` cut to :data:`REPR_MAX` characters."""
    return text if len(text) <= REPR_MAX else text[: REPR_MAX - 2] + "…>"


def _number(v: Optional[float], digits: int = 5) -> str:
    """`v` for a repr: "—" where there is none."""
    return "—" if v is None or not math.isfinite(v) else f"{v:.{digits}g}"


def _pandas(what: str):
    """The pandas module, or an ImportError that says how to install it."""
    try:
        import pandas
    except ImportError as e:
        raise ImportError(
            f"{what} needs pandas, which is not installed: pip install pandas "
            "(or pip install 'jkrbem[pandas]')"
        ) from e
    return pandas


def _dataframe(runs: Sequence["Run"], what: str, with_run: bool):
    """The states of `runs` as one pandas DataFrame: ``run`` (the run's index; where
    `with_run`), ``nx`` and ``ny`` (its grid; -1 where unknown), then :data:`STATE_COLUMNS`."""
    pd = _pandas(what)
    counts = [len(r.states) for r in runs]
    columns: Dict[str, Any] = {}
    if with_run:
        columns["run"] = np.repeat(np.arange(len(runs), dtype=np.int64), counts)
    for axis, name in ((0, "nx"), (1, "ny")):
        sides = [-1 if r.grid is None else int(r.grid[axis]) for r in runs]
        columns[name] = np.repeat(np.array(sides, dtype=np.int64), counts)
    empty = states_array([])
    for name, _ in STATE_COLUMNS:
        parts = [r.states[name] for r in runs] or [empty[name]]
        values = np.concatenate(parts)
        columns[name] = values.astype(object) if values.dtype.kind == "U" else values
    return pd.DataFrame(columns)


@dataclass(repr=False)
class Run:
    """One grid's pull-off: its grid, element side and states."""

    #: Elements along x and y; None for a states CSV loaded without its summary or fields
    #: file beside it (the CSV does not say).
    grid: Optional[Tuple[int, int]]
    #: Element side Δx at the start (length).
    dx: float
    #: Whether it reached its end (or its confirmed force minimum).
    complete: bool
    #: Every recorded state, a structured array with :data:`STATE_COLUMNS`.
    states: np.ndarray
    #: Which detachment onsets the run located ("near-minimum", "all", "none"), where known.
    onsets: Optional[str] = None
    #: The comment lines (``# …``, without the ``# ``) of a states CSV read by
    #: :func:`jkrbem.load`; empty otherwise.
    comments: List[str] = field(default_factory=list)

    @property
    def lowest_f_bar(self) -> Optional[float]:
        """The lowest F̄ recorded (dimensionless, negative in tension): the grid's own force
        minimum where the run reached it; None without states."""
        f = self.states["f_bar"] if len(self.states) else np.array([])
        f = f[np.isfinite(f)]
        return float(f.min()) if len(f) else None

    def to_dataframe(self):
        """The states as a pandas DataFrame: ``nx`` and ``ny`` (the grid; -1 where unknown)
        beside the :data:`STATE_COLUMNS` (units as there). Needs pandas
        (``pip install 'jkrbem[pandas]'``)."""
        return _dataframe([self], "Run.to_dataframe", with_run=False)

    def __repr__(self) -> str:
        grid = "?" if self.grid is None else f"{self.grid[0]}×{self.grid[1]}"
        return _short(
            f"<jkrbem.Run grid {grid}, Δx = {_number(self.dx)}, {len(self.states)} states, "
            f"min F̄ = {_number(self.lowest_f_bar)}, {'complete' if self.complete else 'INCOMPLETE'}>"
        )


@dataclass(repr=False)
class Fields:
    """The fields of one state on its grid. 2-D arrays have shape (ny, nx): ``a[j, i]`` is
    the element at ``x[i]``, ``y[j]``. Each field is the state's contact set solved again on
    the CPU (f64) at its approach."""

    #: Which run (0: the first grid run) and which of its states (0: the first press).
    run: int
    index: int
    #: Why it was kept ("force minimum", "state 12").
    label: str
    #: The state (a dict with the states' columns; read from a fields file without its
    #: states CSV beside it, only d, force, dx, d_bar, f_bar and c_bar).
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

    def __repr__(self) -> str:
        ny, nx = self.pressure.shape if self.pressure.ndim == 2 else (0, 0)
        f_bar = self.state.get("f_bar")
        label = self.label if len(self.label) <= 40 else self.label[:39] + "…"
        return _short(
            f"<jkrbem.Fields run {self.run}, state {self.index} ({label}), {nx}×{ny}, "
            f"F̄ = {_number(f_bar)}, F = {_number(self.force)}, "
            f"{int(np.count_nonzero(self.contact))} elements in contact>"
        )


def fields_from_raw(raw: List[Dict[str, Any]]) -> List[Fields]:
    """The fields the compiled module hands back (dicts of raw bytes and JSON text)."""
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


@dataclass(repr=False)
class Result:
    """A simulation's answer.

    ``adhesive_force`` is |min F̄| (dimensionless; F = F̄ times the force scale, 3π Re Δγ for
    the ellipsoid) with its ``uncertainty`` (absolute, same units), for every indenter:

    - where the summary states an estimate at Δx → 0 (the ellipsoid: ``estimate`` is
      "single-grid" or "extrapolated"), its value and uncertainty;
    - else (the flat punch, the power law: no convergence law is known for them) the finest
      grid's own |min F̄|, with ``estimate`` = "grid" and ``uncertainty`` None: the grid's
      value, which carries its discretisation error (of first order in Δx; the summary's
      ``exact_limit`` sets it beside the closed form where there is one).

    ``adhesive_force_in_units`` and ``uncertainty_in_units`` are the same in the user's force
    unit (``force_scale`` times them). ``jg`` is Johnson–Greenwood's value beside it, a
    comparison and never the reference (``deviation_from_jg`` is relative).
    """

    #: |min F̄| (dimensionless): the estimate's, else the finest grid's own (see above); None
    #: where no run reached (and resolved) the force minimum.
    adhesive_force: Optional[float]
    #: Its stated half-width (absolute, dimensionless); None for a grid's own value.
    uncertainty: Optional[float]
    #: Where ``adhesive_force`` comes from: the estimate's kind ("single-grid",
    #: "extrapolated", …), or "grid" for the finest grid's own value.
    estimate: Optional[str]
    #: Johnson–Greenwood's (JKR's for a sphere) |min F̄|, for comparison.
    jg: Optional[float]
    #: (adhesive_force − jg)/jg.
    deviation_from_jg: Optional[float]
    #: c̄ and d̄ at the force minimum (dimensionless), of the estimate or of the grid as
    #: ``adhesive_force``.
    c_bar_at_min: Optional[float]
    d_bar_at_min: Optional[float]
    #: Every grid's run, in the order run (coarse to fine).
    runs: List[Run]
    #: The summary, the same dict as the CLI's ``--summary`` JSON.
    summary: Dict[str, Any]
    #: What an accuracy plan chose, in words.
    plan: Optional[str] = None
    #: Why the request fell short, if it did.
    failure: Optional[str] = None
    #: Whether Ctrl-C (KeyboardInterrupt) stopped a run; its partial states are kept.
    interrupted: bool = False
    #: Warnings about the answer (each is also issued as a :class:`jkrbem.JkrbemWarning`
    #: by :func:`jkrbem.simulate`).
    warnings: List[str] = field(default_factory=list)
    #: The fields kept (``fields=`` of :func:`simulate`), of every run.
    fields: List[Fields] = field(default_factory=list)
    #: The force scale (force, the user's unit): F = F̄·force_scale. The summary's
    #: ``force_scale`` where it states one, else F/F̄ of the states; None without either.
    force_scale: Optional[float] = None

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
            return states_array([])
        return self.runs[-1].states

    @property
    def complete(self) -> bool:
        """Whether every run reached its end and nothing fell short."""
        return self.failure is None and all(r.complete for r in self.runs)

    @property
    def adhesive_force_in_units(self) -> Optional[float]:
        """The adhesive force |min F| in the user's force unit: ``adhesive_force`` times
        ``force_scale``; None where either is missing."""
        if self.adhesive_force is None or self.force_scale is None:
            return None
        return self.adhesive_force * self.force_scale

    @property
    def uncertainty_in_units(self) -> Optional[float]:
        """``uncertainty`` in the user's force unit (absolute); None where either it or
        ``force_scale`` is missing (always for a grid's own value)."""
        if self.uncertainty is None or self.force_scale is None:
            return None
        return self.uncertainty * self.force_scale

    def force_in(self, radius_e: float, work_of_adhesion: float) -> Optional[float]:
        """The adhesive force in the user's force unit: |min F̄|·3π Re Δγ (Re in L, Δγ in F/L;
        the ellipsoid's scale; :attr:`adhesive_force_in_units` needs neither)."""
        radius_e = _check.real("radius_e", radius_e, "a radius (length)")
        work_of_adhesion = _check.real("work_of_adhesion", work_of_adhesion, "a work of adhesion (force/length)")
        if self.adhesive_force is None:
            return None
        return self.adhesive_force * 3.0 * math.pi * radius_e * work_of_adhesion

    def to_dataframe(self):
        """The states of every run as one pandas DataFrame, coarse grid first: ``run`` (the
        run's index in :attr:`runs`), ``nx`` and ``ny`` (its grid; -1 where unknown), then the
        :data:`STATE_COLUMNS` (dimensional columns in the user's units, ``_bar`` columns
        normalised). Needs pandas (``pip install 'jkrbem[pandas]'``)."""
        return _dataframe(self.runs, "Result.to_dataframe", with_run=True)

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
        u = "" if self.uncertainty is None else f" ± {_number(self.uncertainty, 3)}"
        units = ""
        if self.adhesive_force_in_units is not None:
            du = self.uncertainty_in_units
            units = f"; F = {_number(self.adhesive_force_in_units)}" + ("" if du is None else f" ± {_number(du, 3)}")
        runs = f"{len(self.runs)} run{'s' if len(self.runs) != 1 else ''}"
        if self.runs:
            last = self.runs[-1]
            grid = "?" if last.grid is None else f"{last.grid[0]}×{last.grid[1]}"
            runs += f", finest {grid} with {len(last.states)} states"
        extra = ""
        if self.warnings:
            extra += f", {len(self.warnings)} warning{'s' if len(self.warnings) != 1 else ''}"
        if self.interrupted:
            extra += ", interrupted"
        return _short(
            f"<jkrbem.Result |min F̄| = {_number(self.adhesive_force)}{u} ({self.estimate or '—'}{units}), "
            f"{runs}, {'complete' if self.complete else 'INCOMPLETE'}{extra}>"
        )


def _adhesive_force(summary: Dict[str, Any]) -> Dict[str, Any]:
    """|min F̄|, its uncertainty, where it comes from and c̄, d̄ at the minimum: the summary's
    estimate, else the finest run's own values where that run resolved its minimum (with
    uncertainty None)."""
    if summary.get("f_ad_bar") is not None:
        return {
            "adhesive_force": summary["f_ad_bar"],
            "uncertainty": summary.get("f_ad_bar_uncertainty"),
            "estimate": summary.get("estimate"),
            "c_bar_at_min": summary.get("c_bar_at_min"),
            "d_bar_at_min": summary.get("d_bar_at_min"),
        }
    runs = summary.get("runs") or []
    finest = runs[-1] if runs else {}
    if finest.get("f_ad_bar") is not None and finest.get("min_resolved", True):
        return {
            "adhesive_force": finest["f_ad_bar"],
            "uncertainty": None,
            "estimate": GRID_VALUE,
            "c_bar_at_min": finest.get("c_bar_at_min"),
            "d_bar_at_min": finest.get("d_bar_at_min"),
        }
    return {
        "adhesive_force": None,
        "uncertainty": None,
        "estimate": summary.get("estimate"),
        "c_bar_at_min": summary.get("c_bar_at_min"),
        "d_bar_at_min": summary.get("d_bar_at_min"),
    }


def _force_scale(summary: Dict[str, Any], runs: Sequence[Run]) -> Optional[float]:
    """F/F̄ (force): the summary's ``force_scale``, else read off the finest run's states
    that have one (the state of largest |F̄|, for the fewest rounding digits lost)."""
    stated = summary.get("force_scale")
    if isinstance(stated, (int, float)) and not isinstance(stated, bool) and math.isfinite(stated):
        return float(stated)
    for run in reversed(runs):
        s = run.states
        if not len(s):
            continue
        f, f_bar = s["force"], s["f_bar"]
        ok = np.isfinite(f) & np.isfinite(f_bar) & (np.abs(f_bar) > 1e-12)
        if ok.any():
            i = int(np.argmax(np.where(ok, np.abs(f_bar), -1.0)))
            return float(f[i] / f_bar[i])
    return None


def result_from(
    summary: Dict[str, Any],
    runs: List[Run],
    fields: List[Fields],
    plan: Optional[str] = None,
    failure: Optional[str] = None,
    interrupted: bool = False,
) -> Result:
    """The :class:`Result` of a summary (the CLI's JSON, as a dict) and its runs."""
    return Result(
        **_adhesive_force(summary),
        jg=summary.get("jg_f_ad_bar"),
        deviation_from_jg=summary.get("jg_deviation"),
        runs=runs,
        summary=summary,
        plan=plan,
        failure=failure,
        interrupted=interrupted,
        warnings=list(summary.get("warnings", [])),
        fields=fields,
        force_scale=_force_scale(summary, runs),
    )
