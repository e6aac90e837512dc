"""``jkrbem.batch``: many scenes run in the library, several at a time, each giving the same
:class:`jkrbem.Result` as :func:`jkrbem.simulate` of its keywords; every scene checked before
any runs, refusals naming the scene and the keyword; a pandas DataFrame taken by its rows;
``sweep_results`` as one batch."""

import math

import pytest

import jkrbem

FAST = {"backend": "cpu", "grid": 32, "measure": "adhesive_force"}

SCENES = [
    dict(ratio=1, **FAST),
    dict(ratio=2, e_star=2.0, work_of_adhesion=0.5, mesh_angle=30, **FAST),
    dict(indenter="flat_punch", radius=1.0, backend="cpu", grid=16, measure="adhesive_force"),
    dict(indenter="power_law", exponent=4, **FAST),
]


def test_each_scene_answers_as_simulate_does():
    results = jkrbem.batch(SCENES, processes=2)
    assert len(results) == len(SCENES)
    for scene, r in zip(SCENES, results):
        alone = jkrbem.simulate(**scene)
        assert isinstance(r, jkrbem.Result)
        assert r.summary["runs"][0]["f_ad_bar"] == alone.summary["runs"][0]["f_ad_bar"]
        assert r.adhesive_force == alone.adhesive_force
        assert len(r.states) == len(alone.states)
    # The sphere meets JKR's 1/2 within its stated uncertainty.
    assert abs(results[0].adhesive_force - 0.5) <= results[0].uncertainty


def test_one_at_a_time_and_several_at_a_time_agree():
    one = jkrbem.batch(SCENES[:2])
    two = jkrbem.batch(SCENES[:2], processes=2)
    assert [r.adhesive_force for r in one] == [r.adhesive_force for r in two]


def test_progress_hears_every_scene_end():
    events = []
    jkrbem.batch(SCENES[:3], processes=2, progress=events.append)
    ends = [e for e in events if e["event"] == "scene"]
    assert sorted(e["index"] for e in ends) == [0, 1, 2]
    assert sorted(e["done"] for e in ends) == [1, 2, 3]
    assert all(e["total"] == 3 for e in ends)
    notes = [e["text"] for e in events if e["event"] == "note"]
    assert notes and all(n.startswith("scenes[") for n in notes), notes


def test_a_bad_scene_is_refused_before_any_runs_naming_it_and_the_keyword():
    events = []
    scenes = [dict(ratio=1, **FAST), dict(ratio=1, **FAST), dict(ratio=1, mesh_angle=500, **FAST)]
    with pytest.raises(jkrbem.InputError) as e:
        jkrbem.batch(scenes, progress=events.append)
    message = str(e.value)
    assert message.startswith("scenes[2]: ") and "mesh_angle" in message, message
    assert "--" not in message and "⟨" not in message, message
    assert events == [], "a scene ran before the bad one was refused"
    # Conflicts, unknown keywords and wrong types name the scene too.
    with pytest.raises(jkrbem.InputError, match=r"scenes\[1\]: accuracy"):
        jkrbem.batch([dict(ratio=1, **FAST), dict(ratio=1, accuracy="2%", **FAST)])
    # An unknown keyword is a TypeError, as for simulate (and as Python's own calls make it).
    with pytest.raises(TypeError, match=r'scenes\[0\]: "ratoi"'):
        jkrbem.batch([dict(ratoi=2, **FAST)])
    with pytest.raises(TypeError, match=r"scenes\[1\]: ratio"):
        jkrbem.batch([dict(ratio=1, **FAST), dict(ratio=object(), **FAST)])
    with pytest.raises(TypeError, match=r"scenes\[0\]"):
        jkrbem.batch([5])
    with pytest.raises(TypeError, match="scenes"):
        jkrbem.batch(dict(ratio=1))
    with pytest.raises(jkrbem.InputError, match="processes"):
        jkrbem.batch(SCENES[:1], processes=0)
    assert jkrbem.batch([]) == []


def test_a_dataframe_is_taken_by_its_rows_empty_cells_not_given():
    pd = pytest.importorskip("pandas")
    frame = pd.DataFrame(
        {
            "indenter": ["ellipsoid", "flat_punch", None],
            "ratio": [2.0, math.nan, 1.0],
            "grid": [32, 16, 32],
            "steps": [20, math.nan, 12],  # float64 because of the gap: 20.0 is taken as 20
            "measure": ["adhesive_force"] * 3,
            "backend": ["cpu"] * 3,
        }
    )
    results = jkrbem.batch(frame)
    assert [r.summary["runs"][0]["nx"] for r in results] == [32, 16, 32]
    assert [r.summary["provenance"]["options"]["steps"] for r in results] == [20, 20, 12]
    assert results[1].summary["provenance"]["scene"]["indenter"] == "flat-punch"
    assert results[0].adhesive_force == jkrbem.simulate(ratio=2, **FAST).adhesive_force


def test_sweep_results_run_as_one_batch():
    rs = jkrbem.sweep_results([1, 2], processes=2, **FAST)
    assert [r.summary["ratio"] for r in rs] == [1.0, 2.0]
    t = jkrbem.sweep([1, 2], **FAST)
    assert list(t["f_ad_bar"]) == [r.adhesive_force for r in rs]
    with pytest.raises(jkrbem.InputError, match="ratios"):
        jkrbem.sweep_results([0.5], **FAST)


class _TwoRatioColumns:
    """What batch reads of a DataFrame with the column ratio twice (pandas' to_dict keeps the
    last copy's values)."""

    columns = ["ratio", "ratio", "grid"]

    def to_dict(self, orient):
        return [{"ratio": 32.0, "grid": 32}]


def test_a_dataframe_with_a_repeated_column_is_refused():
    # Before any run, and before pandas is needed: every row ran with the last copy's values.
    with pytest.raises(jkrbem.InputError, match="ratio more than once"):
        jkrbem.batch(_TwoRatioColumns())


def test_a_pandas_dataframe_with_a_repeated_column_is_refused():
    pd = pytest.importorskip("pandas")
    frame = pd.DataFrame([[1.0, 32.0, 32]], columns=["ratio", "ratio", "grid"])
    with pytest.raises(jkrbem.InputError, match="ratio more than once"):
        jkrbem.batch(frame)


@pytest.mark.parametrize("progress", [None, False, True, lambda event: None])
def test_every_progress_value_of_batch_runs(progress):
    # progress=True and False raised NameError (_PROGRESS) before they were checked.
    results = jkrbem.batch(SCENES[:1], progress=progress)
    assert results[0].adhesive_force is not None
    with pytest.raises(TypeError, match="progress"):
        jkrbem.batch(SCENES[:1], progress="yes")


def test_an_interrupted_batch_warns_and_keeps_its_results():
    # The warning of an interrupted batch raised NameError (warnings) and lost the results.
    seen = []

    def stop(event):
        seen.append(event)
        if event["event"] == "scene":
            raise KeyboardInterrupt

    with pytest.warns(RuntimeWarning, match="interrupted"):
        results = jkrbem.batch(SCENES[:2], progress=stop)
    # The first scene ended before the interrupt; the second was not started.
    assert len(results) == 2 and results[1] is None
    assert results[0].adhesive_force is not None
