"""Hostile inputs (issue 41, "Hardening, round three"): no input reaches a panic, every
refusal is an InputError (a ValueError) or a TypeError naming the keyword, numpy scalars are
numbers, nothing is coerced silently, and a slow progress callback cannot multiply a run's
time. Grids stay at 32 or 64 on the CPU so that the file runs in a few minutes."""

import json
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


# Hardening four (issue 55).

#: A paraboloid of radius 1 on 64 × 64 nodes at spacing 0.05: a height map that plans.
_X = (np.arange(64) - 31.5) * 0.05
BOWL = (_X[None, :] ** 2 + _X[:, None] ** 2) / 2

#: Where a map's array goes: as the indenter, or as the roughness added to a sphere.
AS = {
    "height_map": {"indenter": "height_map", "spacing": 0.05},
    "roughness": {"ratio": 1, "spacing": 0.05},
}


def _masked(a):
    return np.ma.masked_array(a, mask=a > 1.0)


# ITEM 20: the CLI reads float64 and float32 .npy maps only; Python takes real numbers
# (float or integer arrays) and refuses, naming the keyword and before any run, what the CLI
# refuses and numpy would have turned into heights silently: complex numbers (their imaginary
# part dropped), masked arrays (their hidden values read as heights), bools (0 and 1).
@pytest.mark.parametrize("keyword", ["height_map", "roughness"])
@pytest.mark.parametrize(
    "array, says",
    [
        (BOWL.astype(np.complex128), "complex"),
        (BOWL + 0.5j, "complex"),
        (BOWL.astype(np.complex64), "complex"),
        (_masked(BOWL), "masked"),
        (np.ma.masked_array(BOWL), "masked"),  # nothing masked: still a masked array
        (BOWL > 0.5, "bool"),
    ],
    ids=["complex128", "complex-imaginary", "complex64", "masked", "masked-none", "bool"],
)
def test_a_complex_masked_or_bool_map_array_is_refused_naming_its_keyword(keyword, array, says):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no ComplexWarning on the way: refused before numpy casts
        e = refused(lambda: jkrbem.plan(**{keyword: array}, **AS[keyword]), keyword, TypeError)
        assert says in str(e), str(e)
        refused(lambda: jkrbem.simulate(**{keyword: array}, **AS[keyword], **FAST), keyword, TypeError)


def test_a_real_map_array_of_any_float_or_integer_dtype_is_taken():
    f64 = jkrbem.plan(indenter="height_map", height_map=BOWL, spacing=0.05)
    assert f64["grids"] == jkrbem.plan(indenter="height_map", height_map=BOWL.astype(np.float32),
                                       spacing=0.05)["grids"]
    # The same bowl 10⁴ times larger, in whole numbers (Δγ scaled to keep the contact's size).
    whole = jkrbem.plan(indenter="height_map", height_map=np.rint(BOWL * 1e4).astype(np.int32),
                        spacing=500, work_of_adhesion=1e4)
    assert whole["grids"] == f64["grids"]


@pytest.mark.parametrize(
    "kwargs, keyword",
    [
        ({"extrapolate": np.array([32, 64], dtype=complex)}, "extrapolate"),
        ({"apex_offset": np.array([0.1, 0.0], dtype=complex)}, "apex_offset"),
        ({"apex_offset": np.array(0.1 + 0j)}, "apex_offset"),
        ({"e_star": np.array(2 + 0j)}, "e_star"),
        ({"extrapolate": np.ma.masked_array([32, 64, 128], mask=[0, 0, 1])}, "extrapolate"),
        ({"extrapolate": np.ma.masked_array([32, 64])}, "extrapolate"),
        ({"apex_offset": np.ma.masked_array([0.1, 0.2], mask=[0, 1])}, "apex_offset"),
        ({"e_star": np.ma.masked_array(2.0, mask=True)}, "e_star"),
        ({"fields": np.ma.masked_array([1, 2], mask=[0, 1])}, "fields"),
    ],
)
def test_a_complex_or_masked_array_for_any_other_keyword_is_refused_naming_it(kwargs, keyword):
    # Before: "Object of type complex is not JSON serializable" (no keyword), and a masked
    # value read as its hidden data (nothing masked) or as null.
    args = {"ratio": 1, "backend": "cpu", **kwargs}
    if "extrapolate" not in kwargs:
        args["grid"] = 32
    e = refused(lambda: jkrbem.simulate(**args), keyword, TypeError)
    assert "serializable" not in str(e)
    if isinstance(next(iter(kwargs.values())), np.ma.MaskedArray):
        assert "masked" in str(e), str(e)


def test_a_masked_array_of_ratios_or_angles_is_refused_naming_it():
    e = refused(lambda: jkrbem.sweep(np.ma.masked_array([1, 2]), **FAST), "ratios", TypeError)
    assert "masked" in str(e)
    e = refused(lambda: jkrbem.crossed(np.ma.masked_array([90, 45], mask=[0, 1]), **FAST), "angles", TypeError)
    assert "masked" in str(e)


