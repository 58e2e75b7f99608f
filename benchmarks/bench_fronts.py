"""Default runs against brute-force reference fronts (issue 12, part 3).

For every registered problem with at most 2 design variables, a reference front
is computed by brute force from the problem's own ``evaluate_designs``:

1. a lattice over the bounds: 2001 points for one variable, 161 x 161 for two
   (``--quick``: 201, 41 x 41);
2. refinement: a lattice 10 (two variables: 6; quick: 8, 4) times finer in the
   cells around every non-dominated feasible lattice point that has a neighbour
   off the front (the edges of the Pareto set in design space: for a front that
   is a curve in design space every point of it, for a 2-D set its outline; at
   most :data:`MAX_CENTRES` of them, evenly), once for one variable, twice for
   two (quick: once);
3. the feasible non-dominated designs of all evaluations.

A single-objective problem's "front" is its best feasible design; the
refinement zooms :data:`SO_LEVELS` times, :data:`SO_REFINE` times finer each,
around the best :data:`SO_TOP` designs instead.

Then the problem's default run, ``mechopt.run.runner.optimize(get(name), seed=1,
n_jobs=2)``, is measured against it: objectives in minimisation form,
normalised by the reference front's ideal and nadir (an objective whose span on
the reference front is zero, as on a single-design front, by its declared
range, :attr:`mechopt.run.problem.Objective.bounds`), IGD+
(``pymoo.indicators.igd_plus.IGDPlus``) and the ratio of hypervolumes
(``pymoo.indicators.hv.HV``, reference point 1.1 in every direction; above 1
where the run beats the lattice). For a single objective, the relative gap
``(f_run - f_ref) / |f_ref|`` of the best values in minimisation form (> 0: the
run is worse). Targets: IGD+ <= 0.01, HV ratio >= 0.98 (gap <= 1e-4 for one
objective) and each default run under 60 s on 2 cores. The same run is repeated
with ``n_jobs=None`` (the runner's choice, shown with its time): its front must
be the same (``--no-auto`` skips it).

    python benchmarks/bench_fronts.py [--quick] [--problems a,b] [--cache DIR] [--no-auto]

The full references take about 15 minutes on 2 cores (most of it le2013-gamma and
le2013-relaxed, 3-5 ms per design), ``--quick`` about 1 minute; the default runs
about 2 minutes twice. ``--cache DIR`` keeps the reference fronts
(``DIR/<problem>-<lattice>.npz``) for the next call. Exit status 1 if a target is
missed. The functions are imported by ``tests/test_convergence.py``.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from mechopt.problems import get, names
from mechopt.run import reference as _ref
from mechopt.run.reference import (FULL, MAX_CENTRES, QUICK, SO_LEVELS, SO_REFINE, SO_TOP,  # noqa: F401
                                   compare, nondominated, normalisation)

#: targets of the issue
IGD_MAX, HV_MIN, GAP_MAX, SECONDS_MAX = 0.01, 0.98, 1e-4, 60.0


def reference_front(name, grid=None, refine=None, levels=None, n_jobs=2, quick=False, log=None):
    """:func:`mechopt.run.reference.reference_front` of the registered problem ``name``."""
    return _ref.reference_front(get(name), grid, refine, levels, n_jobs=n_jobs, quick=quick, log=log)


def default_run(name, n_jobs=2, seed=1):
    """The default run of ``name``: ``(F in minimisation form, seconds, run.json info)``;
    ``n_jobs=None``: the runner chooses."""
    from mechopt.run.runner import optimize

    p = get(name)
    t0 = time.perf_counter()
    res = optimize(p, seed=seed, n_jobs=n_jobs, progress=False, plot=False)
    wall = time.perf_counter() - t0
    F = np.column_stack([ob.sense * res.front[ob.name].to_numpy(float) for ob in p.objectives]) \
        if len(res.front) else np.empty((0, p.n_obj))
    return F, wall, res.info


def bench_problems():
    """Every registered problem with at most 2 design variables."""
    return [n for n in names() if get(n).n_var <= 2]


def _cached_reference(name, quick, cache, log):
    p = get(name)
    grid = (QUICK if quick else FULL)[p.n_var]
    grid = (grid[0], SO_TOP, SO_REFINE, SO_LEVELS) if p.n_obj == 1 else grid + (MAX_CENTRES,)
    path = Path(cache) / f"{name}-{'-'.join(map(str, grid))}.npz" if cache else None
    if path is not None and path.exists():
        z = np.load(path)
        return {"X": z["X"], "F": z["F"], "evaluations": int(z["evaluations"]), "seconds": float(z["seconds"])}
    ref = reference_front(name, quick=quick, log=log)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez(path, **ref)
    return ref


def _budget(info):
    a = info["algorithm"]
    text = f"{a['name']} {a['pop']}x{a['gen']}"
    if a.get("polish"):
        text += f" + {a['polish']}"
    return text


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="coarse reference lattices")
    ap.add_argument("--problems", default=None, help="comma list (default: every problem with <= 2 variables)")
    ap.add_argument("--cache", default=None, help="folder that keeps the reference fronts")
    ap.add_argument("--no-auto", action="store_true",
                    help="skip the second default run with the automatic number of processes")
    args = ap.parse_args(argv)
    todo = args.problems.split(",") if args.problems else bench_problems()

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    rows, ok = [], True
    for name in todo:
        p = get(name)
        ref = _cached_reference(name, args.quick, args.cache, log)
        F, wall, info = default_run(name, n_jobs=2)
        if args.no_auto:
            auto = ""
        else:  # the same run with n_jobs=None: the same front, the runner's choice of processes
            F_auto, wall_auto, info_auto = default_run(name, n_jobs=None)
            same = F_auto.shape == F.shape and np.array_equal(F_auto, F)
            ok &= same
            auto = f"{wall_auto:.1f} ({info_auto['n_jobs']}){'' if same else ' FRONT DIFFERS'}"
        m = compare(p, ref["F"], F)
        if p.n_obj == 1:
            good = m["gap"] <= GAP_MAX and wall < SECONDS_MAX
            quality = f"gap {m['gap']:+.2e}"
        else:
            good = m["igd_plus"] <= IGD_MAX and m["hv_ratio"] >= HV_MIN and wall < SECONDS_MAX
            quality = f"{m['igd_plus']:.4f}  {m['hv_ratio']:.4f}"
        ok &= good
        rows.append((name, p.n_var, p.n_obj, quality, len(F), len(ref["F"]), wall, auto, _budget(info),
                     "ok" if good else "MISS"))
        log(f"{name}: {quality}, {wall:.1f} s ({len(ref['F'])} reference points, "
            f"{ref['evaluations']} evaluations in {ref['seconds']:.0f} s)")
    print("| problem | vars | obj | IGD+ (or gap) | HV ratio | front | ref. front | s (2 jobs) "
          "| s (auto: jobs) | default run | |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        q = r[3].split()
        igd, hv = (q[0], q[1]) if q[0] != "gap" else (" ".join(q), "-")
        print(f"| {r[0]} | {r[1]} | {r[2]} | {igd} | {hv} | {r[4]} | {r[5]} | {r[6]:.1f} | {r[7]} | {r[8]} | {r[9]} |")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
