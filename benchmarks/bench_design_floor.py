"""Where a ``mechopt design`` command's CPU time goes, and the least it could cost with
its evaluations unchanged.

    python benchmarks/bench_design_floor.py [--cases tutorial,star-free-y,...] [--baseline PYTHON]

Runs each case of :mod:`bench_design_speed` (the same commands) in this process with
``--n-jobs 1``, once to warm numba's cache and once measured, counting every design
evaluation (:meth:`mechopt.analysis.design_eval.DesignEvaluator.evaluate`) by stage and
sampling, the time spent in evaluations and, inside them, in the compiled loops
(:class:`mechopt.core.jit.Twin`). Stages: ``search`` (the genetic searches, those of
the other working modes and placements included), ``polish``, ``certification``,
``certificate`` (its proven bounds), ``other`` (set-up, the CSV, JSON and PNG
files) and ``start-up`` (a separate process importing what the command imports and loading
numba). Prints, per case, each stage's CPU seconds, its evaluations and their seconds,
then two floors of the command's CPU time with the same evaluations:

* ``compiled only``: every evaluation costs only its compiled loops (no Python around
  them);
* ``free evaluations``: evaluations cost nothing (what is left: start-up, pymoo and
  SciPy's own work, certificate bounds, files).

With ``--baseline`` (another installation's Python, e.g. a checkout of the landed code
of an issue's day) the baseline command's CPU time is measured too
(:func:`bench_design_speed.run`) and the largest ratio each floor would allow printed.
The evaluations and their order are what fix a run's numbers (its fronts are compared
byte for byte), so a floor is the most a byte-identical speed-up can reach.
"""
from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_design_speed import CASES, run  # noqa: E402

#: what a design command imports before it evaluates (start-up)
IMPORTS = ("import mechopt.cli.design, mechopt.workflows.design, mechopt.workflows.certificate, "
           "mechopt.run.plotting, mechopt.problems.design, pymoo.algorithms.moo.nsga2, scipy.optimize, pandas; "
           "from mechopt.core import jit; jit.load_numba()")


def cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def startup_cpu() -> float:
    """CPU seconds of a process that imports what the command imports."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", IMPORTS], check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


class Meter:
    """Counts evaluations and times stages, evaluations and compiled loops (CPU s)."""

    def __init__(self):
        self.reset()
        self.install()

    def reset(self):
        self.stage = ["other"]
        self.stage_cpu = Counter()
        self.evals = Counter()
        self.eval_cpu = Counter()
        self.compiled_cpu = Counter()
        self.depth = 0

    def install(self):
        import mechopt.run.runner as runner
        import mechopt.workflows.design as wd
        from mechopt.analysis.design_eval import DesignEvaluator
        from mechopt.core.jit import Twin

        meter = self

        def staged(name, fn):
            def wrapper(*a, **k):
                meter.stage.append(name)
                t0 = cpu()
                try:
                    return fn(*a, **k)
                finally:
                    dt = cpu() - t0
                    meter.stage.pop()
                    meter.stage_cpu[name] += dt
                    if meter.stage[-1] not in (name, "other"):  # nested in another stage: not counted twice
                        meter.stage_cpu[meter.stage[-1]] -= dt
            return wrapper

        for module, attr, name in ((runner, "optimize", "search"), (wd, "_polish_front", "polish"),
                                   (wd, "certify", "certification"), (wd, "_certificate", "certificate")):
            setattr(module, attr, staged(name, getattr(module, attr)))

        evaluate = DesignEvaluator.evaluate

        def counted(ev, v, sampling=None):
            kind = "search" if sampling is None or sampling.n_interior < 61 else "fine"
            kind += " (settled)" if sampling is not None and sampling.settle else ""
            key = (meter.stage[-1], kind)
            meter.evals[key] += 1
            meter.depth += 1
            t0 = cpu()
            try:
                return evaluate(ev, v, sampling)
            finally:
                meter.eval_cpu[key] += cpu() - t0
                meter.depth -= 1

        DesignEvaluator.evaluate = counted
        call = Twin.__call__

        def timed(twin, *args):
            t0 = cpu()
            try:
                return call(twin, *args)
            finally:
                meter.compiled_cpu[(meter.stage[-1], meter.depth > 0)] += cpu() - t0

        Twin.__call__ = timed


def measure(case: str, meter: Meter) -> dict:
    """One in-process run of ``case`` after a warming run: the meter's counts and the
    total CPU [s]."""
    from mechopt.cli import main

    with tempfile.TemporaryDirectory() as d:
        args = ["design", *CASES[case], "--n-jobs", "1", "--quiet"]
        main([*args, "--out", str(Path(d) / "warm")])
        meter.reset()
        t0 = cpu()
        main([*args, "--out", str(Path(d) / "run")])
        total = cpu() - t0
    return {"meter": meter, "total": total}


def report(case: str, m: dict, start: float, baseline: float | None):
    meter, total = m["meter"], m["total"]
    stages = dict(meter.stage_cpu)
    print(f"{case}: CPU {total + start:.2f} s (start-up {start:.2f}, the command {total:.2f})")
    evals_by_stage = defaultdict(list)
    for (stage, kind), n in sorted(meter.evals.items()):
        evals_by_stage[stage].append((kind, n, meter.eval_cpu[(stage, kind)]))
    eval_total = sum(meter.eval_cpu.values())
    compiled_in = sum(v for (s, inside), v in meter.compiled_cpu.items() if inside)
    for stage in ("search", "polish", "certification", "certificate"):
        parts = "; ".join(f"{n} {kind} evaluations {t:.2f} s ({1e3 * t / n:.2f} ms each)"
                          for kind, n, t in evals_by_stage.get(stage, []))
        print(f"  {stage:14s} {stages.get(stage, 0.0):6.2f} s  {parts}")
    print(f"  {'other':14s} {total - sum(stages.values()):6.2f} s  (set-up, the front's table and files but the "
          f"certificate's)")
    print(f"  evaluations: {sum(meter.evals.values())}, {eval_total:.2f} s, of which compiled loops "
          f"{compiled_in:.2f} s; compiled loops outside evaluations (bounds) "
          f"{sum(v for (s, inside), v in meter.compiled_cpu.items() if not inside):.2f} s")
    floors = {"compiled only": total + start - eval_total + compiled_in,
              "free evaluations": total + start - eval_total}
    for name, f in floors.items():
        ratio = f"; baseline {baseline:.2f} s / floor = {baseline / f:.2f}x at most" if baseline else ""
        print(f"  floor, {name:17s} {f:6.2f} s{ratio}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default="tutorial,star-free-y,star-free", help=f"comma-separated, of {', '.join(CASES)}")
    ap.add_argument("--baseline", help="another installation's python: its command's CPU time (--n-jobs 1)")
    args = ap.parse_args(argv)
    names = [c.strip() for c in args.cases.split(",") if c.strip()]
    for c in names:
        if c not in CASES:
            ap.error(f"unknown case {c!r}; known: {', '.join(CASES)}")
    start = startup_cpu()
    meter = Meter()
    for c in names:
        baseline = run(args.baseline, CASES[c], 1)["cpu_s"] if args.baseline else None
        t0 = time.perf_counter()
        m = measure(c, meter)
        report(c, m, start, baseline)
        print(f"  (measured in {time.perf_counter() - t0:.0f} s)", flush=True)


if __name__ == "__main__":
    main()
