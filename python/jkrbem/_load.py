"""Reading back what the ``jkrbem`` command writes: a summary (``--summary``, JSON), a states
CSV (``--out``) and a fields archive (``<out>.fields.npz``), as the objects
:func:`jkrbem.simulate` returns. The formats are the CLI's (src/output/summary.rs,
states_csv.rs, fields_npz.rs); nothing is recomputed."""

from __future__ import annotations

import csv
import json
import math
import os
import stat
import zipfile
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

from ._jkrbem import InputError
from ._results import STATE_COLUMNS, Fields, Result, Run, result_from, states_array
from ._warnings import warn_all

__all__ = ["load"]

#: The columns a states CSV cannot do without (older files may lack cg_residual and dx).
_NEEDED = ("step", "phase", "d", "force", "d_bar", "f_bar", "c_bar")

#: The arrays of a fields archive (src/output/fields_npz.rs), besides its metadata.
_ARRAYS = ("pressure", "gap", "contact", "x", "y", "state_index", "d", "force", "dx", "sigma_c",
           "d_bar", "f_bar", "c_bar")

_WHAT = "a summary (.json), a states CSV (.csv) or a fields archive (.fields.npz)"

#: The largest summary read (bytes), as the command's own reads of summaries.
_MAX_SUMMARY_BYTES = 16 << 20

#: The largest states CSV read (bytes): a run's 100 000 steps with their onsets take far less.
_MAX_STATES_BYTES = 1 << 30


def _open_regular(p: Path, cap: Optional[int]) -> int:
    """A descriptor of `p` opened for reading without blocking (a FIFO never hangs), checked
    to be a regular file of at most `cap` bytes (None: any size); :class:`InputError`
    otherwise (a device such as /dev/zero, a FIFO, a folder, a file too large), OSError where
    it cannot be opened."""
    fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise _refuse(p, "not a regular file (a device, a FIFO or a folder): jkrbem.load "
                             "reads the files the command wrote")
        if cap is not None and st.st_size > cap:
            raise _refuse(p, f"{st.st_size} bytes, more than the {cap} such a file can hold")
    except BaseException:
        os.close(fd)
        raise
    return fd


def _read_regular(p: Path, cap: Optional[int]) -> str:
    """The text (UTF-8) of the regular file `p`, of at most `cap` bytes ([`_open_regular`])."""
    with os.fdopen(_open_regular(p, cap), "rb") as f:
        data = f.read(cap + 1 if cap is not None else -1)
    if cap is not None and len(data) > cap:
        raise _refuse(p, f"more than the {cap} bytes such a file can hold")
    return data.decode("utf-8")


def load(path: Union[str, "os.PathLike[str]"]) -> Union[Result, Run, List[Fields]]:
    """Read a file the ``jkrbem`` command wrote, chosen by its extension:

    - ``.json``, a summary (``--summary``): a :class:`Result` whose ``runs`` hold the states
      of the CSVs the summary names (looked for where it says, else beside the summary; a
      run whose CSV is missing has no states, with a :class:`JkrbemWarning`), and whose
      ``fields`` hold the ``.fields.npz`` beside them, where there is one;
    - ``.csv``, a states CSV (``--out``; lines starting with ``#`` are comments, kept in
      :attr:`Run.comments`): a :class:`Run`, its grid from the summary or fields file beside
      it (None without either), complete unless the file still has its partial name
      (``<stem>.incomplete-<pid>.csv``);
    - ``.npz``, a fields archive (``<out>.fields.npz``): a list of :class:`Fields`, one per
      state, with each state's full row where the states CSV beside it is found.

    Lengths and forces are in the units the run was given. Raises :class:`InputError` (a
    ValueError) for another extension or a file that is not of that format (naming the file
    and what is wrong), and OSError (FileNotFoundError …) where the file cannot be read.
    """
    p = Path(os.fspath(path))
    name = p.name.lower()
    if name.endswith(".json"):
        return _load_summary(p)
    if name.endswith(".csv"):
        return _load_run(p)
    if name.endswith(".npz"):
        return _load_fields(p)
    shown = p.suffix or "no extension"
    raise InputError(f"path = {str(p)!r} is invalid: jkrbem.load reads {_WHAT}, not {shown}")


class _TooDeep(ValueError):
    """JSON nested too deeply for Python's parser."""


def _json(text: str) -> Any:
    """`text` parsed as JSON; a document nested too deeply for Python's parser (which recurses
    once per level and runs out of stack) is a ValueError (:class:`_TooDeep`), as any other
    text that is not JSON, never a RecursionError."""
    try:
        return json.loads(text)
    except RecursionError:
        raise _TooDeep("nested deeper than Python's parser can follow, as no file jkrbem "
                       "writes is") from None


def _refuse(p: Path, why: str) -> InputError:
    """The error for a file that is not of the format its extension says."""
    return InputError(f"path = {str(p)!r} is invalid: {why}")


