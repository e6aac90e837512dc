"""Type stubs of the compiled part of jkrbem (``jkrbem._jkrbem``). Use the package's own
functions (``jkrbem.simulate`` …): these take and return JSON text."""

from typing import Any, Callable, Dict, List, Optional, Tuple

__version__: str

class InputError(ValueError):
    """A parameter is out of its range or the combination cannot run; names the keyword."""

    parameter: Optional[str]

class SolveError(RuntimeError):
    """A run failed after it started; ``result`` keeps the partial states."""

    result: Any
    parameter: Optional[str]

def simulate(
    request: str,
    progress: Optional[Callable[[Dict[str, Any]], Any]] = ...,
    height_map: Optional[Tuple[bytes, int, int]] = ...,
) -> Tuple[str, List[Dict[str, Any]]]:
    """Run a simulation (the keywords given, as JSON; a height map's f64 bytes, ny, nx): the
    answer as JSON and the fields as dicts of bytes."""

def batch(
    requests: str, processes: int = ..., progress: Optional[Callable[[Dict[str, Any]], Any]] = ...
) -> List[Tuple[Optional[str], List[Dict[str, Any]], Optional[Tuple[str, str]]]]:
    """Run a batch of simulations (a JSON list of requests): per scene, its answer as JSON and
    its fields, or None and why it has none (kind, message)."""

def plan(request: str, height_map: Optional[Tuple[bytes, int, int]] = ...) -> str:
    """What a run to the request's accuracy would do, as JSON."""

def schema() -> str:
    """Every keyword of a simulation (name, unit, kind, default, terms, help), as JSON."""

def theory_curve(model: str, ratio: float, points: int) -> str:
    """A closed-form curve (c̄, F̄, d̄, ā, b̄ per point) as JSON."""

def theory_pull_off(model: str, ratio: float) -> str:
    """A closed form's force minimum and end of contact as JSON."""

def reference_table_csv() -> str:
    """The reference table of converged adhesive forces, as CSV text."""

def devices() -> str:
    """The GPU adapters wgpu sees, best first, as JSON."""

def crossed_scene(radius: float, young: float, poisson: float, work_of_adhesion: float, angle: float) -> str:
    """The equivalent ellipsoid of crossed cylinders (R1, R2, E*, force scale) as JSON."""

def limits() -> str:
    """The library's ranges the package checks its keywords against (grid sides, load steps,
    R1/R2, closed-form points, time limit in s), as JSON."""

def roughness(request: str) -> Tuple[str, bytes]:
    """A random self-affine surface (its keywords as JSON): the generator's version, the
    parameters with defaults filled in and the statistics as JSON, and the heights' f64 bytes
    (native order, row-major (ny, nx))."""

def _panic_for_tests() -> None:
    """Panics on purpose inside the guard every function has: raises SolveError (tests only)."""
