"""jkrbem.load reads back what the ``jkrbem`` command writes (summary JSON, states CSV,
fields .npz) as the objects simulate returns: the same states, adhesive force and fields as
the same run made in memory. Files the CLI wrote where its binary is built (cargo build
--release, or JKRBEM_CLI naming it), and files written here in the documented formats."""

import json
import os
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

import jkrbem

ROOT = Path(__file__).resolve().parents[2]

#: The small runs here warn that they are coarse; these tests are not about that.
pytestmark = pytest.mark.filterwarnings("ignore::jkrbem.JkrbemWarning")

#: The states CSV's header (src/output/states_csv.rs).
HEADER = [name for name, _ in jkrbem.STATE_COLUMNS] + ["onsets"]


def cli_binary():
    """The jkrbem command: JKRBEM_CLI, else the worktree's release or debug build."""
    named = os.environ.get("JKRBEM_CLI")
    for c in ([Path(named)] if named else []) + [ROOT / "target/release/jkrbem", ROOT / "target/debug/jkrbem"]:
        if c.is_file() and os.access(c, os.X_OK):
            return c
    return None


@pytest.fixture
def cli():
    b = cli_binary()
    if b is None:
        pytest.skip("no jkrbem binary: cargo build --release (or set JKRBEM_CLI)")
    return b


def run_cli(cli, cwd, *args):
    subprocess.run([str(cli), "simulate", "--backend", "cpu", *args], cwd=cwd, check=True,
                   capture_output=True, timeout=300)


def same_states(a, b):
    assert a.dtype == b.dtype and len(a) == len(b)
    for name in a.dtype.names:
        if a.dtype[name].kind == "f":
            assert np.array_equal(a[name], b[name], equal_nan=True), name
        else:
            assert np.array_equal(a[name], b[name]), name


def same_fields(a, b):
    assert (a.run, a.index, a.label) == (b.run, b.index, b.label)
    for name in ("x", "y", "pressure", "gap", "contact"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert (a.dx, a.sigma_c) == (b.dx, b.sigma_c)
    assert a.state == b.state


# --- files the CLI wrote ----------------------------------------------------------------------


def test_the_clis_summary_states_and_fields_load_as_the_same_run_in_memory(cli, tmp_path, monkeypatch):
    run_cli(cli, tmp_path, "--ratio", "1", "--grid", "32", "--out", "s.csv", "--summary", "s.json",
            "--fields", "minimum")
    memory = jkrbem.simulate(ratio=1, grid=32, backend="cpu", fields="minimum")
    monkeypatch.chdir(ROOT)  # the summary names "s.csv", relative to where the CLI ran
    r = jkrbem.load(tmp_path / "s.json")
    assert isinstance(r, jkrbem.Result)
    assert (r.adhesive_force, r.uncertainty, r.estimate) == (memory.adhesive_force, memory.uncertainty,
                                                             memory.estimate)
    assert r.runs[0].grid == (32, 32) and r.complete
    # The file is the command line's: its warnings name flags where Python's name keywords.
    flags = {f"--{n.replace('_', '-')}": n for n in jkrbem._request.BY_NAME}
    worded = [re.sub(r"--[a-z][a-z0-9-]*", lambda m: flags.get(m.group(0), m.group(0)), w) for w in r.warnings]
    assert worded == memory.warnings
    same_states(r.states, memory.states)
    assert r.force_scale == memory.force_scale
    assert len(r.fields) == 1
    same_fields(r.fields[0], memory.fields[0])
    assert r.field_at_minimum is not None

    run = jkrbem.load(str(tmp_path / "s.csv"))
    assert isinstance(run, jkrbem.Run)
    assert run.grid == (32, 32) and run.complete and run.onsets == "near-minimum"
    assert run.dx == memory.runs[0].dx
    same_states(run.states, memory.states)

    fields = jkrbem.load(tmp_path / "s.fields.npz")
    assert isinstance(fields, list) and len(fields) == 1
    same_fields(fields[0], memory.fields[0])


def test_an_extrapolated_runs_summary_loads_every_grid(cli, tmp_path):
    run_cli(cli, tmp_path, "--ratio", "1", "--extrapolate", "--extrapolate-grids", "32,64",
            "--out", "e.csv", "--summary", "e.json")
    memory = jkrbem.simulate(ratio=1, extrapolate=[32, 64], backend="cpu")
    r = jkrbem.load(tmp_path / "e.json")
    assert [run.grid for run in r.runs] == [run.grid for run in memory.runs]
    assert r.estimate == "extrapolated" and r.adhesive_force == memory.adhesive_force
    for a, b in zip(r.runs, memory.runs):
        same_states(a.states, b.states)


def test_a_flat_punch_summary_gives_the_grids_adhesive_force(cli, tmp_path):
    run_cli(cli, tmp_path, "--indenter", "flat-punch", "--radius", "2", "--grid", "32",
            "--out", "p.csv", "--summary", "p.json")
    r = jkrbem.load(tmp_path / "p.json")
    assert r.adhesive_force == r.summary["runs"][0]["f_ad_bar"] and r.estimate == "grid"
    assert r.uncertainty is None
    assert r.force_scale == pytest.approx(np.sqrt(8 * np.pi * 2.0**3), rel=1e-12)  # Kendall's


# --- files written here in the documented formats ---------------------------------------------


def write_states_csv(path, states, comments=(), onsets="near-minimum"):
    """`states` as the CLI writes them (src/output/states_csv.rs), after `comments`."""
    lines = [f"# {c}" for c in comments] + [",".join(HEADER)]
    for row in states:
        values = [repr(float(row[n])) if states.dtype[n].kind == "f" else str(row[n]) for n in states.dtype.names]
        lines.append(",".join(values + [onsets]))
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def write_fields_npz(path, fields, about):
    """`fields` as the CLI writes them (src/output/fields_npz.rs)."""
    meta = {"format": "jkrbem fields", "labels": [f.label for f in fields], "about": about}
    per = lambda key: np.array([f.state[key] for f in fields])
    np.savez_compressed(
        path,
        pressure=np.stack([f.pressure for f in fields]), gap=np.stack([f.gap for f in fields]),
        contact=np.stack([f.contact for f in fields]), x=np.stack([f.x for f in fields]),
        y=np.stack([f.y for f in fields]), state_index=np.array([f.index for f in fields], dtype=np.uint64),
        d=per("d"), force=per("force"), dx=np.array([f.dx for f in fields]),
        sigma_c=np.array([f.sigma_c for f in fields]), d_bar=per("d_bar"), f_bar=per("f_bar"),
        c_bar=per("c_bar"), metadata=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8),
    )


