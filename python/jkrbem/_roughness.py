"""``jkrbem.roughness``: a random self-affine rough surface by Fourier synthesis, the same
generator as the command line's ``jkrbem roughness`` (same parameters and seed, same surface)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any, Dict, Optional

import numpy as np

from . import _check, _jkrbem

#: Fewest and most nodes along each side of a surface.
_MIN_NODES, _MAX_NODES = 4, 16384
_NODES = f"a whole number of nodes from {_MIN_NODES} to {_MAX_NODES}"


@dataclass(frozen=True)
class Roughness:
    """A generated surface.

    ``heights``: float64 array of shape (ny, nx) in the spacing's length unit, zero mean;
    ``heights[j, i]`` is node (i, j), x along axis 1, as ``simulate(height_map=...)`` and
    ``simulate --height-map`` read a map. ``spacing``: the nodes' spacing (length).
    ``params``: every parameter with its default filled in (``grid``, ``grid_y``,
    ``spacing``, ``hurst``, ``rms_height`` or ``rms_slope``, ``rolloff``, ``cutoff``,
    ``largest_wavelength`` (lengths), ``seed``): passing them back gives the same surface.
    ``statistics``: ``mean`` and ``rms_height`` (length), ``rms_slope`` (the spectral rms of
    |∇h|, dimensionless) and ``rms_curvature`` (the spectral rms of ½∇²h, 1/length).
    ``generator``: the generator's version."""

    heights: np.ndarray
    spacing: float
    params: Dict[str, Any]
    statistics: Dict[str, float]
    generator: str


def _length(name: str, value: Any) -> Optional[float]:
    return None if value is None else _check.real(name, value)


def roughness(
    grid: int,
    spacing: float,
    hurst: float,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
    rolloff: Optional[float] = None,
    cutoff: Optional[float] = None,
    seed: int = 0,
    grid_y: Optional[int] = None,
    largest_wavelength: Optional[float] = None,
) -> Roughness:
    """A periodic random self-affine surface on ``grid`` × ``grid_y`` nodes (x by y; ``grid_y``
    defaults to ``grid``; 4 to 16384 each, any count) at ``spacing`` (length L).

    Its power spectrum is isotropic: C(q) ∝ q^(−2(1+H)) with the Hurst exponent ``hurst`` H in
    (0, 1] between the roll-off wavelength ``rolloff`` λ_r and the cut-off ``cutoff`` λ_s,
    flat from λ_r up to ``largest_wavelength`` λ_L, zero outside (lengths in L). Defaults:
    λ_L the domain's longer side max(grid, grid_y)·spacing, λ_r = λ_L (no plateau), λ_s four
    spacings (the shortest wave sampled by 4 nodes; at least 2, the Nyquist wavelength).
    Exactly one of ``rms_height`` (L, over the nodes) and ``rms_slope`` (the spectral rms of
    |∇h|) is given, and met exactly. ``seed`` (0 to 2⁶⁴ − 1) picks the random numbers: the same
    parameters and seed give the same surface on every machine (to the rounding of the FFT).

    Raises :class:`InputError` (a ValueError) for a bad value and :class:`TypeError` for one
    of the wrong type, each naming the keyword; an InputError naming ``grid`` and ``grid_y``,
    before any work, for a surface past the memory available (about 32 bytes per node while it
    is generated; ``JKRBEM_MEMORY_LIMIT``, in bytes, plans for less) or past 8192² nodes in all.

    >>> r = roughness(64, 0.5, 0.8, rms_height=0.1, seed=1)
    >>> r.heights.shape, round(float(r.heights.std()), 12)
    ((64, 64), 0.1)
    """
    request = {
        "grid": _check.integer("grid", grid, _MIN_NODES, _MAX_NODES, _NODES),
        "grid_y": None if grid_y is None else _check.integer("grid_y", grid_y, _MIN_NODES, _MAX_NODES, _NODES),
        "spacing": _check.real("spacing", spacing),
        "hurst": _check.real("hurst", hurst),
        "rms_height": _length("rms_height", rms_height),
        "rms_slope": _length("rms_slope", rms_slope),
        "rolloff": _length("rolloff", rolloff),
        "cutoff": _length("cutoff", cutoff),
        "largest_wavelength": _length("largest_wavelength", largest_wavelength),
        "seed": _check.integer("seed", seed, 0, 2**64 - 1, "a whole number from 0 to 2**64 - 1"),
    }
    answer, data = _jkrbem.roughness(json.dumps(request))
    meta = json.loads(answer)
    params = meta["params"]
    heights = np.frombuffer(data, dtype=np.float64).reshape(params["grid_y"], params["grid"]).copy()
    return Roughness(
        heights=heights,
        spacing=params["spacing"],
        params=params,
        statistics=meta["statistics"],
        generator=meta["generator"],
    )
