"""The checks of the keywords that are not a simulation's (a simulation's keywords are checked
by the library against its schema): ``crossed``'s, ``theory``'s, ``sweep``'s ratios, a
batch's ``processes``. Each value of the type it is meant to be (Python and numpy numbers
alike, never a bool where a number is meant, never a float where an integer is) and finite. A
refusal is a :class:`TypeError` (wrong type) or an :class:`InputError` (a ValueError: wrong
value) whose message names the keyword and says what is expected. The ranges themselves are
the library's (``_jkrbem.limits()``)."""

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




def text(name: str, value: Any, what: str) -> str:
    """`value` as a str (the choices are the library's to check)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} = {shown(value)} is invalid: {what} is expected, not {_type_name(value)}")
    return value




def flag(name: str, value: Any, what: str) -> bool:
    """`value` as a bool: True or False (numpy's too), never a number or a string."""
    if not _is_bool(value):
        raise TypeError(f"{name} = {shown(value)} is invalid: {what} is expected, not {_type_name(value)}")
    return bool(value)


def unmasked(name: str, value: Any) -> None:
    """Refuse a numpy masked array: a masked value has no number, and the data hidden under
    its mask is what numpy would hand on (a masked array with nothing masked is refused too,
    so that an answer never depends on what a mask happens to hide)."""
    if isinstance(value, np.ma.MaskedArray):
        raise TypeError(
            f"{name} is invalid: a masked array is not taken (a masked value has no number, "
            "and the one hidden under the mask would be read): give a plain numpy array, "
            "e.g. a.filled(value)"
        )


#: The dtypes of an array that is not one of real numbers, in words.
_NOT_REAL = {
    "c": "a complex array",
    "b": "a bool array",
    "O": "an object array",
    "U": "an array of strings",
    "S": "an array of bytes",
    "M": "an array of dates",
    "m": "an array of time spans",
    "V": "an array of records",
}

#: What to do with an array of such a dtype, where there is a likely remedy.
_REMEDY = {
    "c": ": give its real part (a.real) if that is what is meant",
    "O": ": convert it, a.astype(float)",
    "U": ": convert it, a.astype(float)",
    "S": ": convert it, a.astype(float)",
}


def real_array(name: str, value: np.ndarray, what: str) -> np.ndarray:
    """`value` (a numpy array) checked to hold real numbers, a float or integer dtype, as
    `what`: a masked array, and one of complex numbers, bools, objects, strings, dates or
    records are refused (numpy would turn each into floats without a word, dropping an
    imaginary part, reading a bool as 0 or 1, parsing a string), naming `name`."""
    unmasked(name, value)
    kind = value.dtype.kind
    if kind not in "fiu":
        words = _NOT_REAL.get(kind, "an array")
        raise TypeError(
            f"{name} is invalid: {what} (real numbers: a float or integer dtype) is expected, "
            f"not {words} ({value.dtype}){_REMEDY.get(kind, '')}"
        )
    return value


def items(name: str, value: Any, what: str) -> List[Any]:
    """`value` as a list: a list, tuple, range or 1-D numpy array (not a masked one), never a
    string (whose characters would be taken one by one), a dict, a set or a scalar."""
    if isinstance(value, np.ndarray):
        unmasked(name, value)
        if value.ndim != 1:
            raise TypeError(f"{name} is invalid: {what} is expected, not a {value.ndim}-D array")
        return list(value)
    if isinstance(value, (list, tuple, range)):
        return list(value)
    raise TypeError(f"{name} = {shown(value)} is invalid: {what} is expected, not {_type_name(value)}")




def ratio(name: str, value: Any) -> float:
    """An axis ratio R1/R2 in [1, the library's largest]."""
    hi = LIMITS["max_ratio"]
    what = f"an axis ratio R1/R2 in [1, {hi:g}]"
    r = real(name, value, what)
    if not 1.0 <= r <= hi:
        raise InputError(f"{name} = {r:g} is invalid: {what}")
    return r
