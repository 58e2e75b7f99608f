"""The certificate of one README design: ``mechopt check`` wall time, and its parts.

    python benchmarks/bench_certificate.py [--repeat 5]

Designs the README's rectangle once (``mechopt design five-bar --task
rect:100,60@0,180 --min-lci 0.4``, seed 1, ``--n-jobs 2``; its time is printed but is
not the figure) and then prints, for the chosen design:

* ``mechopt check DESIGN.json`` as a user runs it (a new interpreter: import, read,
  re-certify every requirement with the certification's sampling, compare with
  certificate.json), wall time [s], the median of ``--repeat`` runs;
* :func:`mechopt.workflows.certificate.check` in one process, the first call (cold:
  the task's samples built) and the median of the next ``--repeat`` calls [s];
* the interpreter's own start and ``import mechopt.cli`` [s], which the command pays
  before any check.

Issue target: the certificate of one README design in at most 1 s wall on 2 cores.
The machine is shared: compare figures of one run.
"""
from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

DESIGN = ["five-bar", "--task", "rect:100,60@0,180", "--min-lci", "0.4", "--seed", "1", "--n-jobs", "2"]


def _wall(cmd, cwd) -> float:
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd[1:])} failed ({proc.returncode}): {proc.stdout[-300:]}{proc.stderr[-300:]}")
    return wall


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5, help="runs of each timed step (median printed; default 5)")
    args = ap.parse_args(argv)
    py = sys.executable
    with tempfile.TemporaryDirectory() as d:  # an empty folder: nothing shadows the installation
        out = Path(d) / "run"
        t = _wall([py, "-m", "mechopt.cli", "design", *DESIGN, "--out", str(out)], d)
        print(f"design (not the figure): {t:.1f} s wall")
        design = str(out / "design.json")
        runs = [_wall([py, "-m", "mechopt.cli", "check", design], d) for _ in range(args.repeat)]
        start = [_wall([py, "-c", "pass"], d) for _ in range(args.repeat)]
        imp = [_wall([py, "-c", "import mechopt.cli"], d) for _ in range(args.repeat)]
        from mechopt.workflows.certificate import check

        t0 = time.perf_counter()
        rep = check(design)
        cold = time.perf_counter() - t0
        warm = []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            check(design)
            warm.append(time.perf_counter() - t0)
    print(f"mechopt check DESIGN.json: {statistics.median(runs):.2f} s wall (median of {args.repeat}; "
          f"target <= 1 s); holds: {rep['holds']}, {len(rep['requirements'])} requirements")
    print(f"  of which interpreter start {statistics.median(start):.2f} s, import mechopt.cli "
          f"{statistics.median(imp):.2f} s (with the start)")
    print(f"  check() in process: cold {cold:.3f} s, warm {statistics.median(warm):.3f} s (median)")


if __name__ == "__main__":
    main()
