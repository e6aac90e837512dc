"""What ``progress=`` shows: the user's callable, a tqdm bar (``progress=True`` where tqdm is
installed: ``pip install 'jkrbem[progress]'``), or, without tqdm, a plain line on stderr at
most every few seconds. ``progress=True`` never fails for want of tqdm."""

from __future__ import annotations

import sys
import time
from typing import Any, Callable, Dict, Optional, TextIO, Union

from . import _check

__all__ = ["display", "PlainProgress"]

_PROGRESS = "None, True or False (a progress bar), or a callable taking an event dict"

#: Shortest time between two progress lines of the plain display (s).
PLAIN_EVERY_S = 5.0


def _grid(event: Dict[str, Any]) -> str:
    """An event's grid as "Nx×Ny"."""
    nx, ny = event["grid"]
    return f"{nx}×{ny}"


class PlainProgress:
    """The display of ``progress=True`` without tqdm: one short line on `stream` (stderr by
    default, looked up at each line) at most every `every_s` seconds, of the grid, its step
    and the latest F̄ and c̄ (dimensionless); a run's notes and warnings are written at once,
    each on its own line. `clock` gives seconds (``time.monotonic``; tests pass their own)."""

    def __init__(
        self,
        stream: Optional[TextIO] = None,
        every_s: float = PLAIN_EVERY_S,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self._stream = stream
        self._every_s = every_s
        self._clock = clock
        self._last: Optional[float] = None  # when the last progress line was written (s)
        self._started = 0.0  # when the current grid started (s)
        self._total: Optional[int] = None  # the current grid's expected steps

    def _write(self, line: str) -> None:
        stream = self._stream if self._stream is not None else sys.stderr
        stream.write(line + "\n")
        stream.flush()

    def _due(self) -> bool:
        """Whether a progress line may be written now (and, if so, marks it written)."""
        now = self._clock()
        if self._last is not None and now - self._last < self._every_s:
            return False
        self._last = now
        return True

    def __call__(self, event: Dict[str, Any]) -> None:
        """Show one event of the run (a dict, as ``progress=`` callables receive)."""
        kind = event.get("event")
        if kind == "note":
            self._write(f"jkrbem: {event['text']}")
        elif kind == "warning":
            self._write(f"jkrbem: warning: {event['text']}")
        elif kind == "start":
            self._started = self._clock()
            self._total = event.get("expected_steps")
            if self._due():
                total = "" if self._total is None else f", about {self._total} steps"
                self._write(f"jkrbem: grid {_grid(event)} started{total}")
        elif kind == "state":
            if self._due():
                of = "" if self._total is None else f"/{self._total}"
                self._write(
                    f"jkrbem: grid {_grid(event)}, step {event['step']}{of}, "
                    f"F̄ = {event['f_bar']:.4f}, c̄ = {event['c_bar']:.3f}, "
                    f"{self._clock() - self._started:.0f} s"
                )
        elif kind == "end":
            if self._due():
                self._write(f"jkrbem: grid {_grid(event)} done in {self._clock() - self._started:.1f} s")


def _tqdm_bar() -> Optional[Callable[[Dict[str, Any]], None]]:
    """A tqdm bar per grid, or None where tqdm cannot be imported."""
    try:
        from tqdm.auto import tqdm
    except Exception:  # not installed, or broken: the plain display takes over
        return None
    bars: Dict[str, Any] = {}

    def bar(event: Dict[str, Any]) -> None:
        kind = event["event"]
        if kind == "start":
            if "bar" in bars:
                bars["bar"].close()
            bars["bar"] = tqdm(total=event["expected_steps"], desc=f"grid {_grid(event)}")
        elif kind == "state" and "bar" in bars:
            b = bars["bar"]
            b.update(max(0, event["step"] - b.n))
            b.set_postfix(F=f"{event['f_bar']:.4f}", c=f"{event['c_bar']:.3f}")
        elif kind == "end" and "bar" in bars:
            bars.pop("bar").close()
        elif kind == "note":
            tqdm.write(f"jkrbem: {event['text']}", file=sys.stderr)
        elif kind == "warning":
            tqdm.write(f"jkrbem: warning: {event['text']}", file=sys.stderr)

    return bar


def display(progress: Union[None, bool, Callable[[dict], Any]]) -> Optional[Callable[[dict], Any]]:
    """The callable that sees a run's events for ``progress=``: the user's own, a tqdm bar
    (True, where tqdm imports), a :class:`PlainProgress` (True, without tqdm), or None."""
    if progress is None:
        return None
    if callable(progress):
        return progress
    if not _check.flag("progress", progress, _PROGRESS):
        return None
    return _tqdm_bar() or PlainProgress()
