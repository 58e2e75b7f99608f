"""Tasks whose reference point is not theirs (issue: certificates that hold): an arch
(a half annulus about the base) and an L shape. The bounding-box centre of both lies
outside the task, and for the arch it can lie in the hole of a design's workspace, where
the type-II sign used to be taken: such designs were refused ("singular") or the search
ended on larger ones. Checked against the brute-force scan of
benchmarks/bench_design.py, which knows nothing of the design workflow (it checks
``FiveBar.reachable``, ``lci`` and ``type2_function`` on its own points: a grid of the
polygon's box kept inside by matplotlib's point-in-polygon, and points along its edges)."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from matplotlib.path import Path as PolyPath

from mechopt import FiveBar
from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.task import Task
from mechopt.requirements import Requirements
from mechopt.workflows.design import design

ROOT = Path(__file__).resolve().parents[1]

_A = np.radians(np.linspace(20.0, 160.0, 29))
#: 100-130 mm from the base midpoint, 20-160 deg: its box centre (0, 82.1) is in the hole
ARCH = np.vstack([np.column_stack([130 * np.cos(_A), 130 * np.sin(_A)]),
                  np.column_stack([100 * np.cos(_A[::-1]), 100 * np.sin(_A[::-1])])])
#: its box centre (0, 165) lies in the missing corner
L_SHAPE = np.array([(-60, 120), (60, 120), (60, 150), (-30, 150), (-30, 210), (-60, 210)], float)
CASES = {"arch": (ARCH, 0.2), "L": (L_SHAPE, 0.3)}


def polygon_points(V, n=60, nb=600):
    """A grid of ``V``'s box (``n`` x ``n``) kept inside ``V`` and ``nb`` points along
    its edges at uniform arc length."""
    x0, y0 = V.min(0)
    x1, y1 = V.max(0)
    gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    inside = PolyPath(V).contains_points(np.column_stack([gx.ravel(), gy.ravel()]))
    E = np.vstack([V, V[:1]])
    seg = np.hypot(*np.diff(E, axis=0).T)
    ends = np.concatenate([[0.0], np.cumsum(seg)])
    s = np.linspace(0.0, ends[-1], nb, endpoint=False)
    k = np.searchsorted(ends, s, side="right") - 1
    t = (s - ends[k]) / seg[k]
    P = E[k] + t[:, None] * (E[k + 1] - E[k])
    return np.concatenate([gx.ravel()[inside], P[:, 0]]), np.concatenate([gy.ravel()[inside], P[:, 1]])


def _holds_on_points(r1, r2, r3, V, gamma):
    """The scan's own check (reach, LCI >= gamma, one type-II sign) on a denser set."""
    x, y = polygon_points(V, n=201, nb=4000)
    fb = FiveBar(r1, r2, r3, "+-")
    if not fb.reachable(x, y).all():
        return False
    f = fb.type2_function(x, y)
    return bool(fb.lci(x, y).min() >= gamma - 1e-9 and (np.all(f > 0) or np.all(f < 0)))


def test_a_design_whose_workspace_misses_the_box_centre_is_certified():
    """r1 = 45.6, r2 = 131.3, r3 = 7.3 (mode +-) covers the arch (100-130 mm from the
    base midpoint; each leg's annulus is 85.7-176.9 mm about its base joint) with one
    type-II sign, while the arch's box centre (0, 82.1) is in the holes: the evaluator
    certifies it (reach and one type-II sign over the arch), as the check on 201 x 201
    + 4000 points written here does."""
    ev = DesignEvaluator("five-bar", Task.polygon(ARCH), Requirements(), ("size",), max_length=300)
    cx, cy = ev.task.reference
    r1, r2, r3 = 45.6, 131.3, 7.3
    v = {"r1": r1, "r2": r2, "r3": r3, "mode": "+-", "task_x": cx, "task_y": cy}
    fb = FiveBar(r1, r2, r3, "+-")
    box = (ARCH.min(0) + ARCH.max(0)) / 2
    assert not fb.reachable(*box)  # the old reference point is out of reach
    assert _holds_on_points(r1, r2, r3, ARCH, 0.0)
    res = certify(ev, v)
    assert res["feasible"], res["g"]
    assert res["margin"]["reach"] > 0 and res["margin"]["singular"] > 0


@pytest.mark.parametrize("case", list(CASES))
def test_small_runs_on_the_arch_and_the_l_shape_hold_on_a_dense_check(case):
    """A small seeded run (no polish) finds feasible designs on both, and each front
    design passes the dense check written here."""
    V, gamma = CASES[case]
    res = design("five-bar", Task.polygon(V), Requirements(min_lci=gamma), ("size",), mode="+-", seed=1,
                 pop=12, gen=8, n_jobs=1, polish=False, max_length=300)
    assert len(res.front) >= 1
    for _, row in res.front.iterrows():
        assert (row["task_x"], row["task_y"]) == pytest.approx(tuple(Task.polygon(V).reference))
        assert _holds_on_points(row["r1"], row["r2"], row["r3"], V, gamma), row.to_dict()


def _bench():
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import bench_design

    return bench_design


@pytest.mark.slow
@pytest.mark.parametrize("case", list(CASES))
def test_smallest_design_within_half_a_percent_of_the_brute_force_scan(case):
    """The default run (with its polish) against the scan (lattice 10 mm, then 1 mm, then
    0.1 mm around the best; fixed placement, mode +-): the smallest front design at most
    0.5 % above the scan's smallest, and it passes the dense check (201 x 201 + 4000
    points)."""
    V, gamma = CASES[case]
    x, y = polygon_points(V)
    fixed = lambda *r: np.zeros(1)  # noqa: E731
    bf = _bench()._brute_force(x, y, fixed, lambda dy: fixed, (0.0, 0.0), gamma)
    res = design("five-bar", Task.polygon(V), Requirements(min_lci=gamma), ("size",), mode="+-", seed=1,
                 n_jobs=1, max_length=300)
    best = res.front.iloc[int(np.argmin(res.front["size"]))]
    gap = (best["size"] - bf["size"]) / bf["size"]
    print(f"{case}: design {best['size']:.2f} mm, brute force {bf['size']:.2f} mm, gap {100 * gap:.3f} %")
    # not more than 0.5 % above the scan; below it only with the dense check passed (the
    # scan is a descent on a 0.1 mm lattice, not a global certificate: on the arch the
    # run's 262.22 mm design holds where the scan stopped at 263.6 mm)
    assert gap <= 0.005, (best.to_dict(), bf)
    assert _holds_on_points(best["r1"], best["r2"], best["r3"], V, gamma), best.to_dict()