@pytest.fixture(scope="module")
def memory():
    return jkrbem.simulate(ratio=1, grid=32, backend="cpu", fields=[3, 10])


def test_files_in_the_documented_formats_load_as_the_run_they_hold(memory, tmp_path):
    write_states_csv(tmp_path / "m.csv", memory.states, comments=["jkrbem 0.1.0", "ratio 1"])
    write_fields_npz(tmp_path / "m.fields.npz", memory.fields, {"grid": [32, 32], "states_csv": "m.csv"})
    summary = json.loads(json.dumps(memory.summary))
    summary["runs"][0]["states_csv"] = "elsewhere/m.csv"  # found under its name beside the summary
    (tmp_path / "m.json").write_text(json.dumps(summary), encoding="utf-8")

    run = jkrbem.load(tmp_path / "m.csv")
    same_states(run.states, memory.states)
    assert run.comments == ["jkrbem 0.1.0", "ratio 1"]
    assert run.grid == (32, 32) and run.complete

    fields = jkrbem.load(tmp_path / "m.fields.npz")
    assert [f.index for f in fields] == [f.index for f in memory.fields]
    for a, b in zip(fields, memory.fields):
        same_fields(a, b)

    r = jkrbem.load(tmp_path / "m.json")
    assert r.adhesive_force == memory.adhesive_force and r.uncertainty == memory.uncertainty
    same_states(r.states, memory.states)
    assert len(r.fields) == len(memory.fields)


def test_a_csv_alone_has_an_unknown_grid_and_its_partial_name_says_incomplete(memory, tmp_path):
    path = tmp_path / "run.incomplete-4242.csv"
    write_states_csv(path, memory.states[:10])
    run = jkrbem.load(path)
    assert run.grid is None and not run.complete and len(run.states) == 10
    assert run.dx == memory.runs[0].dx
    assert "grid ?" in repr(run)


