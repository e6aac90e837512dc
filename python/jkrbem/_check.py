"""The checks every keyword of the package passes before a request is built: each value of the
type it is meant to be (Python and numpy numbers alike, never a bool where a number is meant,
never a float where an integer is), finite, and within what the JSON request can carry. A
refusal is a :class:`TypeError` (wrong type) or an :class:`InputError` (a ValueError: wrong
value) whose message names the keyword and says what is expected. The ranges themselves are
the library's (``_jkrbem.limits()``); what only the library can judge (a power of two, R1 ≥ R2
…) it refuses, naming the keyword too."""

from __future__ import annotations

import json
import math
import numbers
import operator
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from . import _jkrbem
from ._jkrbem import InputError

#: The library's ranges: grid sides, load steps, R1/R2, closed-form points, time limit (s).
LIMITS = json.loads(_jkrbem.limits())

#: Longest part of a refused value a message shows (characters).
_SHOWN = 60


def shown(value: Any) -> str:
    """`value` for a message: its repr, shortened; a huge integer by its size."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 64:
        return f"an integer of about {int(value.bit_length() * math.log10(2)) + 1} digits"
    try:
        text = repr(value)
    except Exception:  # a hostile __repr__ must not hide the refusal
        text = f"<{type(value).__name__}>"
    return text if len(text) <= _SHOWN else text[: _SHOWN - 1] + "…"


def _type_name(value: Any) -> str:
    return type(value).__name__


def _is_bool(value: Any) -> bool:
    return isinstance(value, (bool, np.bool_))


def real(name: str, value: Any, what: str = "a number") -> float:
    """`value` as a finite float: an int, a float or a numpy scalar (not a bool, a string,
    None or a complex number). -0.0 is 0.0."""
    if _is_bool(value) or not isinstance(value, (numbers.Real, np.integer, np.floating)):
        raise TypeError(f"{name} = {shown(value)} is invalid: {what} is expected, not {_type_name(value)}")
    try:
        x = float(value)
    except OverflowError:
        raise InputError(f"{name} = {shown(value)} is invalid: {what} within the range of a float") from None
    if not math.isfinite(x):
        raise InputError(f"{name} = {x} is invalid: {what}, finite (not nan or inf)")
    return x + 0.0


def optional_real(name: str, value: Any, what: str = "a number") -> Optional[float]:
    """None, or :func:`real`."""
    return None if value is None else real(name, value, what)


def integer(name: str, value: Any, low: int, high: int, what: str) -> int:
    """`value` as an int in [`low`, `high`]: an int or a numpy integer (not a bool, nor a
    float even if integral: 32.0 is refused as 32.5 is)."""
    if _is_bool(value):
        raise TypeError(f"{name} = {value!r} is invalid: {what} is expected, not a bool")
    try:
        i = operator.index(value)
    except TypeError:
        raise TypeError(
            f"{name} = {shown(value)} is invalid: {what} is expected (an integer, not {_type_name(value)})"
        ) from None
    if not low <= i <= high:
        raise InputError(f"{name} = {shown(i)} is invalid: {what} is expected")
    return i


def optional_integer(name: str, value: Any, low: int, high: int, what: str) -> Optional[int]:
    """None, or :func:`integer`."""
    return None if value is None else integer(name, value, low, high, what)


def text(name: str, value: Any, what: str) -> str:
    """`value` as a str (the choices are the library's to check)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} = {shown(value)} is invalid: {what} is expected, not {_type_name(value)}")
    return value


def optional_text(name: str, value: Any, what: str) -> Optional[str]:
    """None, or :func:`text`."""
    return None if value is None else text(name, value, what)


def flag(name: str, value: Any, what: str) -> bool:
    """`value` as a bool: True or False (numpy's too), never a number or a string."""
    if not _is_bool(value):
        raise TypeError(f"{name} = {shown(value)} is invalid: {what} is expected, not {_type_name(value)}")
    return bool(value)


def items(name: str, value: Any, what: str) -> List[Any]:
    """`value` as a list: a list, tuple, range or 1-D numpy array, never a string (whose
    characters would be taken one by one), a dict, a set or a scalar."""
    if isinstance(value, np.ndarray):
        if value.ndim != 1:
            raise TypeError(f"{name} is invalid: {what} is expected, not a {value.ndim}-D array")
        return list(value)
    if isinstance(value, (list, tuple, range)):
        return list(value)
    raise TypeError(f"{name} = {shown(value)} is invalid: {what} is expected, not {_type_name(value)}")


def grid_side(name: str, value: Any) -> int:
    """A grid side: an integer (the library checks that it is a power of two)."""
    lo, hi = LIMITS["min_grid"], LIMITS["max_grid"]
    return integer(name, value, lo, hi, f"a power of two from {lo} to {hi} (e.g. 64, 128, 256)")


def ratio(name: str, value: Any) -> float:
    """An axis ratio R1/R2 in [1, the library's largest]."""
    hi = LIMITS["max_ratio"]
    what = f"an axis ratio R1/R2 in [1, {hi:g}]"
    r = real(name, value, what)
    if not 1.0 <= r <= hi:
        raise InputError(f"{name} = {r:g} is invalid: {what}")
    return r


def pair(name: str, value: Any, what: str) -> Tuple[float, float]:
    """Two finite numbers."""
    values = items(name, value, what)
    if len(values) != 2:
        raise InputError(f"{name} = {shown(value)} is invalid: {what} is expected")
    return real(name, values[0], what), real(name, values[1], what)


def conflict(given: Sequence[Tuple[str, bool]], why: str) -> None:
    """Refuse keywords given together that cannot be (each pair: a name, whether given)."""
    names = [n for n, g in given if g]
    if len(names) > 1:
        raise InputError(f"{' and '.join(names)} cannot be given together: {why}")
