"""jkrbem.roughness: the asked rms is met exactly, the spectrum lies in its band on the axes
the map's readers use, a seed gives one surface (the CLI's too), and bad keywords are refused
by name. The spectral statistics are recomputed here with numpy's FFT, independently of the
library's."""

import json
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import jkrbem

ROOT = Path(__file__).resolve().parents[2]


def wavenumbers(shape, spacing):
    """|q| (1/length) of each coefficient of rfft2 of an array of `shape` (ny, nx)."""
    ny, nx = shape
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=spacing)
    qx = 2 * np.pi * np.fft.rfftfreq(nx, d=spacing)
    return np.hypot(qx[None, :], qy[:, None])


def spectral_rms(heights, spacing, power):
    """√(Σ |q|^power |H|² / N²) over the full spectrum, from numpy's FFT."""
    h = np.fft.fft2(heights)
    ny, nx = heights.shape
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=spacing)
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=spacing)
    q = np.hypot(qx[None, :], qy[:, None])
    return math.sqrt(float(np.sum(q**power * np.abs(h) ** 2)) / heights.size**2)


def test_the_rms_height_or_slope_asked_for_is_met_exactly():
    r = jkrbem.roughness(64, 0.5, 0.8, rms_height=0.2, seed=3, grid_y=48)
    assert isinstance(r, jkrbem.Roughness)
    assert r.heights.shape == (48, 64) and r.heights.dtype == np.float64
    assert r.spacing == 0.5
    assert abs(r.heights.mean()) < 1e-12 * 0.2
    assert math.isclose(float(r.heights.std()), 0.2, rel_tol=1e-9)
    assert math.isclose(r.statistics["rms_height"], 0.2, rel_tol=1e-9)
    # The defaults, filled in: λ_L the longer side, λ_r = λ_L, λ_s four spacings.
    assert r.params["largest_wavelength"] == 32.0
    assert r.params["rolloff"] == 32.0
    assert r.params["cutoff"] == 2.0
    assert r.params["grid_y"] == 48 and r.params["seed"] == 3
    assert r.params["rms_slope"] is None
    # The statistics agree with numpy's spectral ones (slope: |q|², curvature: ½|q|² squared).
    assert math.isclose(r.statistics["rms_slope"], spectral_rms(r.heights, 0.5, 2), rel_tol=1e-9)
    assert math.isclose(r.statistics["rms_curvature"], 0.5 * spectral_rms(r.heights, 0.5, 4), rel_tol=1e-9)

    s = jkrbem.roughness(32, 1.0, 0.5, rms_slope=0.1, rolloff=16.0, cutoff=4.0)
    assert math.isclose(spectral_rms(s.heights, 1.0, 2), 0.1, rel_tol=1e-9)
    assert math.isclose(s.statistics["rms_slope"], 0.1, rel_tol=1e-9)


def test_the_spectrum_lies_in_its_band_along_the_maps_axes():
    # 64 × 16 nodes with λ_L = 64: only the long axis (x, axis 1) holds waves that long, so
    # the band [2π/64, 2π/4] is met only if axis 1 is x.
    r = jkrbem.roughness(64, 1.0, 0.7, rms_height=1.0, grid_y=16, seed=5)
    power = np.abs(np.fft.rfft2(r.heights)) ** 2
    q = wavenumbers(r.heights.shape, 1.0)
    inside = (q >= 2 * np.pi / 64 * (1 - 1e-9)) & (q <= 2 * np.pi / 4 * (1 + 1e-9))
    top = power.max()
    assert np.all(power[~inside] < 1e-20 * top)
    assert np.all(power[inside] > 1e-20 * top)
    assert power[0, 1] > 1e-20 * top  # the wave of length 64 along x


def test_one_seed_one_surface():
    a = jkrbem.roughness(32, 1.0, 0.6, rms_height=1.0, seed=7)
    b = jkrbem.roughness(32, 1.0, 0.6, rms_height=1.0, seed=7)
    c = jkrbem.roughness(32, 1.0, 0.6, rms_height=1.0, seed=8)
    assert np.array_equal(a.heights, b.heights)
    assert not np.allclose(a.heights, c.heights)
    # The parameters given back give the surface again.
    again = jkrbem.roughness(**{k: v for k, v in a.params.items() if k != "rms_slope"})
    assert np.array_equal(again.heights, a.heights)


def cli_binary():
    """The jkrbem command: JKRBEM_CLI, else the worktree's release build."""
    named = os.environ.get("JKRBEM_CLI")
    for c in ([Path(named)] if named else []) + [ROOT / "target/release/jkrbem"]:
        if c.is_file() and os.access(c, os.X_OK):
            return c
    return None


def test_the_command_line_makes_the_same_surface(tmp_path):
    cli = cli_binary()
    if cli is None:
        pytest.skip("no jkrbem binary built (cargo build --release)")
    args = ["roughness", "--out", "s.npy", "--grid", "40", "--grid-y", "24", "--spacing", "0.25",
            "--hurst", "0.9", "--rms-slope", "0.3", "--cutoff", "1", "--seed", "11"]
    done = subprocess.run([str(cli), *args], cwd=tmp_path, capture_output=True, text=True)
    if done.returncode != 0 and "unrecognized subcommand" in done.stderr:
        pytest.skip("the jkrbem binary predates the roughness command")
    assert done.returncode == 0, done.stderr
    r = jkrbem.roughness(40, 0.25, 0.9, rms_slope=0.3, cutoff=1.0, seed=11, grid_y=24)
    on_disk = np.load(tmp_path / "s.npy")
    assert on_disk.shape == (24, 40)
    np.testing.assert_allclose(on_disk, r.heights, rtol=0, atol=1e-12 * float(r.heights.std()))
    meta = json.loads((tmp_path / "s.json").read_text())
    assert meta["params"] == r.params
    assert meta["generator"] == r.generator


@pytest.mark.parametrize(
    "kwargs, keyword, error",
    [
        (dict(hurst=1.5), "hurst", jkrbem.InputError),
        (dict(hurst=float("nan")), "hurst", jkrbem.InputError),
        (dict(rms_slope=0.1), "rms_slope", jkrbem.InputError),
        (dict(rms_height=None), "rms_height", jkrbem.InputError),
        (dict(cutoff=0.5), "cutoff", jkrbem.InputError),
        (dict(rolloff=100.0), "rolloff", jkrbem.InputError),
        (dict(largest_wavelength=100.0), "largest_wavelength", jkrbem.InputError),
        (dict(grid=3), "grid", jkrbem.InputError),
        (dict(grid=32.0), "grid", TypeError),
        (dict(grid=True), "grid", TypeError),
        (dict(grid_y=20000), "grid_y", jkrbem.InputError),
        (dict(spacing="1"), "spacing", TypeError),
        (dict(spacing=0.0), "spacing", jkrbem.InputError),
        (dict(seed=-1), "seed", jkrbem.InputError),
        (dict(seed=1.0), "seed", TypeError),
    ],
)
def test_bad_keywords_are_refused_by_name(kwargs, keyword, error):
    given = dict(grid=32, spacing=1.0, hurst=0.8, rms_height=1.0)
    given.update(kwargs)
    with pytest.raises(error) as caught:
        jkrbem.roughness(**given)
    message = str(caught.value)
    assert keyword in message, message
    assert "--" not in message and "⟨" not in message, message