# --- states CSV ---------------------------------------------------------------------------


def _read_states(p: Path) -> Tuple[np.ndarray, List[str], Optional[str]]:
    """The states of a states CSV, its comment lines (without ``# ``) and its ``onsets``."""
    text = _read_regular(p, _MAX_STATES_BYTES).splitlines()
    comments = [line[1:].strip() for line in text if line.lstrip().startswith("#")]
    numbered = [(i + 1, line) for i, line in enumerate(text) if line.strip() and not line.lstrip().startswith("#")]
    if not numbered:
        raise _refuse(p, "not a jkrbem states CSV: it has no header line")
    rows = csv.reader([line for _, line in numbered])
    header = [h.strip() for h in next(rows)]
    missing = [c for c in _NEEDED if c not in header]
    if missing:
        raise _refuse(p, f"not a jkrbem states CSV: its header lacks {', '.join(missing)}")
    where = {name: i for i, name in enumerate(header)}
    states = []
    onsets = None
    for (lineno, _), record in zip(numbered[1:], rows):
        if len(record) != len(header):
            raise _refuse(p, f"line {lineno} has {len(record)} values, the header {len(header)}")
        row: Dict[str, Any] = {}
        for name, kind in STATE_COLUMNS:
            i = where.get(name)
            text_value = record[i].strip() if i is not None else ""
            if not text_value:
                continue  # states_array reads it as NaN or -1
            try:
                row[name] = float(text_value) if kind == "f8" else int(text_value) if kind == "i8" else text_value
            except ValueError:
                raise _refuse(p, f"line {lineno}: {name} = {text_value!r} is not a number") from None
        if "onsets" in where:
            onsets = record[where["onsets"]].strip() or onsets
        states.append(row)
    return states_array(states), comments, onsets


def _summary_beside(csv_path: Path) -> Optional[Dict[str, Any]]:
    """The run report naming `csv_path` in the summary beside it (``<stem>.json``), if any."""
    beside = csv_path.with_suffix(".json")
    try:
        summary = _json(_read_regular(beside, _MAX_SUMMARY_BYTES))
    except (OSError, ValueError):
        return None
    for report in summary.get("runs", []) if isinstance(summary, dict) else []:
        named = report.get("states_csv") if isinstance(report, dict) else None
        if named and Path(named).name == csv_path.name:
            return report
    return None


def _fields_path(csv_path: Path) -> Path:
    """The fields archive beside a states CSV: ``<stem>.fields.npz``."""
    return csv_path.with_name(csv_path.stem + ".fields.npz")


def _grid_of_fields(npz: Path) -> Optional[Tuple[int, int]]:
    """The grid a fields archive states (its metadata's ``about.grid``), if it can be read."""
    try:
        os.close(_open_regular(npz, None))
        with np.load(npz, allow_pickle=False) as z:
            meta = _json(z["metadata"].tobytes().decode("utf-8"))
        nx, ny = meta["about"]["grid"]
        return int(nx), int(ny)
    except Exception:  # no archive, or not one of ours: the grid stays unknown
        return None


def _run_from_csv(p: Path, report: Optional[Dict[str, Any]]) -> Run:
    """The :class:`Run` of a states CSV, with what its run report says (grid, Δx, complete)."""
    states, comments, onsets = _read_states(p)
    if report is not None:
        grid: Optional[Tuple[int, int]] = (int(report["nx"]), int(report["ny"]))
        complete = bool(report.get("complete", True))
        dx = float(report["dx"])
    else:
        grid = _grid_of_fields(_fields_path(p))
        complete = ".incomplete-" not in p.name
        dx = float(states["dx"][0]) if len(states) else math.nan
    return Run(grid=grid, dx=dx, complete=complete, states=states,
               onsets=onsets if report is None else report.get("onsets", onsets), comments=comments)


def _load_run(p: Path) -> Run:
    return _run_from_csv(p, _summary_beside(p))


# --- fields archive -------------------------------------------------------------------------


