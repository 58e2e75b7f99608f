"""Proven lower bounds of the requirement minima (mechopt.analysis.bounds): seconds, cells
and gap per front design and quantity.

    python benchmarks/bench_bounds.py [--task rect:100,60@0,180] [--min-lci 0.4] [--pop 24 --gen 20]
        [--mechanism five-bar] [--joint-limits -60,240] [--max-stroke 300]

Runs ``mechopt design MECHANISM`` (no files) with LCI, speed and force requirements
(actuators 3 rad/s and 2 N m each; a five-bar's), the joint limits (mechanisms with
cranks) or the longest stroke (sliders, struts), then, for every front design, bounds each
minimum the certificate records (:func:`mechopt.workflows.certificate.proven_bounds`, one
design at a time, its quantities in lock-step; joints and stroke: the proven outer ranges
of both actuator coordinates, four searches) and prints per design its seconds and per
quantity the cells evaluated, the smallest cell, the proven bound, the sampled-and-zoomed
estimate and their gap; then the time of all front designs in lock-step (as the
certificate computes them). Figures are printed, never asserted.

    python benchmarks/bench_bounds.py --tutorial [--before PYTHON]

The CPU of the bounds of the tutorial's front designs (``mechopt design five-bar --task
rect:100,60@0,180 --min-lci 0.4 --joint-limits=-60,240 --max-length 250 --objectives
size,min-lci --seed 1``): runs the command (output in a temporary folder), times the
certificate's bounds of its front designs as the certificate computes them, and, with
``--before`` (the Python of another checkout of mechopt, e.g. a virtual environment of an
earlier commit), the same designs' bounds by that checkout's code in a subprocess, one
design at a time as it computes them; prints both CPU times and whether every bound is
the same bit for bit.
"""
from __future__ import annotations

import argparse
import time

