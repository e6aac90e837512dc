"""Hostile inputs (issue 41, "Hardening, round three"): no input reaches a panic, every
refusal is an InputError (a ValueError) or a TypeError naming the keyword, numpy scalars are
numbers, nothing is coerced silently, and a slow progress callback cannot multiply a run's
time. Grids stay at 32 or 64 on the CPU so that the file runs in a few minutes."""

import time
import warnings

import numpy as np
import pytest

import jkrbem
from jkrbem import _jkrbem

FAST = {"backend": "cpu", "grid": 32}


def refused(call, keyword, kind=(jkrbem.InputError, TypeError)):
    """`call` raises `kind` (never a PanicException, a BaseException) naming `keyword`, in
    Python's words (no CLI flag, no JSON parser's position)."""
    try:
        call()
    except kind as e:
        message = str(e)
        assert keyword in message, f"{keyword!r} not named: {message}"
        assert "--" not in message, f"a CLI flag in a Python error: {message}"
        assert "bad request" not in message and "line 1 column" not in message, message
        assert "JSON" not in message, message
        assert len(message) < 600, f"a message that repeats a huge input: {len(message)} chars"
        return e
    except BaseException as e:  # noqa: B902 - a panic is what this test exists to catch
        pytest.fail(f"{type(e).__name__} (not {kind}) for {keyword}: {e}")
    pytest.fail(f"no error for {keyword}")


# HIGH 3: panics.


@pytest.mark.parametrize("limit", [1e300, 1e19, 1e20, 1e15, 30 * 86400 + 1])
def test_a_huge_time_limit_is_refused_naming_it_never_a_panic(limit):
    e = refused(lambda: jkrbem.simulate(ratio=1, backend="cpu", time_limit=limit), "time_limit")
    assert isinstance(e, jkrbem.InputError) and isinstance(e, Exception)
    assert "30 days" in str(e) and len(str(e)) < 150, str(e)


def test_a_panic_reaches_python_as_solve_error_not_panic_exception():
    # The last line of defence: every entry point runs inside a guard.
    with pytest.raises(jkrbem.SolveError, match="internal error") as e:
        _jkrbem._panic_for_tests()
    assert isinstance(e.value, Exception)


def test_the_compiled_functions_refuse_out_of_range_values_themselves():
    # Called directly (past the package's checks), the compiled part still refuses cleanly.
    refused(lambda: _jkrbem.theory_curve("jg", 2.0, 10**9), "points", jkrbem.InputError)
    refused(lambda: _jkrbem.theory_pull_off("jg", 1e300), "ratio", jkrbem.InputError)
    refused(lambda: _jkrbem.crossed_scene(0.01, 3e6, 0.5, 0.05, float("nan")), "angles")


# MEDIUM 8: every refusal names the keyword; numpy numbers are numbers.


