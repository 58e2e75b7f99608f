"""Certificates that hold (issue 28): full-precision CSV, placement on both sides of the
base line, certificate.json and ``mechopt check`` (with tolerance boxes).

The knife-edge design below was found by bisection on r3 from a polished front design
(rect:40,30@0,150, LCI >= 0.4): at full precision its LCI margin is >= 0 (5.6e-17),
at r3 rounded to 10 significant digits it is -2.7e-12 (the assertions check both).
"""
from __future__ import annotations

import io
import json

import numpy as np
import pandas as pd
import pytest

from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.task import parse_task
from mechopt.requirements import Requirements
from mechopt.run import io as _io

KNIFE_TASK = "rect:40,30@0,150"
KNIFE = dict(r1=124.36986838734104, r2=45.953153080330914, r3=3.175029087666897, mode="+-",
             task_x=0.0, task_y=150.0)


def _knife_evaluator():
    return DesignEvaluator("five-bar", parse_task(KNIFE_TASK), Requirements(min_lci=0.4), ("size", "min-lci"),
                           max_length=250)


# ----------------------------------------------------------------- 1. full precision
def test_write_csv_round_trips_every_double(tmp_path):
    """Any double written by write_csv reads back (pandas' default parser) bit for bit;
    10 significant digits (the former format) would not."""
    rng = np.random.default_rng(5)
    x = rng.normal(size=5000) * 10.0 ** rng.integers(-12, 12, 5000)
    x[:4] = [0.1, 1 / 3, -0.0, 5e-324]
    df = pd.DataFrame({"a": x, "b": np.nextafter(x, np.inf), "mode": ["+-"] * len(x)})
    _io.write_csv(df, tmp_path / "f.csv")
    back = pd.read_csv(tmp_path / "f.csv", dtype={"mode": str})
    assert np.array_equal(back["a"].to_numpy(), x) and np.array_equal(back["b"].to_numpy(), df["b"].to_numpy())
    assert np.array_equal(np.signbit(back["a"].to_numpy()), np.signbit(x))
    rounded = pd.read_csv(io.StringIO(df.to_csv(index=False, float_format="%.10g")))
    assert not np.array_equal(rounded["a"].to_numpy(), x)  # the check can fail


def test_front_row_of_a_knife_edge_design_reads_back_feasible(tmp_path):
    """A design whose LCI margin is 5.6e-17: its front.csv row, re-read, has the very
    lengths and margins, and re-evaluating the re-read lengths violates nothing; the
    same row at 10 digits violates LCI (what the issue found in front.csv)."""
    ev = _knife_evaluator()
    res = certify(ev, KNIFE)
    assert res["feasible"] and 0 <= res["margin"]["lci"] < 1e-15
    row = ev.row(KNIFE, res)
    _io.write_csv(pd.DataFrame([row]), tmp_path / "front.csv")
    back = pd.read_csv(tmp_path / "front.csv", dtype={"mode": str}).iloc[0].to_dict()
    for k, val in row.items():
        assert back[k] == val, k
    again = certify(ev, {k: back[k] for k in KNIFE})
    assert again["feasible"] and again["margin"] == res["margin"]
    rounded = {k: float(f"{val:.10g}") if isinstance(val, float) else val for k, val in KNIFE.items()}
    assert not certify(ev, rounded)["feasible"]


# ----------------------------------------------------------------- 2. placement
SHAPE_TASK = dict(shape=(1.2, 0.8, 0.6), max_length=100, seed=1, pop=12, gen=6, n_jobs=1, polish=False)


def _grid_check(mech, task, gamma, n=61):
    """Own check on an n x n grid of the placed square task: every point reachable, one
    sign of the type-II function, the smallest LCI (mechopt.FiveBar's kinematics)."""
    x0, x1, y0, y1 = task.bbox
    gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    x, y = gx.ravel(), gy.ravel()
    if not mech.reachable(x, y).all():
        return False, 0.0
    f = mech.type2_function(x, y)
    lci = mech.lci(x, y)
    return bool((np.all(f > 0) or np.all(f < 0)) and lci.min() >= gamma - 1e-9), float(lci.min())


@pytest.fixture(scope="module")
def shape_runs():
    from mechopt.analysis.task import Task
    from mechopt.workflows.design import design

    task, req = Task.rect(10, 10), Requirements(min_lci=0.5)
    return task, {place: design("five-bar", task, req, ("size",), place=place, mode="+-", **SHAPE_TASK)
                  for place in ("free-y", "free")}


def test_free_y_searches_below_the_base_line(shape_runs):
    """Mode +-, shape (1.2, 0.8, 0.6), a 10 mm square, LCI >= 0.5: the design found lies
    below the base line, holds on a 61 x 61 grid (own check), and at its size no height
    above the line works in mode +- (a scan of 300 heights, each on the grid): the
    search above only could not have found it. Its mirror image is the same design in
    mode -+ above the line."""
    import mechopt

    task, runs = shape_runs
    best = runs["free-y"].front.iloc[0]
    assert best["task_y"] < 0
    mech = mechopt.FiveBar(best["r1"], best["r2"], best["r3"], mode="+-")
    ok, lmin = _grid_check(mech, task.moved_to(best["task_x"], best["task_y"]), 0.5)
    assert ok, lmin
    mirror = mechopt.FiveBar(best["r1"], best["r2"], best["r3"], mode="-+")
    ok_m, lmin_m = _grid_check(mirror, task.moved_to(best["task_x"], -best["task_y"]), 0.5)
    assert ok_m and lmin_m == pytest.approx(lmin, rel=1e-12, abs=1e-12)
    D = best["D"]
    above = [_grid_check(mech, task.moved_to(0.0, y), 0.5, n=21) for y in np.linspace(0.01 * D, 3 * D, 300)]
    assert not any(ok for ok, _ in above)


def test_free_contains_free_y(shape_runs):
    """``--place free`` on the same seed and budget ends no worse than ``free-y``: every
    free-y front design is on free's front or dominated by one of its designs."""
    _, runs = shape_runs
    fy, fr = runs["free-y"], runs["free"]
    assert fr.info["free_y_designs"] == len(fy.front) >= 1
    assert fr.front["size"].min() <= fy.front["size"].min()
    for s in fy.front["size"]:
        assert (fr.front["size"] <= s).any()
