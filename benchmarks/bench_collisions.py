"""Cost of the capsule checks (mechopt.analysis.collisions) per design evaluation.

    python benchmarks/bench_collisions.py

For one design of each mechanism, on the samples of one design evaluation (192
boundary points + a 13 x 13 interior grid, :class:`mechopt.analysis.sampling.Sampling`),
prints the best of 30 runs, in ms, of

* the bodies (``DesignSpec.links``) and every checked pair's clearance;
* that plus the certified bound (joint speeds over the covering disc, Lipschitz bound);
* the keep-out margin to the task (bodies, margins, bound);
* ``DesignEvaluator.evaluate`` of the same design (reach, singularity, LCI, joint
  ranges and size, with the zoom refinement), without, with ``--min-clearance 0`` (the
  refined minimum and the certified bound) and with ``--keep-out task``.
"""
from __future__ import annotations

import time

import numpy as np

from mechopt.analysis.collisions import Collisions, lipschitz_bound, parse_zone, task_samples
from mechopt.analysis.design_eval import DesignEvaluator
from mechopt.analysis.task import Task
from mechopt.mechanisms import design_spec as get_spec
from mechopt.requirements import Requirements

CASES = [
    ("five-bar", dict(r1=150.0, r2=250.0, r3=60.0), "+-", Task.rect(200, 120, (0, 230))),
    ("asymmetric-five-bar", dict(a1=140.0, c1=230.0, a2=170.0, c2=260.0, r3=50.0), "+-", Task.rect(160, 100, (0, 200))),
    ("biglide", dict(l1=240.0, l2=520.0), "--", Task.rect(400, 300, (0, 400))),
    ("gantry", dict(d1=150.0, l=300.0), "--", Task.rect(260, 120, (0, 300))),
    ("bipod", dict(b=100.0), "up", Task.rect(160, 60, (0, 100))),
]


def best_ms(fn, repeat=30):
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return 1e3 * best


def main():
    print(f"{'mechanism':22s} {'poses':>5s} {'pairs':>5s} {'clearance':>10s} {'+bound':>8s} "
          f"{'keep-out':>9s} {'evaluate':>9s} {'+clearance':>11s} {'+keep-out':>10s}  [ms, best of 30 (10 for evaluate)]")
    for name, v, mode, task in CASES:
        spec = get_spec(name)
        ev = DesignEvaluator(name, task, Requirements(), ("size",), mode=mode, place="fixed", max_length=2000.0)
        full = {**v, "mode": mode, "task_x": task.reference[0], "task_y": task.reference[1]}
        mech = ev.mechanism(full)
        col = Collisions(spec, mech)
        zone = parse_zone("task", task)
        x, y, r = task_samples(task)

        def clearance():
            return col.pair_clearances(x, y).min()

        def bound():
            return lipschitz_bound(col.pair_clearances(x, y), col.clearance_lipschitz(x, y, r), r)

        def keep_out():
            b = col.bodies(x, y)
            return lipschitz_bound(col.keep_out(x, y, zone, b), col.keep_out_lipschitz(x, y, zone, r), r)

        t_ev = best_ms(lambda: ev.evaluate(full), 10)
        ev_c = DesignEvaluator(name, task, Requirements(min_clearance=0.0), ("size",), mode=mode, place="fixed",
                               max_length=2000.0)
        t_evc = best_ms(lambda: ev_c.evaluate(full), 10)
        ev_k = DesignEvaluator(name, task, Requirements(keep_out="task"), ("size",), mode=mode, place="fixed",
                               max_length=2000.0)
        t_evk = best_ms(lambda: ev_k.evaluate(full), 10)
        print(f"{name:22s} {x.size:5d} {len(col.pairs):5d} {best_ms(clearance):10.2f} {best_ms(bound):8.2f} "
              f"{best_ms(keep_out):9.2f} {t_ev:9.2f} {t_evc:11.2f} {t_evk:10.2f}")


if __name__ == "__main__":
    main()
