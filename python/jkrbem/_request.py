"""A simulation's request from Python keywords: the keywords given, as JSON, for the library to
check against its one schema (``_jkrbem.schema()``: every keyword's unit, range, default and
help) and to complete with its defaults. Only what is Python's own is done here: numpy values
as plain numbers, a height map given as an array, ``fields`` and ``extrapolate`` in their
Python forms."""

from __future__ import annotations

import inspect
import json
import math
import os
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _check, _jkrbem
from ._jkrbem import InputError

#: Every keyword of a simulation, as the library's schema declares it (name, unit, kind,
#: default, terms, help).
SCHEMA: List[Dict[str, Any]] = json.loads(_jkrbem.schema())

#: The schema by keyword.
BY_NAME: Dict[str, Dict[str, Any]] = {s["name"]: s for s in SCHEMA}

_FIELDS = 'None, "minimum", ("every", k) or a list of state indices'


def _plain(name: str, value: Any) -> Any:
    """`value` as JSON can carry it: numpy scalars and arrays as Python numbers and lists,
    tuples as lists, paths as strings; anything else JSON cannot carry (a complex number, a
    masked array) is a TypeError."""
    if isinstance(value, np.generic):
        return _plain(name, value.item())
    if isinstance(value, np.ndarray):
        _check.unmasked(name, value)
        return _plain(name, value.tolist())
    if isinstance(value, (tuple, list)):
        return [_plain(name, v) for v in value]
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, float) and not math.isfinite(value):
        # JSON carries no NaN or infinity: refused here, as the library would refuse it.
        raise InputError(f"{name} = {value} is invalid: a finite number is expected")
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 63:
        # Beyond a 64-bit integer: as a float where JSON can carry it (the library refuses
        # it as out of range), else refused here.
        as_float = float(value) if value.bit_length() < 1024 else math.inf
        if not math.isfinite(as_float):
            digits = int(value.bit_length() * math.log10(2)) + 1
            raise InputError(f"{name} = an integer of about {digits} digits is invalid: out of range")
        return as_float
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, complex):
        raise TypeError(f"{name} = {_check.shown(value)} is invalid: a real number is expected, not a complex one")
    raise TypeError(f"{name} = {type(value).__name__} is invalid: a number, a string or a list is expected")


def _fields(value: Any) -> Optional[str]:
    """``fields`` in the library's words: "minimum", "every:K" or "states:I,J"."""
    if value is None or isinstance(value, str):
        return value
    if not isinstance(value, (list, tuple, np.ndarray)):
        raise TypeError(f"fields = {type(value).__name__} is invalid: {_FIELDS} is expected")
    _check.unmasked("fields", value)
    items = [v.item() if isinstance(v, np.generic) else v for v in value]
    if not items:
        raise InputError(f"fields = [] is invalid: {_FIELDS}, at least one")
    indices = items[1:] if len(items) == 2 and items[0] == "every" else items
    if not all(isinstance(i, int) and not isinstance(i, bool) for i in indices):
        raise TypeError(f"fields = {value!r} is invalid: state indices and k are integers")
    if indices is not items:
        return f"every:{indices[0]}"
    return "states:" + ",".join(str(i) for i in items)


def _heights(name: str, value: Any) -> Optional[Tuple[bytes, int, int]]:
    """A height map (or roughness) given as a 2-D array of real numbers (a float or integer
    dtype, as the CLI's .npy of float64 or float32; never complex, bool, object or masked):
    its heights as f64 bytes, and its shape."""
    if not isinstance(value, np.ndarray):
        return None
    _check.real_array(name, value, "a 2-D array of heights")
    if value.ndim != 2:
        raise InputError(f"{name} is invalid: a 2-D array of heights (rows along y), not {value.ndim}-D")
    a = np.ascontiguousarray(value, dtype=np.float64)
    return a.tobytes(), a.shape[0], a.shape[1]


#: The indenters, as the library spells them (hyphens).
_INDENTERS: List[str] = json.loads(BY_NAME["indenter"]["kind"][len("Choice("):-1])


def _refuse_foreign_array(name: str, indenter: Any) -> None:
    """Refuse an array given as ``height_map`` with another indenter, or as ``roughness``
    with ``indenter="height_map"``, as the library refuses such a file: the library takes an
    array as the indenter's map or as the roughness by the indenter alone, and would run a
    height_map array as the roughness of the ellipsoid (or a roughness array as the map)."""
    if indenter is None:
        indenter = BY_NAME["indenter"]["default"]
    if not isinstance(indenter, str):
        return  # the library refuses the indenter itself
    shape = indenter.strip().replace("_", "-")
    if shape not in _INDENTERS:
        return  # likewise
    if name == "height_map" and shape != "height-map":
        raise InputError(
            f"height_map is for indenter height-map, not {shape}: give indenter=\"height_map\" to "
            f"run the map, or give the array as roughness to add it to the {shape}"
        )
    if name == "roughness" and shape == "height-map":
        others = " or ".join(s for s in _INDENTERS if s != "height-map")
        raise InputError(
            f"roughness is for indenter {others}, not height-map: give the array as height_map "
            "to run it as the indenter"
        )


def request(params: Dict[str, Any]) -> Tuple[str, Optional[Tuple[bytes, int, int]]]:
    """The JSON request of the keywords given (None: not given) and the array of a height map
    (or of the roughness added to a base shape)."""
    given: Dict[str, Any] = {}
    heights = None
    for name, value in params.items():
        if value is None:
            continue
        if name in ("height_map", "roughness") and isinstance(value, np.ndarray):
            if heights is not None:
                raise InputError("height_map and roughness: give one array (a height map has no base shape to add roughness to)")
            heights = _heights(name, value)
            _refuse_foreign_array(name, params.get("indenter"))
            continue
        if name == "fields":
            value = _fields(value)
        elif name == "extrapolate" and not isinstance(value, (bool, np.bool_)):
            given["extrapolate_grids"] = _plain(name, value)
            value = True
        given[name] = _plain(name, value)
    return json.dumps(given, allow_nan=False), heights


def signature(first: Tuple[str, ...] = ("ratio",), extra: Tuple[inspect.Parameter, ...] = ()) -> inspect.Signature:
    """A signature of every schema keyword with its default (None where the library chooses),
    the names in `first` positional, then `extra`."""
    P = inspect.Parameter
    params = [P(n, P.POSITIONAL_OR_KEYWORD, default=None) for n in first]
    for s in SCHEMA:
        if s["name"] not in first:
            params.append(P(s["name"], P.KEYWORD_ONLY, default=s["default"]))
    return inspect.Signature(params + list(extra))


def keyword_docs() -> str:
    """Every keyword with its unit, range, default and help, for a docstring."""
    lines = ["Keywords (from the library's schema):", ""]
    for s in SCHEMA:
        lines.append(f"``{s['name']}``: {s['help']} [{s['terms']}]" if s["terms"] else f"``{s['name']}``: {s['help']}")
        lines.append("")
    return "\n".join(lines)
