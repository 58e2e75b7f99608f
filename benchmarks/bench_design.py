"""``mechopt design`` against a brute-force scan: the smallest feasible five-bar.

    python benchmarks/bench_design.py [--place fixed|free-y] [--task rect:W,H@X,Y]
                                      [--min-lci G] [--cli]

The scan is independent of :mod:`mechopt.workflows.design` (it calls only ``FiveBar``'s
``reachable``, ``lci`` and ``type2_function``). A design is feasible when, on the
task's check points (a 41 x 25 grid of the rectangle, edges included, plus 400
points along its boundary), every point is reachable, ``LCI >= gamma`` and
``type2_function`` has one sign. ``size = 2 (r1 + r2 + r3)``. Default task: the
issue's ``rect:100,60@0,180`` with ``LCI >= 0.4``.

Lattice search, coarse to fine: designs of a lattice are checked in order of
increasing size, so the first feasible one is the lattice's smallest.

1. ``r1, r2`` in [20, 300] step 10 mm, ``r3`` in [0, 200] step 10 mm (17 661 designs);
2. step 1 mm in a box of +-10 mm around the 5 smallest feasible designs of stage 1;
3. step 0.1 mm in a box of +-1.5 mm around the best so far (``r3 >= 0``), repeated
   around each new best until the best stays: a descent on the 0.1 mm lattice.
   Near the smallest design the feasible set is a thin wedge in ``(r1, r2)`` (for
   the issue's free-y task ``r2 - r1`` is pinned near 3.3 mm at its tip), which one
   box around the 1 mm lattice's best does not reach.

With ``--place free-y`` every lattice design is checked at every task height
``task_y`` of a grid, vectorised over heights: step 0.25 mm (stages 1-2) from the
task's lower edge on the base line (``task_y = H/2``, the lowest placement ``mechopt
design`` searches) up to where the upper corners leave the outer reach ``r1 + r2``
of the farther base joint; in stage 3 step 0.05 mm in a +-2 mm window around the
best's height. Near the smallest design the heights where a design covers the task
are a window a fraction of a millimetre wide (it closes at the minimum), so a coarse
height grid misses it: the first version of this scan (5 mm heights, one stage-3
box) reported 182.2 mm for the issue's free-y task, where 175.4 mm designs are
feasible by this very check. The result is the lattice's best, within about the
lattice step of a local minimum (0.1 mm per variable, 0.05 mm of height), not a
global certificate.
"""
from __future__ import annotations

import argparse
import itertools
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from mechopt import FiveBar

TASK = dict(width=100.0, height=60.0, center=(0.0, 180.0))
TASK_TEXT = "rect:100,60@0,180"
GAMMA = 0.4


def check_points(width, height, center, nx=41, ny=25, nb=400):
    cx, cy = center
    gx, gy = np.meshgrid(np.linspace(-width / 2, width / 2, nx), np.linspace(-height / 2, height / 2, ny))
    per = 2 * (width + height)
    s = np.linspace(0, per, nb, endpoint=False)
    bx = np.where(s < width, -width / 2 + s,
                  np.where(s < width + height, width / 2,
                           np.where(s < 2 * width + height, width / 2 - (s - width - height), -width / 2)))
    by = np.where(s < width, -height / 2,
                  np.where(s < width + height, -height / 2 + (s - width),
                           np.where(s < 2 * width + height, height / 2, height / 2 - (s - 2 * width - height))))
    x = np.concatenate([gx.ravel(), bx]) + cx
    y = np.concatenate([gy.ravel(), by]) + cy
    return x, y


def feasible_heights(r1, r2, r3, x, y, dys, gamma=GAMMA):
    """Boolean per height offset ``dy``: the design covers the task moved by dy."""
    fb = FiveBar(r1, r2, r3, "+-")
    ok = np.zeros(len(dys), bool)
    X = np.broadcast_to(x[None, :], (len(dys), len(x)))
    Y = y[None, :] + dys[:, None]
    reach = fb.reachable(X, Y).all(axis=1)
    if not reach.any():
        return ok
    k = np.flatnonzero(reach)  # LCI only where everything is reached,
    k = k[(fb.lci(X[k], Y[k]) >= gamma).all(axis=1)]
    if k.size:  # the singularity sign only where the LCI holds too
        f = fb.type2_function(X[k], Y[k])
        ok[k] = np.all(f > 0, axis=1) | np.all(f < 0, axis=1)
    return ok