@pytest.mark.parametrize(
    "kwargs, keyword, kind",
    [
        ({"grid": 32.5}, "grid", TypeError),
        ({"grid": 32.0}, "grid", TypeError),
        ({"grid": True}, "grid", TypeError),
        ({"grid": "32"}, "grid", TypeError),
        ({"grid": -32}, "grid", jkrbem.InputError),
        ({"grid": 10**30}, "grid", jkrbem.InputError),
        ({"grid": 10**5000}, "grid", jkrbem.InputError),
        ({"grid_y": -1}, "grid_y", jkrbem.InputError),
        ({"grid_y": 10**30}, "grid_y", jkrbem.InputError),
        ({"steps": 10**30}, "steps", jkrbem.InputError),
        ({"steps": -5}, "steps", jkrbem.InputError),
        ({"steps": 2.5}, "steps", TypeError),
        ({"ratio": 10**400}, "ratio", jkrbem.InputError),
        ({"ratio": "5"}, "ratio", TypeError),
        ({"ratio": True}, "ratio", TypeError),
        ({"ratio": 1 + 0j}, "ratio", TypeError),
        ({"ratio": float("inf")}, "ratio", jkrbem.InputError),
        ({"ratio": -0.0}, "ratio", jkrbem.InputError),
        ({"ratio": None, "r1": "2"}, "r1", TypeError),
        ({"r2": [1]}, "r2", TypeError),
        ({"work_of_adhesion": np.nan}, "work_of_adhesion", jkrbem.InputError),
        ({"indenter": 5}, "indenter", TypeError),
        ({"indenter": "cône"}, "indenter", jkrbem.InputError),
        ({"indenter": "x" * 100_000}, "indenter", jkrbem.InputError),
        ({"measure": 5}, "measure", TypeError),
        ({"onsets": 5}, "onsets", TypeError),
        ({"backend": 5}, "backend", TypeError),
        ({"mesh_angle": "0"}, "mesh_angle", TypeError),
        ({"margin": True}, "margin", TypeError),
        ({"apex_offset": (float("nan"), 0)}, "apex_offset", jkrbem.InputError),
        ({"apex_offset": "ab"}, "apex_offset", TypeError),
        ({"apex_offset": 5}, "apex_offset", TypeError),
        ({"apex_offset": ("a", 0)}, "apex_offset", TypeError),
        ({"apex_offset": (1, 2, 3)}, "apex_offset", jkrbem.InputError),
        ({"fields": {"a": 1}}, "fields", TypeError),
        ({"fields": 5}, "fields", TypeError),
        ({"fields": [-1]}, "fields", jkrbem.InputError),
        ({"fields": [10**30]}, "fields", jkrbem.InputError),
        ({"fields": []}, "fields", jkrbem.InputError),
        ({"fields": ("every", 2.5)}, "fields", TypeError),
        ({"fields": ("every", -1)}, "fields", jkrbem.InputError),
        ({"fields": ("every", 10**30)}, "fields", jkrbem.InputError),
        ({"fields": "x" * 100_000}, "fields", jkrbem.InputError),
        ({"time_limit": True, "grid": None}, "time_limit", TypeError),
        ({"time_limit": "5", "grid": None}, "time_limit", jkrbem.InputError),
        ({"time_limit": 10**400, "grid": None}, "time_limit", jkrbem.InputError),
    ],
)
def test_a_bad_keyword_is_refused_naming_it(kwargs, keyword, kind):
    args = {**FAST, **kwargs}
    args = {k: v for k, v in args.items() if not (k == "grid" and v is None)}
    if "ratio" not in args and "r1" not in args:
        args["ratio"] = 1
    refused(lambda: jkrbem.simulate(**args), keyword, kind)


@pytest.mark.parametrize(
    "accuracy, kind",
    [("nan%", jkrbem.InputError), ("inf", jkrbem.InputError), ("1e400%", jkrbem.InputError),
     (np.nan, jkrbem.InputError), ("two", jkrbem.InputError), (True, TypeError), ([2], TypeError)],
)
def test_a_bad_accuracy_is_refused_naming_it(accuracy, kind):
    # True is not 100 %: a bool is no number.
    refused(lambda: jkrbem.simulate(ratio=1, backend="cpu", accuracy=accuracy), "accuracy", kind)
    refused(lambda: jkrbem.plan(1, accuracy=accuracy), "accuracy", kind)


def test_numpy_scalars_are_numbers():
    # grid, steps and the ratio as numpy scalars run as the same Python numbers do.
    a = jkrbem.simulate(ratio=np.float32(2), grid=np.int64(32), steps=np.int32(20),
                        work_of_adhesion=np.float64(1), backend="cpu")
    b = jkrbem.simulate(ratio=2, grid=32, steps=20, backend="cpu")
    assert a.adhesive_force == b.adhesive_force
    assert a.summary["provenance"]["options"]["grid"] == 32
    p = jkrbem.pulloff(1, grid=np.int64(32), backend="cpu", fields=[np.int64(3)])
    assert [f.index for f in p.fields][0] == 3
    assert jkrbem.plan(np.int64(5), accuracy=np.float32(0.02))["target"] == pytest.approx(0.02)
    assert jkrbem.theory.adhesive_force(np.float32(2)) == jkrbem.theory.adhesive_force(2)
    assert len(jkrbem.theory.curve("jg", np.float64(2), np.int64(10))) == 10


def test_unknown_keywords_name_themselves():
    refused(lambda: jkrbem.simulate(ratio=1, foo=1, **FAST), "foo", TypeError)
    refused(lambda: jkrbem.sweep([1], foo=1, **FAST), "foo", TypeError)
    refused(lambda: jkrbem.crossed([90], foo=1, **FAST), "foo", TypeError)


