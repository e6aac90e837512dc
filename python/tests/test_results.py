"""What a run hands back, beyond the numbers: its warnings through Python's ``warnings``, the
progress display with and without tqdm, the states as a pandas DataFrame, short reprs, and
the adhesive force (with the force in the user's units) for every indenter."""

import io
import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import jkrbem
from jkrbem import _progress

#: A one-grid run that warns (too coarse a grid: 6 elements across the minor axis), in 0.2 s.
COARSE = dict(ratio=5, grid=32, backend="cpu")

#: The small runs of the tests that are not about warnings warn that they are coarse.
quiet = pytest.mark.filterwarnings("ignore::jkrbem.JkrbemWarning")

HERE = str(Path(__file__).resolve())


# --- 1. warnings ----------------------------------------------------------------------------


def test_a_coarse_run_issues_each_of_its_warnings_as_a_jkrbem_warning_at_the_callers_line():
    with pytest.warns(jkrbem.JkrbemWarning) as caught:
        r = jkrbem.simulate(**COARSE)
    ours = [w for w in caught if issubclass(w.category, jkrbem.JkrbemWarning)]
    # Once per warning, and r.warnings keeps them.
    assert r.warnings and sorted(str(w.message) for w in ours) == sorted(set(r.warnings))
    assert "too coarse a grid" in str(ours[0].message)
    # It points at this file (the user's call), not at the package.
    assert all(w.filename == HERE for w in ours), [w.filename for w in ours]
    assert issubclass(jkrbem.JkrbemWarning, UserWarning)


@pytest.mark.parametrize("call", [
    lambda: jkrbem.pulloff(5, grid=32, backend="cpu"),
    lambda: jkrbem.sweep_results([5], grid=32, backend="cpu"),
])
def test_warnings_point_at_the_callers_line_however_deep_in_the_package(call):
    with pytest.warns(jkrbem.JkrbemWarning) as caught:
        call()
    assert all(w.filename == HERE for w in caught if issubclass(w.category, jkrbem.JkrbemWarning))


def test_jkrbem_warnings_obey_the_warnings_filters():
    with warnings.catch_warnings():
        warnings.simplefilter("error", jkrbem.JkrbemWarning)
        with pytest.raises(jkrbem.JkrbemWarning, match="too coarse"):
            jkrbem.simulate(**COARSE)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.filterwarnings("ignore", category=jkrbem.JkrbemWarning)
        r = jkrbem.simulate(**COARSE)  # silenced, yet kept
    assert r.warnings


def test_a_run_without_warnings_issues_none():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = jkrbem.simulate(ratio=1, grid=64, backend="cpu")
    assert r.warnings == []


# --- 2. progress ----------------------------------------------------------------------------


def hide(monkeypatch, *modules):
    """Make `modules` unimportable (as if not installed) for one test."""
    for name in modules:
        monkeypatch.setitem(sys.modules, name, None)


@quiet
def test_progress_true_without_tqdm_writes_plain_lines_to_stderr(monkeypatch, capsys):
    hide(monkeypatch, "tqdm", "tqdm.auto")
    r = jkrbem.simulate(ratio=1, grid=32, backend="cpu", progress=True)
    assert r.complete
    err = capsys.readouterr().err
    lines = err.splitlines()
    # The note, then the grid's start at once; later lines at most every PLAIN_EVERY_S.
    assert any(line.startswith("jkrbem: grid 32×32 started") for line in lines), err
    assert all(line.startswith("jkrbem: ") for line in lines), err
    progress_lines = [line for line in lines if line.startswith("jkrbem: grid")]
    assert len(progress_lines) <= 1 + r.summary["wall_s"] / _progress.PLAIN_EVERY_S + 1, err


