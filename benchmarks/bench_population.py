"""2-core speed-up of evaluating a population of five-bar designs (MIC + GCI).

Prints wall times for 1 and 2 joblib workers on the same 100 designs of Liu's
design space (``r1 + r2 + r3 = 3``), mapped through the package's single
parallel map exactly as a Problem does it (one chunk per worker), and their
ratio, for two evaluators:

* ``reference``: :func:`mechopt.analysis.workspace.mic` by ray root finding plus
  :func:`mechopt.analysis.performance.global_indices` (about 0.2 s per design);
* ``fast``: the vectorised explicit-locus path the problems use
  (:func:`mechopt.problems.liu2006.liu_indices`, about 1 ms per design), where a
  population of 100 is too small for processes to pay off.

Target (issue "problems/runner"): at least 1.7x. Run it on an otherwise idle
machine; the timings of one evaluator are taken in the same run.

    python benchmarks/bench_population.py [--designs 100] [--repeats 2]
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from mechopt.run.parallel import chunks, parallel_map
from mechopt.problems import get


def _designs(n, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        r1, r3 = rng.uniform(0.3, 1.8), rng.uniform(0.0, 1.0)
        if 3.0 - r1 - r3 > 0.3:
            out.append((r1, r3))
    return np.array(out)


def _reference(X):
    from mechopt import FiveBar
    from mechopt.analysis.performance import global_indices
    from mechopt.analysis.workspace import mic

    out = []
    for r1, r3 in X:
        fb = FiveBar(r1, 3.0 - r1 - r3, r3)
        out.append(global_indices(fb, "polar", mic=mic(fb, method="rays"))["gci"])
    return np.array(out)


def _fast(X):
    return get("liu2006-w-gci").evaluate_designs(X)["extra"]["gci"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", type=int, default=100)
    ap.add_argument("--repeats", type=int, default=2)
    args = ap.parse_args()
    X = _designs(args.designs)
    for name, func in (("reference", _reference), ("fast", _fast)):
        parallel_map(func, chunks(X[:4], 2), n_jobs=2)  # start the workers once
        times = {}
        for n_jobs in (1, 2):
            best = np.inf
            for _ in range(args.repeats):
                t0 = time.perf_counter()
                res = parallel_map(func, chunks(X, n_jobs), n_jobs=n_jobs)
                best = min(best, time.perf_counter() - t0)
            times[n_jobs] = best
            gci = np.concatenate(res)
            print(f"{name}: n_jobs={n_jobs}: {best:.3f} s for {len(X)} designs "
                  f"({len(X) / best:.1f} designs/s), mean GCI {np.nanmean(gci):.4f}")
        print(f"{name}: speed-up 2 vs 1 worker: {times[1] / times[2]:.2f}x (target >= 1.7x)")


if __name__ == "__main__":
    main()