def test_the_other_functions_refuse_bad_values_naming_them():
    refused(lambda: jkrbem.plan(ratio="5"), "ratio", TypeError)
    refused(lambda: jkrbem.plan(ratio=1e300), "ratio", jkrbem.InputError)
    refused(lambda: jkrbem.plan(margin=float("nan")), "margin", jkrbem.InputError)
    refused(lambda: jkrbem.crossed([90], radius="1", **FAST), "radius", TypeError)
    refused(lambda: jkrbem.crossed([90], poisson=True, **FAST), "poisson", TypeError)
    refused(lambda: jkrbem.crossed([90], young=10**400, **FAST), "young", jkrbem.InputError)
    refused(lambda: jkrbem.crossed([float("nan")], **FAST), "angles", jkrbem.InputError)
    refused(lambda: jkrbem.crossed([120], **FAST), "angles", jkrbem.InputError)
    refused(lambda: jkrbem.crossed(90, **FAST), "angles", TypeError)
    refused(lambda: jkrbem.crossed([], **FAST), "angles", jkrbem.InputError)
    refused(lambda: jkrbem.sweep(5, **FAST), "ratios", TypeError)
    refused(lambda: jkrbem.sweep([], **FAST), "ratios", jkrbem.InputError)
    refused(lambda: jkrbem.sweep([None], **FAST), "ratios", TypeError)
    refused(lambda: jkrbem.sweep([1, 2000], **FAST), "ratios", jkrbem.InputError)
    refused(lambda: jkrbem.theory.curve(points=10**30), "points", jkrbem.InputError)
    refused(lambda: jkrbem.theory.curve(points=10**8), "points", jkrbem.InputError)
    refused(lambda: jkrbem.theory.curve(points=2.5), "points", TypeError)
    refused(lambda: jkrbem.theory.curve(points=-1), "points", jkrbem.InputError)
    refused(lambda: jkrbem.theory.curve(model=5), "model", TypeError)
    refused(lambda: jkrbem.theory.curve(model="x" * 100_000), "model", jkrbem.InputError)
    refused(lambda: jkrbem.theory.curve(ratio=1e6), "ratio", jkrbem.InputError)
    refused(lambda: jkrbem.theory.pull_off(ratio=None), "ratio", TypeError)
    refused(lambda: jkrbem.theory.pull_off("hertz"), "model", jkrbem.InputError)
    refused(lambda: jkrbem.theory.adhesive_force("2"), "ratio", TypeError)
    refused(lambda: jkrbem.theory.adhesive_force(True), "ratio", TypeError)
    refused(lambda: jkrbem.theory.adhesive_force(float("nan")), "ratio", jkrbem.InputError)
    r = jkrbem.pulloff(1, grid=32, measure="adhesive_force", backend="cpu")
    refused(lambda: r.force_in("1", 1.0), "radius_e", TypeError)


# LOW: the theory's range as the CLI's.


@pytest.mark.parametrize("ratio", [1e300, 1e4, 1000.5, 0.5])
def test_the_theory_refuses_ratios_outside_the_cli_range(ratio):
    refused(lambda: jkrbem.theory.adhesive_force(ratio), "ratio", jkrbem.InputError)
    refused(lambda: jkrbem.theory.curve("jg", ratio, 10), "ratio", jkrbem.InputError)
    refused(lambda: jkrbem.theory.pull_off("jg", ratio), "ratio", jkrbem.InputError)


def test_the_theory_answers_at_the_ends_of_the_cli_range():
    assert jkrbem.theory.adhesive_force(1) == pytest.approx(0.5, abs=1e-12)
    assert 0 < jkrbem.theory.adhesive_force(1000) < 0.5


# LOW: the power law's default scale is the CLI's 0.5.


def test_the_power_law_scale_defaults_to_the_cli_half():
    default = jkrbem.simulate(indenter="power_law", exponent=2, grid=32, backend="cpu")
    half = jkrbem.simulate(indenter="power_law", exponent=2, scale=0.5, grid=32, backend="cpu")
    assert default.summary["provenance"]["scene"] == half.summary["provenance"]["scene"]
    assert default.adhesive_force == half.adhesive_force
    # h = 0.5·r² is the sphere of R = 1: the same as the ellipsoid at ratio 1, within the grid.
    sphere = jkrbem.simulate(ratio=1, grid=32, backend="cpu")
    assert default.summary["runs"][0]["f_ad_bar"] == pytest.approx(
        sphere.summary["runs"][0]["f_ad_bar"], rel=0.05)