# ITEM 20 (found beside it): an array's keyword says what it is, as the CLI's flag does. A
# height_map array without indenter="height_map" ran the ellipsoid with the map as its
# roughness; a roughness array with indenter="height_map" ran it as the map.


def test_a_height_map_array_with_another_indenter_is_refused_not_taken_as_roughness():
    e = refused(lambda: jkrbem.plan(height_map=BOWL, spacing=0.05), "height_map", jkrbem.InputError)
    assert "indenter" in str(e) and "ellipsoid" in str(e), str(e)
    e = refused(lambda: jkrbem.simulate(height_map=BOWL, spacing=0.05, indenter="flat-punch", **FAST),
                "height_map", jkrbem.InputError)
    assert "flat-punch" in str(e), str(e)
    e = refused(lambda: jkrbem.plan(indenter="height-map", roughness=BOWL, spacing=0.05),
                "roughness", jkrbem.InputError)
    assert "height" in str(e), str(e)
    # As the CLI: --height-map with the default indenter is refused the same way.
    refused(lambda: jkrbem.plan(height_map="map.npy", spacing=0.05), "height_map", jkrbem.InputError)


# LOW: an object array (or one of strings, dates or records) is no array of heights.


@pytest.mark.parametrize("keyword", ["height_map", "roughness"])
@pytest.mark.parametrize(
    "array",
    [
        BOWL.astype(object),
        np.full((64, 64), "a", dtype=object),
        np.full((64, 64), "1.5"),
        np.zeros((64, 64), dtype="M8[s]"),
        np.zeros((64, 64), dtype=[("h", "f8")]),
    ],
    ids=["object-floats", "object-strings", "strings", "datetimes", "records"],
)
def test_an_object_or_text_map_array_is_refused_naming_its_keyword(keyword, array):
    # Before: an object array of strings raised numpy's "could not convert string to float"
    # (no keyword); one of floats, strings of numbers, dates and records were read as heights.
    e = refused(lambda: jkrbem.plan(**{keyword: array}, **AS[keyword]), keyword, TypeError)
    assert str(array.dtype) in str(e), str(e)


def test_a_batch_scenes_map_array_of_a_bad_dtype_names_the_scene_and_keyword():
    e = refused(lambda: jkrbem.batch([{"indenter": "height_map", "height_map": BOWL.astype(object),
                                       "spacing": 0.05}]), "height_map", TypeError)
    assert "scenes[0]" in str(e)


# LOW: a summary nested too deeply for Python's JSON parser.


def test_a_deeply_nested_summary_is_refused_as_a_load_error_not_a_recursion_error(tmp_path):
    deep = "[" * 100_000 + "]" * 100_000
    summary = tmp_path / "deep.json"
    summary.write_text(deep)
    e = refused(lambda: jkrbem.load(summary), "deep.json", jkrbem.InputError)
    assert "nested" in str(e), str(e)
    # A states CSV beside such a summary loads alone, as beside any unreadable summary.
    (tmp_path / "deep.csv").write_text("step,phase,d,force,d_bar,f_bar,c_bar\n0,approach,0,0,0,0,0\n")
    run = jkrbem.load(tmp_path / "deep.csv")
    assert run.grid is None and len(run.states) == 1
    # A fields archive whose metadata is so nested.
    np.savez(tmp_path / "deep.fields.npz", metadata=np.frombuffer(deep.encode(), dtype=np.uint8))
    e = refused(lambda: jkrbem.load(tmp_path / "deep.fields.npz"), "deep.fields.npz", jkrbem.InputError)
    assert "nested" in str(e), str(e)


# A summary whose runs are malformed (edited by hand, or not ours): an InputError naming the
# file, never a raw KeyError, TypeError or AttributeError.


def test_a_summary_with_malformed_runs_is_refused_naming_the_file(tmp_path):
    for i, runs in enumerate([[1], [{}], [{"nx": "x", "ny": 2, "dx": 1}], [{"states_csv": 3}],
                              [None], [{"nx": 1, "ny": 1, "dx": [1]}]]):
        summary = tmp_path / f"bad{i}.json"
        summary.write_text(json.dumps({"f_ad_bar": 0.5, "runs": runs}))
        e = refused(lambda: jkrbem.load(summary), f"bad{i}.json", jkrbem.InputError)
        assert "not a jkrbem summary" in str(e), str(e)


# Issue 56, item 3: a run's error carries the parameter to change, as the exception's
# `parameter` (the keyword), not only in its words.


def test_a_runs_error_names_its_parameter_as_an_attribute():
    e = refused(lambda: jkrbem.simulate(ratio=50, grid=16), "grid", jkrbem.InputError)
    assert e.parameter == "grid", (e.parameter, str(e))
    # A value refused before any run names its parameter too, as does a value of the wrong type.
    e = refused(lambda: jkrbem.simulate(ratio=1, cg_tolerance=0.1), "cg_tolerance",
                jkrbem.InputError)
    assert e.parameter == "cg_tolerance", (e.parameter, str(e))
    # An error that blames no parameter says so.
    assert jkrbem.InputError("x").parameter is None