def _scan(designs, x, y, dys, gamma):
    """First feasible designs of ``designs`` (sorted by size, up to 5) and the best
    height of each. ``dys(r1, r2, r3)`` gives the height offsets to check."""
    sizes = 2 * designs.sum(axis=1)
    order = np.argsort(sizes, kind="stable")
    found, n = [], 0
    for i in order:
        r1, r2, r3 = designs[i]
        if r1 <= 0 or r2 <= 0 or r3 < 0:
            continue
        d = dys(r1, r2, r3)
        n += 1
        if not d.size:
            continue
        ok = feasible_heights(r1, r2, r3, x, y, d, gamma)
        if ok.any():
            # the middle of the feasible heights (the window is one interval near the optimum)
            k = np.flatnonzero(ok)
            found.append((sizes[i], (r1, r2, r3), float(d[k[len(k) // 2]])))
            if len(found) >= 5:
                break
    return found, n


def height_offsets(width, height, center, step):
    """Height offsets ``dy`` (task centre at ``center[1] + dy``) a design can cover, on a
    grid of ``step`` [mm]: from the task's lower edge on the base line (the lowest
    placement ``mechopt design`` searches for the five-bar) up to where the task's
    upper corners leave the outer reach ``r1 + r2`` of the farther base joint (a
    necessary condition: no height above can be feasible)."""
    def dys(r1, r2, r3):
        reach2 = (r1 + r2) ** 2 - (width / 2 + abs(center[0]) + r3) ** 2
        top = np.sqrt(reach2) - height / 2 if reach2 > 0 else -np.inf
        lo = height / 2
        if top < lo:
            return np.zeros(0)
        return np.arange(lo, top + 1e-9, step) - center[1]
    return dys


def brute_force(place="fixed", width=TASK["width"], height=TASK["height"], center=TASK["center"],
                gamma=GAMMA):
    x, y = check_points(width, height, center)
    if place == "fixed":
        dys1 = dys3 = lambda *r: np.zeros(1)  # noqa: E731
        dys3_at = lambda dy: dys3  # noqa: E731
    else:
        dys1 = height_offsets(width, height, center, 0.25)

        def dys3_at(dy):
            return lambda *r: dy + np.arange(-2.0, 2.0 + 1e-9, 0.05)
    return _brute_force(x, y, dys1, dys3_at, center, gamma)


def _brute_force(x, y, dys1, dys3_at, center, gamma):
    t0 = time.perf_counter()
    g = np.array(list(itertools.product(np.arange(20, 301, 10.0), np.arange(20, 301, 10.0),
                                        np.arange(0, 201, 10.0))))
    found, n1 = _scan(g, x, y, dys1, gamma)
    if not found:
        raise RuntimeError("no feasible design on the coarse lattice")
    cands, n2 = [], 0
    for _, (r1, r2, r3), dy in found:
        box = np.array(list(itertools.product(r1 + np.arange(-10, 11.0), r2 + np.arange(-10, 11.0),
                                              np.maximum(r3 + np.arange(-10, 11.0), -1))))
        box = box[box[:, 2] >= 0]
        f2, k = _scan(box, x, y, dys1, gamma)
        n2 += k
        cands += f2[:1]
    cands.sort(key=lambda c: c[0])
    best, n3, boxes = cands[0], 0, 0
    while boxes < 40:  # stage 3, repeated around the best until it stays (a descent on the lattice)
        _, (r1, r2, r3), dy = best
        step = np.round(np.arange(-1.5, 1.51, 0.1), 10)
        box = np.array(list(itertools.product(np.round(r1 + step, 10), np.round(r2 + step, 10),
                                              np.round(r3 + step, 10))))
        box = box[box[:, 2] >= -1e-9]
        box[:, 2] = np.maximum(box[:, 2], 0.0)
        f3, k = _scan(box, x, y, dys3_at(dy), gamma)
        n3, boxes = n3 + k, boxes + 1
        if not f3 or f3[0][0] >= best[0] - 1e-9:
            break
        best = f3[0]
    size, (r1, r2, r3), dy = best
    return {"size": float(size), "r1": float(r1), "r2": float(r2), "r3": float(r3),
            "task_y": float(center[1] + dy), "designs_checked": int(n1 + n2 + n3), "stage3_boxes": boxes,
            "seconds": time.perf_counter() - t0}


def parse_rect(text):
    """``rect:W,H@X,Y`` (the CLI's task syntax, rectangles only) -> (width, height, center)."""
    kind, _, body = text.partition(":")
    size, _, at = body.partition("@")
    if kind != "rect" or not at:
        raise ValueError(f"the scan handles rect:W,H@X,Y tasks, got {text!r}")
    w, h = (float(v) for v in size.split(","))
    cx, cy = (float(v) for v in at.split(","))
    return w, h, (cx, cy)


def run_cli(place, out, task=TASK_TEXT, gamma=GAMMA, extra=()):
    cmd = [sys.executable, "-m", "mechopt.cli", "design", "five-bar", "--task", task,
           "--min-lci", str(gamma), "--out", str(out), *extra] + (["--place", place] if place != "fixed" else [])
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    import pandas as pd

    front = pd.read_csv(Path(out) / "front.csv")
    return wall, float(front["size"].min())


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--place", default="fixed", choices=("fixed", "free-y"))
    ap.add_argument("--task", default=TASK_TEXT, help=f"rect:W,H@X,Y (default {TASK_TEXT})")
    ap.add_argument("--min-lci", type=float, default=GAMMA, help=f"LCI requirement (default {GAMMA})")
    ap.add_argument("--cli", action="store_true", help="also time the CLI command and compare")
    args = ap.parse_args(argv)
    w, h, c = parse_rect(args.task)
    bf = brute_force(args.place, w, h, c, args.min_lci)
    out = {"place": args.place, "task": args.task, "min_lci": args.min_lci, "brute_force": bf}
    if args.cli:
        with tempfile.TemporaryDirectory() as d:
            wall, smallest = run_cli(args.place, Path(d) / "run", args.task, args.min_lci)
        out.update(cli_wall_s=round(wall, 2), cli_smallest_size=smallest,
                   gap_percent=100.0 * (smallest - bf["size"]) / bf["size"])
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