def _load_fields(p: Path, run: int = 0, states: Optional[np.ndarray] = None) -> List[Fields]:
    """The fields of a ``.fields.npz`` (of run `run`), each state's row from `states` (the
    run's states) or, where not given, from the states CSV beside the archive if found."""
    os.close(_open_regular(p, None))
    try:
        z = np.load(p, allow_pickle=False)
    except (ValueError, EOFError, zipfile.BadZipFile) as e:
        raise _refuse(p, f"not a numpy .npz archive ({e})") from None
    if not isinstance(z, np.lib.npyio.NpzFile):
        raise _refuse(p, "not a jkrbem fields archive (a single .npy array, not an .npz archive)")
    with z:
        if "metadata" not in z.files:
            raise _refuse(p, "not a jkrbem fields archive (no metadata)")
        try:
            meta = _json(z["metadata"].tobytes().decode("utf-8"))
        except _TooDeep as e:
            raise _refuse(p, f"not a jkrbem fields archive: its metadata is {e}") from None
        except ValueError:
            raise _refuse(p, "not a jkrbem fields archive (its metadata is not JSON)") from None
        if not isinstance(meta, dict) or meta.get("format") != "jkrbem fields":
            raise _refuse(p, "not a jkrbem fields archive (its metadata names another format)")
        lacking = [k for k in _ARRAYS if k not in z.files]
        if lacking:
            raise _refuse(p, f"a jkrbem fields archive without {', '.join(lacking)}")
        arrays = {k: z[k] for k in _ARRAYS}
    if states is None:
        states = _states_beside(p, meta)
    labels = meta.get("labels", [])
    out = []
    for k, index in enumerate(arrays["state_index"].astype(np.int64)):
        index = int(index)
        if states is not None and 0 <= index < len(states):
            row = states[index]
            state = {name: row[name].item() for name in states.dtype.names}
        else:
            state = {name: float(arrays[name][k]) for name in ("d", "force", "dx", "d_bar", "f_bar", "c_bar")}
        out.append(
            Fields(
                run=run,
                index=index,
                label=labels[k] if k < len(labels) else f"state {index}",
                state=state,
                x=np.array(arrays["x"][k], dtype=np.float64),
                y=np.array(arrays["y"][k], dtype=np.float64),
                pressure=np.array(arrays["pressure"][k], dtype=np.float64),
                gap=np.array(arrays["gap"][k], dtype=np.float64),
                contact=np.array(arrays["contact"][k], dtype=bool),
                dx=float(arrays["dx"][k]),
                sigma_c=float(arrays["sigma_c"][k]),
            )
        )
    return out


def _states_beside(npz: Path, meta: Dict[str, Any]) -> Optional[np.ndarray]:
    """The states of the CSV a fields archive belongs to, where it is found and reads."""
    name = npz.name
    stem = name[: -len(".fields.npz")] if name.lower().endswith(".fields.npz") else npz.stem
    named = (meta.get("about") or {}).get("states_csv") if isinstance(meta.get("about"), dict) else None
    candidates = [npz.with_name(stem + ".csv")]
    if named:
        candidates += [Path(named), npz.with_name(Path(named).name)]
    for c in candidates:
        if c.is_file():
            try:
                return _read_states(c)[0]
            except (OSError, InputError):
                continue
    return None


# --- summary --------------------------------------------------------------------------------


def _find(named: str, base: Path) -> Optional[Path]:
    """A file the summary names: where it says (from the working folder, or from the
    summary's folder), else under its own name beside the summary."""
    q = Path(named)
    for c in ([q] if q.is_absolute() else [q, base / q]) + [base / q.name]:
        if c.is_file():
            return c
    return None


def _load_summary(p: Path) -> Result:
    try:
        summary = _json(_read_regular(p, _MAX_SUMMARY_BYTES))
    except _TooDeep as e:
        raise _refuse(p, f"not a jkrbem summary: it is {e}") from None
    except ValueError as e:
        raise _refuse(p, f"not JSON ({e})") from None
    if not (isinstance(summary, dict) and isinstance(summary.get("runs"), list) and "f_ad_bar" in summary):
        raise _refuse(p, "not a jkrbem summary (it has no f_ad_bar and runs)")
    try:
        return _result_of_summary(p, summary)
    except InputError:
        raise
    except (KeyError, TypeError, ValueError, AttributeError, IndexError) as e:
        # A summary edited or written by something else: never a raw KeyError or TypeError.
        raise _refuse(p, f"not a jkrbem summary: a field is missing or of the wrong type "
                         f"({type(e).__name__}: {e})") from None


def _result_of_summary(p: Path, summary: Dict[str, Any]) -> Result:
    """The :class:`Result` of the summary `summary` read from `p`, its runs' states and fields
    read from the files it names."""
    base = p.parent
    runs: List[Run] = []
    fields: List[Fields] = []
    missing: List[str] = []
    for i, report in enumerate(summary["runs"]):
        named = report.get("states_csv")
        found = _find(named, base) if named else None
        if found is not None:
            run = _run_from_csv(found, report)
            npz = _fields_path(found)
            if npz.is_file():
                fields += _load_fields(npz, run=i, states=run.states)
        else:
            missing.append(named or f"(run {i} was kept in memory only)")
            run = Run(grid=(int(report["nx"]), int(report["ny"])), dx=float(report["dx"]),
                      complete=bool(report.get("complete", True)), states=states_array([]),
                      onsets=report.get("onsets"))
        runs.append(run)
    if missing:
        warn_all([f"jkrbem.load: {str(p)!r} names states that are not found ({', '.join(missing)}): "
                  "those runs have no states"])
    errors = [f"{r.get('grid')}: {r['error']}" for r in summary["runs"] if r.get("error")]
    return result_from(summary, runs, fields, failure="; ".join(errors) or None)