def test_fields_alone_keep_the_archives_per_state_values(memory, tmp_path):
    write_fields_npz(tmp_path / "f.fields.npz", memory.fields, {"grid": [32, 32], "states_csv": "gone.csv"})
    fields = jkrbem.load(tmp_path / "f.fields.npz")
    for a, b in zip(fields, memory.fields):
        assert a.state == {k: b.state[k] for k in ("d", "force", "dx", "d_bar", "f_bar", "c_bar")}
        assert np.array_equal(a.pressure, b.pressure)


def test_a_summary_whose_states_are_missing_loads_with_a_warning(memory, tmp_path):
    summary = json.loads(json.dumps(memory.summary))
    summary["runs"][0]["states_csv"] = "nowhere.csv"
    (tmp_path / "s.json").write_text(json.dumps(summary), encoding="utf-8")
    with pytest.warns(jkrbem.JkrbemWarning, match="nowhere.csv"):
        r = jkrbem.load(tmp_path / "s.json")
    assert r.adhesive_force == memory.adhesive_force and len(r.states) == 0
    assert r.runs[0].grid == (32, 32)


@pytest.mark.parametrize("name, content, says", [
    ("s.txt", "x", "not .txt"),
    ("summary", "{}", "no extension"),
    ("a.csv", "a,b\n1,2\n", "not a jkrbem states CSV"),
    ("e.csv", "", "no header"),
    ("b.json", '{"ratio": 1}', "not a jkrbem summary"),
    ("c.json", "[1, 2]", "not a jkrbem summary"),
    ("d.json", "{", "not JSON"),
    ("f.fields.npz", "not a zip", "not a numpy .npz"),
])
def test_anything_else_is_refused_naming_the_file(tmp_path, name, content, says):
    path = tmp_path / name
    path.write_text(content, encoding="utf-8")
    with pytest.raises(jkrbem.InputError, match=says) as e:
        jkrbem.load(path)
    assert name in str(e.value) and isinstance(e.value, ValueError)


def test_an_npz_that_is_not_a_fields_archive_is_refused(tmp_path):
    np.savez(tmp_path / "other.npz", a=np.arange(3))
    with pytest.raises(jkrbem.InputError, match="no metadata"):
        jkrbem.load(tmp_path / "other.npz")
    np.save(tmp_path / "one.npy", np.arange(3))
    os.replace(tmp_path / "one.npy", tmp_path / "one.npz")
    with pytest.raises(jkrbem.InputError, match="not an .npz archive"):
        jkrbem.load(tmp_path / "one.npz")


def test_a_states_csv_with_a_bad_number_names_its_line(memory, tmp_path):
    path = tmp_path / "bad.csv"
    write_states_csv(path, memory.states[:3], comments=["c"])
    text = path.read_text().splitlines()
    text[3] = text[3].replace(text[3].split(",")[2], "oops", 1)
    path.write_text("\n".join(text) + "\n")
    with pytest.raises(jkrbem.InputError, match="line 4: d = 'oops'"):
        jkrbem.load(path)


def test_a_missing_file_is_an_os_error(tmp_path):
    with pytest.raises(FileNotFoundError):
        jkrbem.load(tmp_path / "none.json")


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
@pytest.mark.parametrize("name", ["s.json", "s.csv", "s.fields.npz"])
def test_a_device_behind_a_name_is_refused_not_read(tmp_path, device, name):
    # It read /dev/urandom for ever and /dev/zero to exhaustion.
    link = tmp_path / name
    link.symlink_to(device)
    with pytest.raises(jkrbem.InputError, match="not a regular file"):
        jkrbem.load(link)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_a_fifo_is_refused_at_once(tmp_path):
    # A FIFO named .json with no writer blocked the call for ever.
    fifo = tmp_path / "s.json"
    os.mkfifo(fifo)
    with pytest.raises(jkrbem.InputError, match="not a regular file"):
        jkrbem.load(fifo)


def test_a_summary_larger_than_any_summary_is_refused(tmp_path, monkeypatch):
    from jkrbem import _load

    monkeypatch.setattr(_load, "_MAX_SUMMARY_BYTES", 64)
    big = tmp_path / "s.json"
    big.write_text(json.dumps({"f_ad_bar": None, "runs": [], "pad": "x" * 100}))
    with pytest.raises(jkrbem.InputError, match="more than the 64"):
        jkrbem.load(big)
