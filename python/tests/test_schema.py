"""The request schema from Python: the keywords are the CLI's parameters with the same defaults
and ranges, and the shared table of bad inputs (tests/data/bad_inputs.txt, which the CLI's tests
run too) is refused naming each keyword."""

import inspect
import json
import os
import re
import subprocess

import pytest

import jkrbem
from jkrbem import _jkrbem, _request

TABLE = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "bad_inputs.txt")


def _cases():
    with open(TABLE, encoding="utf-8") as f:
        for line in f:
            if not line.strip() or line.startswith("#"):
                continue
            named, *given = line.split()
            yield named, [tuple(g.split("=", 1)) for g in given]


def _number(text):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _python_value(name, text):
    """The Python value of the same meaning as the command line's text."""
    kind = _request.BY_NAME[name]["kind"]
    if kind == "Switch":
        return text == "true"
    if kind.startswith(("Pair", "Grids")):
        return [_number(t) for t in text.split(",")] if text else []
    if kind.startswith(("Real", "Count", "PowerOfTwo")):
        value = _number(text)
        return float(value) if kind.startswith("Real") and isinstance(value, int) else value
    return text


CASES = list(_cases())


def test_the_table_has_sixty_cases_or_more():
    assert len(CASES) >= 60


@pytest.mark.parametrize("named,given", CASES, ids=[" ".join("=".join(g) for g in c[1]) for c in CASES])
def test_every_bad_input_is_refused_naming_its_keyword(named, given):
    params = {n: _python_value(n, v) for n, v in given}
    params.setdefault("backend", "cpu")
    # A value of the wrong type (a string where a number is meant) is a TypeError, one out of
    # range an InputError; both name the keyword.
    with pytest.raises((jkrbem.InputError, TypeError)) as e:
        jkrbem.simulate(**params)
    message = str(e.value)
    assert re.search(rf"(?<![a-z_]){named}(?![a-z_])", message), message
    assert "--" not in message, message


def test_keywords_and_defaults_are_the_schemas():
    sig = inspect.signature(jkrbem.simulate)
    for spec in _request.SCHEMA:
        assert spec["name"] in sig.parameters
        assert sig.parameters[spec["name"]].default == spec["default"] or spec["name"] == "ratio"


def test_the_cli_takes_the_same_parameters_with_the_same_defaults():
    """Every keyword is a flag of `jkrbem simulate` whose help states the same terms."""
    exe = os.path.join(os.path.dirname(__file__), "..", "..", "target", "release", "jkrbem")
    if not os.path.exists(exe):
        pytest.skip("the CLI is not built (cargo build --release)")
    help_text = subprocess.run([exe, "simulate", "--help"], capture_output=True, text=True).stdout
    flat = " ".join(help_text.split())
    for spec in _request.SCHEMA:
        assert spec["cli_flag"] in help_text, spec["name"]
        assert " ".join(spec["cli_terms"].split()) in flat, spec["name"]