# LOW: no silent coercion.


def test_a_string_is_not_a_list_of_ratios_or_angles():
    refused(lambda: jkrbem.sweep("12", **FAST), "ratios", TypeError)
    refused(lambda: jkrbem.crossed("90", **FAST), "angles", TypeError)


def test_fields_take_integral_state_indices_only():
    refused(lambda: jkrbem.simulate(ratio=1, fields=[1.5], **FAST), "fields", TypeError)
    refused(lambda: jkrbem.simulate(ratio=1, fields=[True], **FAST), "fields", TypeError)


@pytest.mark.parametrize("progress", [5, "yes", 1.0, [print]])
def test_progress_is_a_bool_or_a_callable(progress):
    refused(lambda: jkrbem.simulate(ratio=1, progress=progress, **FAST), "progress", TypeError)


def test_extrapolate_with_grid_is_a_conflict_naming_both():
    e = refused(lambda: jkrbem.simulate(ratio=1, backend="cpu", grid=64, extrapolate=True),
                "extrapolate", jkrbem.InputError)
    assert "grid" in str(e)
    e = refused(lambda: jkrbem.simulate(ratio=1, backend="cpu", grid_y=64, extrapolate=[32, 64]),
                "extrapolate", jkrbem.InputError)
    assert "grid_y" in str(e)


def test_accuracy_with_a_one_grid_keyword_is_a_conflict_naming_both():
    e = refused(lambda: jkrbem.simulate(ratio=1, backend="cpu", accuracy="5%", grid=32),
                "accuracy", jkrbem.InputError)
    assert "grid" in str(e)
    e = refused(lambda: jkrbem.simulate(ratio=1, backend="cpu", accuracy="5%", extrapolate=True),
                "accuracy", jkrbem.InputError)
    assert "extrapolate" in str(e)


def test_ratio_with_r1_and_shape_keywords_of_another_indenter_are_refused():
    e = refused(lambda: jkrbem.simulate(ratio=3, r1=2, **FAST), "ratio", jkrbem.InputError)
    assert "r1" in str(e)
    refused(lambda: jkrbem.simulate(ratio=1, radius=1.0, **FAST), "radius", jkrbem.InputError)
    refused(lambda: jkrbem.simulate(ratio=1, scale=0.5, **FAST), "scale", jkrbem.InputError)
    refused(lambda: jkrbem.simulate(indenter="flat_punch", radius=1.0, ratio=2, **FAST),
            "ratio", jkrbem.InputError)


@pytest.mark.parametrize(
    "extrapolate, kind",
    [("64", TypeError), ([64.5, 128], TypeError), ([], jkrbem.InputError),
     ([10**30, 10**31], jkrbem.InputError), (5, TypeError),
     ([64, 100], jkrbem.InputError), ([128, 64], jkrbem.InputError)],
)
def test_extrapolate_is_a_bool_or_a_list_of_grids(extrapolate, kind):
    # A list of grids is extrapolate_grids (a keyword of its own): either is named.
    refused(lambda: jkrbem.simulate(ratio=1, backend="cpu", extrapolate=extrapolate),
            "extrapolate", kind)


# LOW: a slow progress callback.


def test_a_slow_progress_callback_does_not_multiply_the_run_time():
    t0 = time.perf_counter()
    jkrbem.pulloff(1, grid=64, backend="cpu")
    alone = time.perf_counter() - t0
    events = []

    def slow(event):
        events.append(event)
        time.sleep(0.3)

    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # not interrupted
        r = jkrbem.pulloff(1, grid=64, backend="cpu", progress=slow)
    watched = time.perf_counter() - t0
    assert r.complete
    # start, note, end and a few states at 0.3 s each; the callback's share is held to ~10 %.
    assert watched <= 1.2 * alone + 4.0, (alone, watched, len(events))
    kinds = [e["event"] for e in events]
    assert kinds[-1] == "end" and "start" in kinds and "note" in kinds
    # The last state before "end" is the run's last state.
    last = [e for e in events if e["event"] == "state"][-1]
    assert last["step"] == r.states["step"].max()


def test_a_fast_progress_callback_still_sees_states_often():
    events = []
    jkrbem.pulloff(1, grid=64, backend="cpu", progress=events.append)
    states = [e for e in events if e["event"] == "state"]
    assert len(states) >= 2
    assert [e["event"] for e in events][-1] == "end"
