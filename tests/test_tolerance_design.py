"""``mechopt design --tolerance T``: every front design holds for every mechanism whose
lengths lie within +-T of its own (issue 28, item 4).

The check is mechopt.FiveBar's own point kinematics on a dense grid of the placed task
plus its boundary, for random builds drawn inside each front design's box: every point
reachable, one sign of the type-II function (the margin 1e-3 of the requirement), LCI
>= gamma. CI: a small run without polish, 40 builds per front design on a 101 x 101 grid
+ 2000 boundary points; ``-m slow``: the issue's figures, the README rectangle with the
polish (which walks into knife edges unless the box stops it), 1000 builds per front
design, each on a 401 x 401 grid + 4000 boundary points.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import mechopt
from mechopt.analysis.design_eval import NoFeasibleDesign
from mechopt.analysis.task import parse_task
from mechopt.requirements import Requirements
from mechopt.workflows.design import design

TASK, GAMMA, T = "rect:100,60@0,180", 0.4, 0.05


def _violations(row, n_builds, n_grid, n_boundary, seed, tol=T):
    """Builds inside the +-``tol`` box of the front row ``row`` (three lengths and the
    task's placement in x and y; the 32 corners among them) that fail somewhere on the
    dense check, and the smallest LCI met."""
    task = parse_task(TASK)
    x0, x1, y0, y1 = task.moved_to(0.0, 0.0).bbox
    gx, gy = np.meshgrid(np.linspace(x0, x1, n_grid), np.linspace(y0, y1, n_grid))
    tb, _ = task.boundary_params(n_boundary)
    bx, by = task.moved_to(0.0, 0.0).boundary_at(tb)
    x0, y0 = np.r_[gx.ravel(), bx], np.r_[gy.ravel(), by]  # about the task's centre
    rng = np.random.default_rng(seed)
    corners = np.array(np.meshgrid(*[[-1.0, 1.0]] * 5)).reshape(5, -1).T
    offsets = np.vstack([corners, rng.uniform(-1.0, 1.0, size=(n_builds - len(corners), 5))]) * tol
    bad, low = [], np.inf
    for off in offsets:
        x, y = x0 + row["task_x"] + off[3], y0 + row["task_y"] + off[4]
        mech = mechopt.FiveBar(row["r1"] + off[0], row["r2"] + off[1], max(row["r3"] + off[2], 0.0),
                               mode=row["mode"])
        f = mech.type2_function(x, y)
        lci = mech.lci(x, y)
        ok = mech.reachable(x, y).all() and (np.all(f >= 1e-3) or np.all(f <= -1e-3)) and lci.min() >= GAMMA
        low = min(low, float(np.nanmin(lci)))
        if not ok:
            bad.append(off)
    return bad, low


def _run(tmp_path, **kw):
    return design("five-bar", parse_task(TASK), Requirements(min_lci=GAMMA), ("size", "min-lci"),
                  max_length=250, seed=1, n_jobs=1, tolerance=T, out=tmp_path / "run", **kw)


@pytest.fixture(scope="module")
def small_run(tmp_path_factory):
    return _run(tmp_path_factory.mktemp("tol"), pop=12, gen=6, polish=False)


def test_every_front_design_holds_over_its_box_on_a_dense_check(small_run):
    res = small_run
    assert len(res.front) >= 2 and res.info["tolerance"] == T
    for i, row in res.front.iterrows():
        bad, low = _violations(row, 40, 101, 2000, seed=i)
        assert not bad, (i, bad[:3])
        # the proven bound over the box never claims more than a build shows
        box = res.boxes[i]
        assert box["method"] == "proven"
        assert box["proven"]["lci"]["lower_bound"] <= low + 1e-12
        # the larger tolerance the front reports holds too (and is at least the one asked)
        assert row["tolerance_max"] >= T
        bad, _ = _violations(row, 40, 101, 2000, seed=100 + i, tol=row["tolerance_max"])
        assert not bad, (i, row["tolerance_max"], bad[:3])
    # the designs away from the LCI edge are certified for larger boxes (T times 2, 4, 8)
    assert set(res.front["tolerance_max"] / T) <= {1.0, 2.0, 4.0, 8.0}
    assert res.front["tolerance_max"].max() >= 4 * T


def test_certificate_json_records_each_design_s_box(small_run):
    from mechopt.workflows.certificate import certificate

    assert small_run.info["dropped_by_tolerance"] >= 0 and small_run.info["tolerance"] == T
    cert = certificate(small_run)
    assert len(cert["designs"]) == len(small_run.front)
    for d in cert["designs"]:
        box = d["tolerance_box"]
        assert box["tolerance"] == T and box["evaluated"] == 8 + 4 and box["holds"] == {
            "reach": True, "singular": True, "lci": True}


def test_a_tolerance_no_design_survives_is_an_empty_result_naming_the_requirement(tmp_path):
    task = parse_task("rect:100,60@0,180")
    with pytest.raises(NoFeasibleDesign, match=r"no design holds over its tolerance box \+-40 mm: .* fails in"):
        design("five-bar", task, Requirements(min_lci=GAMMA), ("size",), max_length=250, seed=1, n_jobs=1,
               pop=12, gen=6, polish=False, tolerance=40.0, out=tmp_path / "run")
    info = json.loads((tmp_path / "run" / "run.json").read_text())
    assert info["no_design"].startswith("no design holds over its tolerance box")


@pytest.mark.slow
def test_issue_28_thousand_builds_per_front_design(tmp_path):
    res = _run(tmp_path)  # the default budget, with the polish
    assert len(res.front) >= 5
    for i, row in res.front.iterrows():
        bad, _ = _violations(row, 1000, 401, 4000, seed=i)
        assert not bad, (i, len(bad))


@pytest.mark.parametrize("value", ["-1", "0", "nan", "inf"])
def test_a_bad_tolerance_is_one_line_exit_2_and_writes_nothing(value, tmp_path, capsys):
    from mechopt.cli import main

    out = tmp_path / "run"
    assert main(["design", "five-bar", "--task", TASK, "--tolerance", value, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "tolerance must be" in err[0] and not out.exists()
