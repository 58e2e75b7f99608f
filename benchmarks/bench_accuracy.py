"""The cost per design of the accuracy requirement inside the design loop.

    python benchmarks/bench_accuracy.py [--designs N] [--repeat R]

For each mechanism ``mechopt design`` sizes, ``N`` seeded designs (the task
``rect:100,60@0,180`` for the five-bars, a task in each design's reachable set
otherwise), each evaluated on the samples of one design evaluation (192 boundary
points and a 13 x 13 interior grid, :func:`mechopt.analysis.sampling.samples`):
:func:`mechopt.analysis.accuracy.task_max_error` (the proven bound at every sample, its
maximum refined by the zoom searches: what ``--max-error`` computes in the design
loop), best of ``R`` timings per design, in CPU time of this process
(``time.process_time``: on a shared machine wall time measures its load). Target:
<= 50 ms per design. Prints one line
per mechanism: median and largest ms per design (and the samples alone,
:func:`~mechopt.analysis.accuracy.max_error`); then the whole evaluation of
a five-bar design in the design loop (:class:`mechopt.analysis.design_eval.DesignEvaluator`,
``--min-lci 0.4``) with and without ``--max-error``: what the requirement adds.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from mechopt import FiveBar
from mechopt.analysis.accuracy import ErrorModel, max_error, task_max_error
from mechopt.analysis.sampling import Sampling, samples
from mechopt.analysis.task import Task
from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar
from mechopt.mechanisms.biglide import Biglide
from mechopt.mechanisms.bipod import Bipod
from mechopt.mechanisms.gantry import Gantry

MODEL = ErrorModel(encoder_counts=16384, backlash_arcmin=1.0, resolution_um=1.0, backlash_um=5.0,
                   clearance_um=5.0, link_tol_um=10.0, base_tol_um=10.0)


def cases(rng, n):
    """``(name, mech, dx, dy)``: seeded designs and the shift of the task samples into their frame."""
    u = rng.uniform
    for _ in range(n):
        yield "five-bar", FiveBar(u(150, 200), u(170, 230), u(0, 40)), 0.0, 0.0
        yield "asymmetric-five-bar", AsymmetricFiveBar(u(150, 200), u(170, 230), u(150, 200), u(170, 230),
                                                       u(0, 40)), 0.0, 0.0
        b = u(100, 200)
        yield "bipod", Bipod(b, 60, 400), b / 2, 0.0
        l1 = u(30, 60)
        yield "biglide", Biglide(l1, l1 + u(90, 150), -400, 400), 0.0, -180.0
        d1 = u(30, 60)
        yield "gantry", Gantry(d1, d1 + u(90, 150), 800, q_min=-400), 0.0, -180.0


def _best(f, repeat):
    best = np.inf
    for _ in range(repeat):
        t0 = time.process_time()
        v = f()
        best = min(best, time.process_time() - t0)
    return v, best * 1e3


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", type=int, default=20, help="designs per mechanism (default 20)")
    ap.add_argument("--repeat", type=int, default=5, help="timings per design, the best kept (default 5)")
    args = ap.parse_args(argv)
    s = samples(Task.rect(100, 60, (0, 180)), Sampling())
    times, plain = {}, {}
    for name, mech, dx, dy in cases(np.random.default_rng(1), args.designs):
        def to_mech(x, y, dx=dx, dy=dy):
            return x + dx, y + dy

        assert mech.reachable(*to_mech(s["allx"], s["ally"])).all(), mech
        v, t = _best(lambda: task_max_error(mech, MODEL, s, to_mech), args.repeat)
        w, t0 = _best(lambda: max_error(mech, MODEL, *to_mech(s["allx"], s["ally"])), args.repeat)
        assert np.isfinite(v) and v >= w, mech
        times.setdefault(name, []).append(t)
        plain.setdefault(name, []).append(t0)
    print(f"accuracy requirement, {s['allx'].size} samples (192 boundary + 13 x 13 grid) and the zoom, "
          "target <= 50 ms per design:")
    for name, t in times.items():
        print(f"  {name:20s} median {np.median(t):6.2f} ms, max {np.max(t):6.2f} ms per design ({len(t)} designs; "
              f"samples alone median {np.median(plain[name]):5.2f} ms)")
    in_loop(args.repeat)


def in_loop(repeat):
    """One design evaluation of the design loop, with and without the requirement."""
    from dataclasses import asdict

    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.analysis.sampling import Sampling
    from mechopt.requirements import Requirements

    task = Task.rect(100, 60, (0, 180))
    v = {"r1": 163.7, "r2": 183.7, "r3": 1.285, "mode": "+-", "task_x": 0.0, "task_y": 180.0}
    out = {}
    for label, req in (("without", Requirements(min_lci=0.4)),
                       ("with", Requirements(min_lci=0.4, max_error=200.0, error_model=asdict(MODEL)))):
        ev = DesignEvaluator("five-bar", task, req, ("size", "min-lci"))
        ev.evaluate(v, Sampling())
        best = np.inf
        for _ in range(repeat):
            t0 = time.process_time()
            ev.evaluate(v, Sampling())
            best = min(best, time.process_time() - t0)
        out[label] = best * 1e3
    print(f"  five-bar design evaluation (--min-lci 0.4): {out['without']:.2f} ms without, {out['with']:.2f} ms "
          f"with --max-error: the requirement adds {out['with'] - out['without']:.2f} ms")


if __name__ == "__main__":
    main()
