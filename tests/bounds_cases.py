"""Random tasks on every mechanism for the proven bounds (tests/test_bounds.py,
benchmarks/bench_bounds.py): a mechanism of each kind of the contract suite, tasks placed
about points away from its singularities, and the dense reference minimum by the point
evaluators (a different algorithm from the intervals)."""
from __future__ import annotations

import numpy as np

from mechanism_cases import CASES, sample_away_from_singularities
from mechopt.analysis import bounds as B
from mechopt.analysis.task import Task

#: one contract case per mechanism kind (all modes of it are drawn among)
KINDS = {
    "five-bar": [c for c in CASES if c[0].startswith("FiveBar[r1<r2")],
    "asymmetric-five-bar": [c for c in CASES if c[0].startswith("AsymmetricFiveBar")],
    "biglide": [c for c in CASES if c[0].startswith("Biglide[l1=40")],
    "bipod": [c for c in CASES if c[0].startswith("Bipod[stan")],
    "gantry": [c for c in CASES if c[0].startswith("Gantry[d1=100")],
}
TASK_KINDS = ("rect", "polygon", "circle", "path", "points")


def random_task(mech, rng, kind):
    """A task of ``kind`` about a point of ``mech`` away from its singularities, of size
    5 % to 30 % of its length scale."""
    x, y = sample_away_from_singularities(mech, rng, 1)
    c = np.array([x[0], y[0]])
    s = rng.uniform(0.05, 0.3) * mech.length_scale
    if kind == "rect":
        w, h = s * rng.uniform(0.5, 1.5, 2)
        return Task.rect(w, h, center=tuple(c))
    if kind == "circle":
        return Task.circle(0.5 * s, center=tuple(c))
    if kind == "polygon":
        n = int(rng.integers(3, 8))
        a = 2 * np.pi * (np.arange(n) + rng.uniform(0.0, 0.8, n)) / n  # increasing: a simple polygon
        r = 0.5 * s * rng.uniform(0.4, 1.0, n)
        return Task.polygon(c + np.stack([r * np.cos(a), r * np.sin(a)], 1))
    pts = c + rng.uniform(-0.5 * s, 0.5 * s, (int(rng.integers(2, 6)), 2))
    return Task.path(pts) if kind == "path" else Task.points(pts)


def dense_min(mech, task, q, n_grid, n_boundary):
    """The minimum of ``q`` over an ``n_grid`` x ``n_grid`` grid of the task's box (kept
    inside) and ``n_boundary`` points of its boundary (a path: along it; points: them)."""
    vals = []
    if task.is_region:
        x0, x1, y0, y1 = task.bbox
        for row in np.linspace(y0, y1, n_grid):  # row by row: memory
            gx = np.linspace(x0, x1, n_grid)
            gy = np.full_like(gx, row)
            keep = task.contains(gx, gy)
            if keep.any():
                vals.append(q.point(mech, gx[keep], gy[keep]).min())
    if task.kind == "points":
        vals.append(q.point(mech, task.pts[:, 0], task.pts[:, 1]).min())
    else:
        t = np.linspace(0.0, 1.0, n_boundary, endpoint=task.is_path)
        vals.append(q.point(mech, *task.boundary_at(t)).min())
    return float(min(vals))


def quantities(mech, rng):
    """Every quantity the requirements bound, with random actuator limits and both readings."""
    s0 = float(np.sign(rng.uniform(-1, 1))) or 1.0
    w, t = rng.uniform(0.5, 3.0, 2), rng.uniform(0.5, 3.0, 2)
    return [B.lci_quantity(), B.type2_quantity(s0), B.speed_quantity(w, "box"), B.speed_quantity(w, 2),
            B.force_quantity(t, "box", 2.0), B.force_quantity(t, 2, 2.0)]