from mechopt.analysis.task import parse_task
from mechopt.requirements import Requirements
from mechopt.workflows.certificate import _variables, proven_bounds
from mechopt.workflows.design import design


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--task", default="rect:100,60@0,180", help="the task (mechopt design's syntax)")
    ap.add_argument("--min-lci", type=float, default=0.4, help="LCI required over the task")
    ap.add_argument("--pop", type=int, default=24, help="population of the search")
    ap.add_argument("--gen", type=int, default=20, help="generations of the search")
    ap.add_argument("--mechanism", default="five-bar", help="the mechanism (mechopt design's names)")
    ap.add_argument("--joint-limits", default="-60,240", help="crank limits LO,HI [deg] (mechanisms with cranks)")
    ap.add_argument("--max-stroke", type=float, default=300.0, help="longest stroke [task unit] (sliders)")
    ap.add_argument("--tutorial", action="store_true", help="time the tutorial's front designs' bounds only")
    ap.add_argument("--before", help="with --tutorial: the Python of a checkout to compare with")
    ap.add_argument("--time-items", help=argparse.SUPPRESS)  # the subprocess of --before
    args = ap.parse_args(argv)
    if args.time_items:
        return _time_items(args.time_items)
    if args.tutorial:
        return _tutorial(args.before)
    from mechopt.analysis.design_eval import get_spec
    from mechopt.requirements.joints import _parse

    if get_spec(args.mechanism).angular:
        req = Requirements(min_lci=args.min_lci, min_speed=50.0, actuator_speed=3.0, min_force=1.0,
                           actuator_torque=2.0, joint_limits=_parse(args.joint_limits))
    else:
        req = Requirements(min_lci=args.min_lci, max_stroke=args.max_stroke)
    t0 = time.perf_counter()
    res = design(args.mechanism, parse_task(args.task), req, ("size", "min-lci"), pop=args.pop, gen=args.gen,
                 plot=False)
    print(f"design: {time.perf_counter() - t0:.1f} s, {len(res.front)} front designs, task {args.task}")
    ev = res.evaluator
    # a design's quantities run in lock-step (mechopt.analysis.bounds.lower_bounds): one time per design
    print(f"{'design':>6} {'quantity':>9} {'seconds':>8} {'cells':>6} {'smallest':>9} {'bound':>12} "
          f"{'estimate':>12} {'gap':>10} {'rel gap':>8}")
    totals, recs = [], [res.design_at(i) for i in range(len(res.front))]
    for i, rec in enumerate(recs):
        v = _variables(rec, ev.spec, None)
        t_all = time.perf_counter()
        b_all = proven_bounds(ev, v, rec["margins"])
        totals.append(time.perf_counter() - t_all)
        for name, b in b_all.items():
            rel = b["gap"] / max(abs(b["estimate"]), 1.0 if name in ("lci", "singular", "joints") else 1e-300)
            print(f"{i:>6} {b['quantity'][:9]:>9} {'':>8} {b['cells']:>6} {b['smallest_cell']:>9.3g} "
                  f"{b['lower_bound']:>12.6g} {b['estimate']:>12.6g} {b['gap']:>10.3g} {rel:>8.2%}")
        print(f"{i:>6} {'all':>9} {totals[-1]:>8.3f}")
    print(f"certificate bounds per design, one at a time: mean {sum(totals) / len(totals):.3f} s, "
          f"max {max(totals):.3f} s")
    from mechopt.workflows.certificate import proven_bounds_of_designs

    t_all = time.perf_counter()
    proven_bounds_of_designs(ev, [_variables(rec, ev.spec, None) for rec in recs], [rec["margins"] for rec in recs])
    print(f"all front designs in lock-step (as the certificate): {time.perf_counter() - t_all:.3f} s")


TUTORIAL = ["design", "five-bar", "--task", "rect:100,60@0,180", "--min-lci", "0.4", "--joint-limits=-60,240",
            "--max-length", "250", "--objectives", "size,min-lci", "--seed", "1", "--n-jobs", "1", "--quiet"]


def _bounds(items):
    """The certificate's bounds of the front ``items`` (``(ev, rec)``) as this checkout
    computes them (in lock-step where it can), and the CPU seconds."""
    from mechopt.workflows import certificate as c

    t = time.process_time()
    if hasattr(c, "proven_bounds_of_designs"):
        out = c._bounds_of((items[0][0], [rec for _, rec in items]))
    else:  # one design at a time
        out = [c._bounds_of(item) for item in items]
    return out, time.process_time() - t


def _time_items(path):
    """The subprocess of ``--before``: the bounds of the pickled items, as JSON on stdout."""
    import json
    import pickle

    with open(path, "rb") as f:
        out, sec = _bounds(pickle.load(f))
    print(json.dumps({"seconds": sec, "bounds": repr(out)}))


def _tutorial(before):
    """``--tutorial``: the tutorial's front designs' bound CPU, here and ``before``."""
    import json
    import os
    import pickle
    import subprocess
    import sys
    import tempfile

    import mechopt.run.parallel as par
    from mechopt.cli import main as cli

    items, plain = [], par.parallel_map

    def capture(func, work, *a, **k):  # the certificate's work units: (ev, design records)
        if func.__name__ == "_bounds_of":
            for ev, recs in work:
                items.extend((ev, rec) for rec in (recs if isinstance(recs, list) else [recs]))
        return plain(func, work, *a, **k)
    par.parallel_map = capture
    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        cli(TUTORIAL + ["--out", os.path.join(tmp, "out")])
        print(f"tutorial design: {time.perf_counter() - t:.1f} s, {len(items)} front designs")
        par.parallel_map = plain
        after, sec = _bounds(items)
        print(f"bounds CPU, this checkout: {sec:.2f} s ({1e3 * sec / len(items):.0f} ms per design)")
        if before:
            path = os.path.join(tmp, "items.pkl")
            with open(path, "wb") as f:
                pickle.dump(items, f)
            res = subprocess.run([before, os.path.abspath(__file__), "--time-items", path], capture_output=True,
                                 text=True, check=True, env={**os.environ, "PYTHONPATH": ""})
            old = json.loads(res.stdout.strip().splitlines()[-1])
            print(f"bounds CPU, before:        {old['seconds']:.2f} s ({1e3 * old['seconds'] / len(items):.0f} ms "
                  f"per design): {old['seconds'] / sec:.2f} x")
            print(f"every bound the same bit for bit: {'yes' if old['bounds'] == repr(after) else 'NO'}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
