"""The documentation (issue 15): tutorials that run, an output reference that is
complete and current, help texts with units, an API page that covers the public API.

* every ```python block of docs/tutorial_design.md and docs/tutorial_evaluate.md
  runs, in order, in one namespace per tutorial, inside a temporary folder; what
  each tutorial promises holds (the printed evaluation table equals a fresh run of
  the command, the Python result equals ``--json``, the run folder holds its files);
* docs/outputs.md equals what docs/gen_outputs.py writes, and tiny real runs of
  every command (evaluate of every mechanism, optimize, an infeasible optimize,
  sweep, atlas, design) write no file, CSV column or JSON key it does not list;
* every option of every sub-command has a help text, and the options that take a
  length, an angle or a time say its unit;
* docs/api.rst documents the public API and no page holds a path of this machine.
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import math
import re
from pathlib import Path

import pandas as pd
import pytest

from mechopt.cli import build_parser, main

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def _python_blocks(name):
    return re.findall(r"```python\n(.*?)```", (DOCS / name).read_text(), flags=re.S)


def _run_tutorial(name, folder, monkeypatch) -> dict:
    """Every ```python block of ``docs/name``, in order, in one namespace, in ``folder``."""
    blocks = _python_blocks(name)
    assert len(blocks) >= 3, name
    monkeypatch.chdir(folder)
    scope: dict = {"__name__": "__tutorial__"}
    for block in blocks:
        exec(compile(block, name, "exec"), scope)  # noqa: S102 - the page's own code
    return scope


def _gen_outputs():
    spec = importlib.util.spec_from_file_location("gen_outputs", DOCS / "gen_outputs.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _numbers_and_words(text):
    """The tokens of a printed table: numbers as floats, everything else as text."""
    out = []
    for tok in re.findall(r"[-+]?\d+\.?\d*(?:e[-+]?\d+)?|[^\s\d\[\],{}:']+", text):
        try:
            out.append(float(tok))
        except ValueError:
            out.append(tok)
    return out


# --------------------------------------------------------------------------- tutorials
def test_design_tutorial_runs(tmp_path, monkeypatch):
    scope = _run_tutorial("tutorial_design.md", tmp_path, monkeypatch)
    run = tmp_path / "tutorial-run"
    # what section 2 says the folder holds
    for name in ("front.csv", "design.json", "run.json", "front.png", "design.png"):
        assert (run / name).is_file(), name
    front = pd.read_csv(run / "front.csv")
    assert len(front) == len(scope["front"])
    for col in ("r1", "r2", "r3", "mode", "task_x", "task_y", "size", "min-lci"):
        assert col in front.columns, col
    assert any(c.startswith("margin_") for c in front.columns)
    # design.json is the knee of the front, the design section 3 checks
    chosen = json.loads((run / "design.json").read_text())
    assert chosen["repr"] == scope["chosen"]["repr"]
    assert chosen["feasible"] is True


def test_evaluate_tutorial_runs_and_equals_the_command(tmp_path, monkeypatch, capsys):
    scope = _run_tutorial("tutorial_evaluate.md", tmp_path, monkeypatch)
    capsys.readouterr()
    assert main(["evaluate", "five-bar", "--r1", "0.85", "--r2", "1.6", "--r3", "0.55", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    res = scope["res"].as_dict()
    assert list(printed) == list(res)          # the keys section 2 explains, in order
    for key, value in res.items():
        if isinstance(value, float) and not math.isfinite(value):
            assert printed[key] is None, key
        else:
            assert printed[key] == value, key
    # section 5: the empty GCW is null in the JSON output
    assert main(["evaluate", "five-bar", "--r1", "0.4", "--r2", "2.33", "--r3", "0.27", "--json"]) == 0
    thin = json.loads(capsys.readouterr().out)
    assert thin["gcw_area"] == 0 and thin["gcw_gci"] is None and thin["theta1_range_deg"] is None
    # section 2's table names every key the tutorial's evaluation has
    text = (DOCS / "tutorial_evaluate.md").read_text()
    for key in scope["res"].values:
        assert f"`{key}`" in text, key


def test_evaluate_tutorial_printed_table_is_a_fresh_run(capsys):
    text = (DOCS / "tutorial_evaluate.md").read_text()
    shown = re.search(r"```text\n(.*?)```", text, flags=re.S).group(1)
    assert main(["evaluate", "five-bar", "--r1", "0.85", "--r2", "1.6", "--r3", "0.55"]) == 0
    fresh = capsys.readouterr().out
    a, b = _numbers_and_words(shown), _numbers_and_words(fresh)
    assert len(a) == len(b), (shown, fresh)
    for x, y in zip(a, b):
        if isinstance(x, float) and isinstance(y, float):
            assert y == pytest.approx(x, rel=2e-5, abs=1e-9), (x, y)
        else:
            assert x == y


# --------------------------------------------------------------------------- help texts
#: an option of another command than evaluate takes a length, an angle or a time when its
#: dest matches this
_UNIT_DESTS = re.compile(r"step|length|_deg|timeout|stroke|angle|limits|_speed|_torque|_force|payload|"
                         r"^task$|^unit$|^shape$")
#: how a help text says its unit: a bracketed unit, or these words
_UNIT_WORDS = re.compile(r"\[[^\]]*\b(mm|cm|m|in|deg|rad|s|N|L|unit|length unit)\b[^\]]*\]|\bseconds\b|"
                         r"non-dimensional|unit of the lengths|\bmm, cm, m or in\b")
#: kinds of a declared mechanism parameter that are lengths or angles
_UNIT_KINDS = ("length", "length0", "position", "angle_deg")


def _walk(parser, path=("mechopt",)):
    """``(path, parser, action)`` of every option and positional, and ``(path, None, help)``
    of every sub-command."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {c.dest: c.help for c in action._choices_actions}
            for name, sub in action.choices.items():
                yield path + (name,), None, helps.get(name)
                yield from _walk(sub, path + (name,))
        elif not isinstance(action, argparse._HelpAction):
            yield path, parser, action


def test_every_option_has_a_help_text_and_lengths_their_unit():
    from mechopt.mechanisms import registry

    kinds = {name: {p.name: p.kind for p in cls.parameters} for name, cls in registry().items()}
    checked, missing, no_unit = 0, [], []
    for path, parser, action in _walk(build_parser()):
        if parser is None:  # a sub-command
            if not (action or "").strip():
                missing.append(" ".join(path))
            continue
        where = f"{' '.join(path)} {'/'.join(action.option_strings) or action.dest}"
        if not (action.help or "").strip():
            missing.append(where)
            continue
        if path[1:2] == ("evaluate",) and len(path) == 3:
            takes_unit = kinds[path[2]].get(action.dest) in _UNIT_KINDS
        else:
            takes_unit = bool(_UNIT_DESTS.search(action.dest))
        if takes_unit:
            checked += 1
            if not _UNIT_WORDS.search(action.help):
                no_unit.append(f"{where}: {action.help!r}")
    assert not missing, missing
    assert not no_unit, no_unit
    assert checked >= 30  # every mechanism's lengths, design's lengths and angles, atlas step, timeout


# --------------------------------------------------------------------------- output reference
def test_output_reference_is_current():
    assert _gen_outputs().render() == (DOCS / "outputs.md").read_text(), \
        "docs/outputs.md is not current: run .venv/bin/python docs/gen_outputs.py"


#: JSON keys whose children are not mechopt's names (hashes by file name, pymoo's
#: operator settings, the run's identifying settings); their own keys are checked
_OPAQUE = {"files", "key", "sampling", "selection", "crossover", "mutation", "mating", "survival"}


def _json_keys(obj, depth=0, max_depth=2):
    out = set()
    if isinstance(obj, dict) and depth < max_depth:
        for k, v in obj.items():
            out.add(k)
            if k not in _OPAQUE:
                out |= _json_keys(v, depth + 1, max_depth)
    return out


def _listed_names() -> set:
    text = (DOCS / "outputs.md").read_text()
    return set(re.findall(r"`([^`]+)`", text))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """Tiny real runs of every command that writes a folder, and every evaluate --json."""
    import contextlib
    import io

    base = tmp_path_factory.mktemp("outputs")
    gen = _gen_outputs()
    from mechopt.mechanisms import registry

    commands = {
        "optimize": ["optimize", "le2013-gamma", "--pop", "4", "--gen", "2", "--n-jobs", "1"],
        "optimize-infeasible": ["optimize", "liu2006-all", "--pop", "4", "--gen", "1", "--n-jobs", "1"],
        "sweep": ["sweep", "le2013-gamma", "--weights", "0,1", "--pop", "4", "--gen", "2", "--n-jobs", "1"],
        "atlas": ["atlas", "five-bar", "--step", "0.5", "--where", "r_mic > 0.5", "--n-jobs", "1"],
        # the command of docs/tutorial_design.md, with a small budget
        "design": ["design", "five-bar", "--task", "rect:100,60@0,180", "--min-lci", "0.4",
                   "--joint-limits=-60,240", "--max-length", "250", "--objectives", "size,min-lci",
                   "--seed", "1", "--pop", "12", "--gen", "6", "--n-jobs", "1", "--no-polish"],
    }
    folders, stdout = {}, {}
    for name, argv in commands.items():
        folders[name] = base / name
        with contextlib.redirect_stdout(io.StringIO()) as out:
            assert main(argv + ["--out", str(folders[name])]) == 0, name
        stdout[name] = out.getvalue()
    # the design above exported (every format but the DXF, whose files are named by body)
    folders["export"] = base / "export"
    with contextlib.redirect_stdout(io.StringIO()) as out:
        assert main(["export", str(folders["design"] / "design.json"), "--to", str(folders["export"]),
                     "--format", "urdf,mjcf,svg,csv,gif", "--samples", "8"]) == 0
    stdout["export"] = out.getvalue()
    evaluations = {}
    for mech, cls in registry().items():
        argv = ["evaluate", mech]
        for p in cls.parameters:
            if p.name in gen.EVAL_EXAMPLES[mech]:
                argv += [p.option, str(gen.EVAL_EXAMPLES[mech][p.name])]
        with contextlib.redirect_stdout(io.StringIO()) as out:
            assert main(argv + ["--json"]) == 0, mech
        evaluations[mech] = json.loads(out.getvalue())
    return {"folders": folders, "stdout": stdout, "evaluations": evaluations}


def test_evaluate_json_keys_are_listed(runs):
    listed = _listed_names()
    from mechopt.mechanisms import registry

    assert set(runs["evaluations"]) == set(registry())
    missing = {m: sorted(_json_keys(d) - listed) for m, d in runs["evaluations"].items()}
    assert not any(missing.values()), missing
    # the five-bar command of the issue, as the tutorial shows it
    assert runs["evaluations"]["five-bar"]["inputs"] == {"r1": 0.85, "r2": 1.6, "r3": 0.55, "mode": "+-",
                                                         "quadrature": "area", "gamma": 0.5}


@pytest.mark.parametrize("command", ["optimize", "optimize-infeasible", "sweep", "atlas", "design", "export"])
def test_every_file_column_and_key_a_command_writes_is_listed(runs, command):
    listed = _listed_names()
    folder = runs["folders"][command]
    files = sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))
    assert files, command
    missing = [f"file {f}" for f in files if f not in listed]
    for f in files:
        path = folder / f
        if f.endswith(".csv"):
            missing += [f"{f}: column {c}" for c in pd.read_csv(path, nrows=0, comment="#").columns
                        if c.split(".")[0] not in listed]  # pandas suffixes a repeated name with .1
        elif f.endswith(".json"):
            missing += [f"{f}: key {k}" for k in sorted(_json_keys(json.loads(path.read_text())))
                        if k not in listed]
    assert not missing, missing
    if command == "optimize-infeasible":  # the keys of a run without a feasible design
        info = json.loads((folder / "run.json").read_text())
        assert info["feasible"] == 0 and "least_violation" in info, info
    if command == "sweep":
        table = pd.read_csv(folder / "sweep.csv")
        assert len(table) == 2 and {"weight", "z", "feasible", "violation"} <= set(table.columns)
        assert any(c.startswith("g_") for c in table.columns)


# --------------------------------------------------------------------------- API page
def test_api_page_covers_the_public_api():
    import mechopt
    from mechopt import mechanisms

    text = (DOCS / "api.rst").read_text()
    documented = set(re.findall(r"^\.\. (?:automodule|py:module):: (\S+)", text, flags=re.M))
    for name, module in mechopt._PUBLIC.items():
        assert module in documented, (name, module)
        assert f"``{name}``" in text, name
    for info in __import__("pkgutil").iter_modules(mechanisms.__path__):
        assert f"mechopt.mechanisms.{info.name}" in documented, info.name
    for module in ("mechopt.problems", "mechopt.run.problem", "mechopt.workflows.design", "mechopt.analysis.evaluate",
                   "mechopt.run.runner"):
        assert module in documented, module
    for func in ("optimize", "resume", "sweep"):
        assert f".. autofunction:: mechopt.run.runner.{func}" in text or "automodule:: mechopt.run.runner" in text
    index = (DOCS / "index.rst").read_text()
    for page in ("tutorial_design", "tutorial_evaluate", "outputs", "api"):
        assert f"   {page}\n" in index, page


def test_docs_hold_no_path_of_this_machine():
    root = str(ROOT)
    for path in sorted(DOCS.rglob("*")):
        if path.suffix in (".md", ".rst", ".py", ".txt"):
            text = path.read_text()
            assert root not in text and "/tmp/" not in text and "/home/" not in text, path
