"""Warnings about an answer, issued through Python's :mod:`warnings` so that the usual filters
(``warnings.simplefilter``, ``pytest.warns``, ``-W error``) see them, each pointing at the line
of the user's code that asked for the run rather than at a line inside the package."""

from __future__ import annotations

import os
import sys
import warnings
from typing import Iterable, Type

__all__ = ["JkrbemWarning", "warn_all"]


class JkrbemWarning(UserWarning):
    """A warning about a jkrbem answer: too coarse a grid for the stated uncertainty, load
    steps too large to resolve the force minimum, CG solves accepted above their tolerance …
    The same texts are kept in :attr:`jkrbem.Result.warnings`."""


#: The package's folder: frames of files inside it are skipped when a warning is placed.
_PACKAGE = os.path.normcase(os.path.dirname(os.path.abspath(__file__))) + os.sep


def _inside_package(filename: str) -> bool:
    """Whether `filename` (a code object's) is one of the package's own files."""
    return os.path.normcase(os.path.abspath(filename)).startswith(_PACKAGE)


def _user_stacklevel() -> int:
    """The ``stacklevel`` for a :func:`warnings.warn` called from :func:`warn_all` that names
    the first frame outside the package: the user's call, however deep inside the package
    (``sweep`` → ``simulate`` …) the warning is raised."""
    frame = sys._getframe(1)  # warn_all's own frame: stacklevel 1 of its warnings.warn
    level = 1
    while frame is not None and _inside_package(frame.f_code.co_filename):
        frame = frame.f_back
        level += 1
    return level


def warn_all(texts: Iterable[str], category: Type[Warning] = JkrbemWarning) -> None:
    """Issue each distinct text of `texts` once, in order, as a `category` warning
    (:class:`JkrbemWarning` unless told) that points at the user's call."""
    level = _user_stacklevel()
    seen = set()
    for text in texts:
        if text in seen:
            continue
        seen.add(text)
        warnings.warn(text, category, stacklevel=level)
