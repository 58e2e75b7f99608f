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
import json
import resource
import subprocess
import sys
import tempfile
import time
from collections import Counter
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
    """Counts evaluations and times stages, evaluations and compiled loops (CPU s) while
    it is entered (``with Meter() as meter:``): it wraps the stages' functions,
    :meth:`DesignEvaluator.evaluate <mechopt.analysis.design_eval.DesignEvaluator.evaluate>`
    and :meth:`Twin.__call__ <mechopt.core.jit.Twin.__call__>`, and puts them back on exit."""

    def __init__(self):
        self.stage = ["other"]
        self.stage_cpu = Counter()
        self.evals = Counter()
        self.eval_cpu = Counter()
        self.compiled_cpu = Counter()
        self.depth = 0
        self._saved = []

    def __enter__(self):
        import mechopt.run.runner as runner
        import mechopt.workflows.design as wd
        from mechopt.analysis.design_eval import DesignEvaluator
        from mechopt.analysis.sampling import Sampling
        from mechopt.core.jit import Twin

        fine = Sampling.fine()
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

        def counted(evaluate):
            def wrapper(ev, v, sampling=None):
                fine_counts = sampling is not None and (sampling.n_boundary, sampling.n_interior) == (
                    fine.n_boundary, fine.n_interior)
                kind = ("fine" if fine_counts else "search") + (" (settled)" if sampling and sampling.settle else "")
                key = (meter.stage[-1], kind)
                meter.evals[key] += 1
                meter.depth += 1
                t0 = cpu()
                try:
                    return evaluate(ev, v, sampling)
                finally:
                    meter.eval_cpu[key] += cpu() - t0
                    meter.depth -= 1
            return wrapper

        def timed(call):
            def wrapper(twin, *args):
                t0 = cpu()
                try:
                    return call(twin, *args)
                finally:
                    meter.compiled_cpu[(meter.stage[-1], meter.depth > 0)] += cpu() - t0
            return wrapper

        for owner, attr, wrap in ((runner, "optimize", lambda f: staged("search", f)),
                                  (wd, "_polish_front", lambda f: staged("polish", f)),
                                  (wd, "certify", lambda f: staged("certification", f)),
                                  (wd, "_certificate", lambda f: staged("certificate", f)),
                                  (DesignEvaluator, "evaluate", counted), (Twin, "__call__", timed)):
            original = getattr(owner, attr)
            self._saved.append((owner, attr, original))
            setattr(owner, attr, wrap(original))
        return self

    def __exit__(self, *exc):
        for owner, attr, original in reversed(self._saved):
            setattr(owner, attr, original)
        self._saved.clear()


def measure(case: str, extra=(), warm=True) -> dict:
    """One in-process run of ``case`` (with the further options ``extra``), after a
    warming run with ``warm``: its :class:`Meter`, total CPU time [s] and the search's
    evaluations as run.json reports them."""
    from mechopt.cli import main

    with tempfile.TemporaryDirectory() as d:
        args = ["design", *CASES[case], *extra, "--n-jobs", "1", "--quiet"]
        if warm:
            main([*args, "--out", str(Path(d) / "warm")])
        with Meter() as meter:
            t0 = cpu()
            main([*args, "--out", str(Path(d) / "run")])
            total = cpu() - t0
        reported = json.loads((Path(d) / "run" / "run.json").read_text())["evaluations"]
    return {"meter": meter, "total": total, "search_evaluations": reported}


def summarise(m: dict, start: float) -> dict:
    """The figures of a :func:`measure` run with ``start`` [s] of start-up: total CPU,
    CPU per stage, ``(count, CPU)`` per stage and kind of evaluation, the evaluations'
    CPU and the compiled loops' inside and outside them, and the two floors [s]."""
    meter, total = m["meter"], m["total"]
    stages = dict(meter.stage_cpu)
    stages["other"] = total - sum(v for k, v in stages.items() if k != "other")
    evals = {k: (n, meter.eval_cpu[k]) for k, n in sorted(meter.evals.items())}
    eval_cpu = sum(meter.eval_cpu.values())
    inside = sum(v for (_, within), v in meter.compiled_cpu.items() if within)
    return {"total": total + start, "start": start, "stages": stages, "evals": evals, "eval_cpu": eval_cpu,
            "compiled_in_evaluations": inside,
            "compiled_elsewhere": sum(v for (_, within), v in meter.compiled_cpu.items() if not within),
            "floors": {"compiled only": total + start - eval_cpu + inside, "free evaluations": total + start - eval_cpu}}


def report(case: str, s: dict, baseline: float | None):
    print(f"{case}: CPU {s['total']:.2f} s (start-up {s['start']:.2f})")
    for stage in ("search", "polish", "certification", "certificate", "other"):
        parts = "; ".join(f"{n} {kind} evaluations {t:.2f} s ({1e3 * t / n:.2f} ms each)"
                          for (st, kind), (n, t) in s["evals"].items() if st == stage)
        print(f"  {stage:14s} {s['stages'].get(stage, 0.0):6.2f} s  {parts}")
    print(f"  evaluations: {sum(n for n, _ in s['evals'].values())}, {s['eval_cpu']:.2f} s, of which compiled "
          f"loops {s['compiled_in_evaluations']:.2f} s; compiled loops outside evaluations (bounds) "
          f"{s['compiled_elsewhere']:.2f} s")
    for name, f in s["floors"].items():
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
    for c in names:
        baseline = run(args.baseline, CASES[c], 1)["cpu_s"] if args.baseline else None
        t0 = time.perf_counter()
        m = measure(c)
        report(c, summarise(m, start), baseline)
        print(f"  (measured in {time.perf_counter() - t0:.0f} s)", flush=True)


if __name__ == "__main__":
    main()