def test_the_plain_display_writes_at_most_one_progress_line_every_few_seconds():
    now = [0.0]
    out = io.StringIO()
    show = _progress.PlainProgress(stream=out, every_s=5.0, clock=lambda: now[0])
    show({"event": "note", "text": "one grid"})
    show({"event": "start", "grid": [64, 64], "expected_steps": 200})
    for step in range(1, 81):  # 80 states, 0.25 s apart: 20 s
        now[0] += 0.25
        show({"event": "state", "grid": [64, 64], "step": step, "f_bar": -0.4, "c_bar": 0.8})
    show({"event": "warning", "text": "too coarse a grid"})
    now[0] += 1.0
    show({"event": "end", "grid": [64, 64]})
    lines = out.getvalue().splitlines()
    assert lines[0] == "jkrbem: one grid"
    assert lines[1] == "jkrbem: grid 64×64 started, about 200 steps"
    states = [line for line in lines if "step " in line]
    assert len(states) == 4, lines  # at 5, 10, 15 and 20 s
    assert "step 20/200, F̄ = -0.4000, c̄ = 0.800, 5 s" in states[0]
    assert "jkrbem: warning: too coarse a grid" in lines  # notes and warnings at once
    assert not any("done" in line for line in lines), "the end came 1 s after the last line"


@quiet
def test_progress_true_uses_tqdm_where_installed(capsys):
    pytest.importorskip("tqdm")
    jkrbem.simulate(ratio=1, grid=32, backend="cpu", progress=True)
    err = capsys.readouterr().err
    assert "grid 32×32:" in err and "|" in err, err  # tqdm's bar, with the grid as its description
    assert "jkrbem: grid" not in err, "not the plain display"


def test_progress_true_never_raises_import_error_even_with_a_broken_tqdm(monkeypatch):
    class Broken:
        def __getattr__(self, name):
            raise RuntimeError("a broken tqdm")

    monkeypatch.setitem(sys.modules, "tqdm.auto", Broken())
    assert isinstance(_progress.display(True), _progress.PlainProgress)


# --- 3. DataFrame ---------------------------------------------------------------------------


@quiet
def test_to_dataframe_holds_every_runs_states_with_run_and_grid_columns():
    pd = pytest.importorskip("pandas")
    r = jkrbem.simulate(ratio=1, extrapolate=[32, 64], backend="cpu")
    assert len(r.runs) == 2
    df = r.to_dataframe()
    assert isinstance(df, pd.DataFrame)
    names = [name for name, _ in jkrbem.STATE_COLUMNS]
    assert list(df.columns) == ["run", "nx", "ny"] + names
    assert len(df) == sum(len(run.states) for run in r.runs)
    for i, run in enumerate(r.runs):
        part = df[df["run"] == i]
        assert (part["nx"] == run.grid[0]).all() and (part["ny"] == run.grid[1]).all()
        assert np.array_equal(part["f_bar"].to_numpy(), run.states["f_bar"])
        assert list(part["phase"]) == list(run.states["phase"])
    one = r.runs[0].to_dataframe()
    assert list(one.columns) == ["nx", "ny"] + names and len(one) == len(r.runs[0].states)


@quiet
def test_to_dataframe_without_pandas_says_how_to_install_it(monkeypatch):
    r = jkrbem.simulate(ratio=1, grid=32, backend="cpu", steps=20)
    hide(monkeypatch, "pandas")
    with pytest.raises(ImportError, match=r"pip install pandas.*jkrbem\[pandas\]"):
        r.to_dataframe()
    with pytest.raises(ImportError, match="pip install pandas"):
        r.runs[0].to_dataframe()


# --- 5. reprs -------------------------------------------------------------------------------


@quiet
def test_reprs_are_short_and_hold_the_key_numbers():
    r = jkrbem.simulate(ratio=1, grid=32, backend="cpu", fields="minimum")
    text = repr(r)
    assert len(text) <= 300, text
    assert f"{r.adhesive_force:.5g}" in text and f"{r.uncertainty:.3g}" in text
    assert "32×32" in text and f"{len(r.states)} states" in text and "complete" in text
    run = repr(r.runs[0])
    assert len(run) <= 300 and "32×32" in run and f"{len(r.states)} states" in run, run
    f = repr(r.fields[0])
    assert len(f) <= 300 and "force minimum" in f and "32×32" in f, f
    assert "INCOMPLETE" not in text + run


