"""The --where grammar: names, numbers, comparisons, and/or/not, parentheses; never eval."""
import numpy as np
import pandas as pd
import pytest

from mechopt.core.conditions import parse_condition

DF = pd.DataFrame({
    "r_mic": [0.9, 0.7, np.nan, 1.0, 0.85],
    "gci": [0.7, 0.9, 0.9, 0.5, 0.6],
    "r3": [0.0, 0.5, 1.5, 0.25, 1.0],
})


def _mask(text):
    return parse_condition(text, DF.columns).evaluate(DF).tolist()


@pytest.mark.parametrize("text, expected", [
    ("r_mic > 0.8 and gci > 0.6", [True, False, False, False, False]),
    ("r_mic > 0.8 or gci > 0.6", [True, True, True, True, True]),
    ("r_mic>0.8 AND gci>=0.6", [True, False, False, False, True]),
    # and binds tighter than or
    ("gci < 0.55 or r_mic > 0.8 and gci > 0.6", [True, False, False, True, False]),
    ("(gci < 0.55 or r_mic > 0.8) and gci > 0.6", [True, False, False, False, False]),
    ("not (r_mic > 0.8)", [False, True, True, False, False]),
    ("not not r3 == 0", [True, False, False, False, False]),
    ("0.6 <= gci < 0.9", [True, False, False, False, True]),  # chained
    ("r3 != 0.5", [True, False, True, True, True]),
    ("gci > r_mic", [False, True, False, False, False]),
    ("r3 >= -1e-3 and r3 <= 1.5E0", [True] * 5),
    ("-r3 < -0.3", [False, True, True, False, True]),
    ("((r_mic > .8))", [True, False, False, True, True]),
    ("1 < 2", [True] * 5),
])
def test_semantics(text, expected):
    assert _mask(text) == expected


def test_nan_never_satisfies_a_comparison():
    assert _mask("r_mic == r_mic")[2] is False
    assert _mask("r_mic != 0.5")[2] is False


def test_names_and_evaluate_on_dict():
    c = parse_condition("r_mic > 0.8 and (gci > 0.6 or r3 < 1)")
    assert c.names == {"r_mic", "gci", "r3"}
    cols = {k: DF[k].to_numpy() for k in DF.columns}
    assert c.evaluate(cols).tolist() == _mask("r_mic > 0.8 and (gci > 0.6 or r3 < 1)")
    with pytest.raises(ValueError, match="unknown name 'gci'"):
        c.evaluate({"r_mic": [1.0], "r3": [0.0]})


@pytest.mark.parametrize("text, message", [
    ("", "the condition is empty"),
    ("   ", "the condition is empty"),
    ("r_mic >", "expected a name or a number at position 7, found the end"),
    ("r_mic 0.8", "expected a comparison operator"),
    ("r_mic", "expected a comparison operator"),
    ("(r_mic > 1", "expected ')'"),
    ("r_mic > 1)", "expected 'and', 'or' or the end"),
    ("r_mic > 1 gci > 2", "expected 'and', 'or' or the end"),
    ("r_mic > 0.8 and", "expected a name or a number"),
    ("and r_mic > 1", "expected a name or a number"),
    ("gci = 0.5", "unexpected character '='"),
    ("gci > 0.5 && r_mic > 1", "unexpected character '&'"),
    ("gci > 0.5; import os", "unexpected character ';'"),
    ("__import__('os').system('echo hacked')", "unexpected character"),
    ("gci.real > 0", "unexpected character '.'"),
    ("abs(gci) > 0", "expected a comparison operator"),
    ("gci > 1 + 2", "expected 'and', 'or' or the end"),
    ("foo > 1", "unknown name 'foo'"),
])
def test_malformed_conditions_raise_one_line(text, message):
    with pytest.raises(ValueError) as exc:
        parse_condition(text, DF.columns)
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith("where")
    assert message in msg


def test_never_evaluates_python(monkeypatch):
    import builtins

    def boom(*a, **k):  # pragma: no cover - must not be called
        raise AssertionError("eval/exec called")

    monkeypatch.setattr(builtins, "eval", boom)
    monkeypatch.setattr(builtins, "exec", boom)
    assert _mask("r_mic > 0.8 and gci > 0.6") == [True, False, False, False, False]


def test_not_a_string():
    with pytest.raises(ValueError, match="where must be a string"):
        parse_condition(0.5)
