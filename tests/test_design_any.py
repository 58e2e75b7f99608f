"""``mechopt design any``: one front across mechanisms, each row re-verified with its own
mechanism's evaluator, the merge checked against an independent dominance scan."""
from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.task import Task
from mechopt.cli import main
from mechopt.requirements import Requirements
from mechopt.workflows.design_any import design_any

TASK = Task.rect(60, 40, (0, 150))
REQ = Requirements(min_lci=0.3)
RUN = dict(pop=12, gen=8, n_jobs=1, polish=False, max_length=200)


@pytest.fixture(scope="module")
def merged():
    return design_any(TASK, REQ, ("size", "min-lci"), mechanisms=("five-bar", "biglide", "bipod"), **RUN)


def test_the_merged_front_is_the_non_dominated_set_of_all_fronts(merged):
    fronts, front = merged.fronts, merged.front
    F = np.column_stack([fronts["size"], -fronts["min-lci"]])
    # independent scan: a row is kept iff no row is at least as good in both and better in one
    keep = set()
    for i in range(len(F)):
        beaten = any((F[k][0] <= F[i][0] and F[k][1] <= F[i][1]) and (F[k][0] < F[i][0] or F[k][1] < F[i][1])
                     for k in range(len(F)))
        if not beaten:
            keep.add((fronts["mechanism"].iloc[i], round(float(fronts["size"].iloc[i]), 9)))
    got = {(m, round(float(s), 9)) for m, s in zip(front["mechanism"], front["size"])}
    assert got == keep and len(front) >= 1
    assert set(merged.results) == {"five-bar", "biglide", "bipod"} and not merged.skipped
    # on this task they trade off: the biglides are smaller, the five-bars better conditioned
    assert {"five-bar", "biglide"} <= set(front["mechanism"])


def test_every_row_re_verifies_with_its_own_mechanism(merged):
    for _, row in merged.front.iterrows():
        m = row["mechanism"]
        ev = DesignEvaluator(m, TASK, REQ, ("size", "min-lci"), max_length=RUN["max_length"])
        v = {k: row[k] for k in (*ev.spec.lengths, "mode", "task_x", "task_y")}
        res = certify(ev, v)
        assert res["feasible"], (m, v)
        assert res["objectives"]["size"] == pytest.approx(row["size"], rel=1e-12)
        assert res["objectives"]["min-lci"] == pytest.approx(row["min-lci"], rel=1e-9)
    assert merged.chosen["feasible"] and merged.chosen["mechanism_name"] == merged.info["chosen"]["mechanism"]


def test_cli_design_any_writes_its_files_and_names_what_it_skips(tmp_path, capsys):
    out = tmp_path / "any"
    # joint limits apply to cranks only: the slider mechanisms are skipped with the reason
    code = main(["design", "any", "--mechanisms", "five-bar,biglide", "--task", "rect:60,40@0,150", "--min-lci",
                 "0.3", "--joint-limits=-60,240", "--max-length", "200", "--pop", "12", "--gen", "8", "--n-jobs",
                 "1", "--no-polish", "--out", str(out)])
    line = capsys.readouterr().out.strip().splitlines()[-1]
    assert code == 0, line
    assert "skipped: biglide (joint_limits applies to" in line
    front = pd.read_csv(out / "front.csv")
    assert set(front["mechanism"]) == {"five-bar"}
    assert json.loads((out / "design.json").read_text())["mechanism_name"] == "five-bar"
    assert sorted(p.name for p in out.iterdir()) == ["certificate.json", "design.json", "design.png", "front.csv",
                                                     "front.png", "fronts.csv", "manifest.json", "run.json"]
    # the certificate records the chosen design; `mechopt check` re-checks it with its mechanism's settings
    cert = json.loads((out / "certificate.json").read_text())
    chosen = cert["designs"][cert["chosen"]]
    assert chosen["mechanism"] == "five-bar" and set(cert["settings"]) == {"five-bar"}
    assert len(cert["designs"]) == len(pd.read_csv(out / "fronts.csv"))
    capsys.readouterr()
    assert main(["check", str(out / "design.json")]) == 0
    text = capsys.readouterr().out
    assert "certificate.json records this design.json" in text and "all requirements hold" in text
    # a tampered claim fails the check, naming it
    chosen["requirements"]["lci"]["margin"] += 0.01
    (out / "certificate.json").write_text(json.dumps(cert))
    assert main(["check", str(out / "design.json")]) == 1
    assert "certificate.json: lci" in capsys.readouterr().out