@quiet
def test_a_repr_stays_short_however_long_its_parts():
    run = jkrbem.Run(grid=(65536, 65536), dx=1e-300, complete=False, states=jkrbem.simulate(
        ratio=1, grid=32, backend="cpu", steps=20).states)
    result = jkrbem.Result(
        adhesive_force=1 / 3, uncertainty=1 / 7, estimate="x" * 500, jg=None, deviation_from_jg=None,
        c_bar_at_min=None, d_bar_at_min=None, runs=[run] * 8, summary={}, failure="y" * 1000,
        warnings=["z" * 1000] * 20, force_scale=math.pi,
    )
    assert len(repr(result)) <= 300 and len(repr(run)) <= 300
    assert "INCOMPLETE" in repr(run)


# --- 6. the adhesive force of every indenter ------------------------------------------------


def test_the_flat_punch_gives_its_grids_adhesive_force_and_kendalls_force():
    e_star, dgamma, a = 2.0, 0.5, 1.5
    r = jkrbem.simulate(indenter="flat_punch", radius=a, grid=32, e_star=e_star,
                        work_of_adhesion=dgamma, backend="cpu")
    own = r.summary["runs"][-1]["f_ad_bar"]
    assert r.adhesive_force == own == pytest.approx(-r.states["f_bar"].min(), rel=1e-12)
    assert r.uncertainty is None and r.estimate == "grid"
    assert r.c_bar_at_min == r.summary["runs"][-1]["c_bar_at_min"]
    # Kendall's |min F̄| = 1 is the limit; the grid is off by the summary's grid_error.
    limit = r.summary["exact_limit"]
    assert r.adhesive_force / limit["f_ad_bar"] - 1 == pytest.approx(limit["grid_error"], rel=1e-9)
    # In the user's units: F̄ times Kendall's force √(8π E* Δγ a³).
    kendall = math.sqrt(8 * math.pi * e_star * dgamma * a**3)
    assert r.force_scale == pytest.approx(kendall, rel=1e-12)
    assert r.adhesive_force_in_units == pytest.approx(r.adhesive_force * kendall, rel=1e-12)
    assert r.uncertainty_in_units is None


def test_the_power_law_gives_its_grids_adhesive_force_and_force_scale():
    n, s, e_star, dgamma = 4.0, 0.5, 1.0, 1.0
    r = jkrbem.simulate(indenter="power_law", exponent=n, scale=s, grid=32, backend="cpu")
    assert r.adhesive_force == r.summary["runs"][-1]["f_ad_bar"] > 0
    assert r.uncertainty is None and r.estimate == "grid"
    # docs/indenters.md: c_n = (9πΔγ/(16E*s²))^(1/(2n−1)), R_n = c_n^(2−n)/(2s), force 3π R_n Δγ.
    c_n = (9 * math.pi * dgamma / (16 * e_star * s * s)) ** (1 / (2 * n - 1))
    r_n = c_n ** (2 - n) / (2 * s)
    assert r.force_scale == pytest.approx(3 * math.pi * r_n * dgamma, rel=1e-12)
    assert r.adhesive_force_in_units == pytest.approx(r.adhesive_force * r.force_scale, rel=1e-15)


def test_the_ellipsoid_keeps_its_estimate_and_gives_the_force_in_the_users_units():
    r2, dgamma = 2.0, 0.3
    r = jkrbem.simulate(ratio=1, r2=r2, work_of_adhesion=dgamma, grid=64, backend="cpu")
    assert r.adhesive_force == r.summary["f_ad_bar"] and r.uncertainty == r.summary["f_ad_bar_uncertainty"]
    assert r.estimate == "single-grid"
    scale = 3 * math.pi * r2 * dgamma  # 3π Re Δγ, Re = √(R1 R2) = R2 for a sphere
    assert r.force_scale == pytest.approx(scale, rel=1e-12)
    assert r.adhesive_force_in_units == pytest.approx(r.force_in(r2, dgamma), rel=1e-12)
    assert r.uncertainty_in_units == pytest.approx(r.uncertainty * scale, rel=1e-12)


@quiet
def test_a_summary_that_states_its_force_scale_is_taken_at_its_word():
    r = jkrbem.simulate(ratio=1, grid=32, backend="cpu", steps=20)
    stated = dict(r.summary, force_scale=2.0)
    again = jkrbem._results.result_from(stated, r.runs, [])
    assert again.force_scale == 2.0
