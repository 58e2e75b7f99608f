"""Throughput of the five-bar LCI on one core: prints points/s, no asserts on time.

    python benchmarks/bench_lci.py [--n 2000000] [--repeats 5] [--svd-n 20000]

Kernels compared (all at full float64 accuracy, checked against the generic path):

* svd loop      a per-point Python loop: ``FiveBar.jacobian`` of one point, then
                ``numpy.linalg.svd`` (the naive reference), and the same loop over
                precomputed Jacobians (svd only);
* generic       ``indices.lci(FiveBar.jacobian(x, y))``: closure -> J -> closed form;
* fused numpy   ``fast_lci.five_bar_lci_numpy``: one pass, blocks of preallocated buffers;
* fused numba   ``fast_lci.five_bar_lci_numba`` (if numba is importable);
* FiveBar.lci   what the library calls (numba when available, else fused numpy).

The process is pinned to one CPU where the OS allows it (NumPy's elementwise ufuncs
are single-threaded anyway). Each figure is the best of ``--repeats`` runs. Two point
sets: uniform in the bounding box (unreachable points are cheap for numba's early
exit) and reachable points only. Target from the issue: >= 1e7 points/s on one core.
"""
from __future__ import annotations

import argparse
import os
import platform
import sys
import time

import numpy as np

from mechopt.mechanisms.five_bar import lci as fast_lci
from mechopt.core import indices
from mechopt.mechanisms.five_bar.model import FiveBar

TARGET = 1e7


def best_time(fn, repeats):
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2_000_000, help="points per run (>= 1e6)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--svd-n", type=int, default=20_000, help="points for the svd loop")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)

    pinned = "no"
    if hasattr(os, "sched_setaffinity"):
        try:
            cpu = min(os.sched_getaffinity(0))
            os.sched_setaffinity(0, {cpu})
            pinned = f"yes (cpu {cpu})"
        except OSError:
            pass

    mech = FiveBar(0.7, 1.7, 0.6, "+-")  # Liu 2006's example, Liu's working mode
    rng = np.random.default_rng(args.seed)
    xmin, xmax, ymin, ymax = mech.bounding_box()
    n = args.n
    xb, yb = rng.uniform(xmin, xmax, n), rng.uniform(ymin, ymax, n)
    xr, yr = np.empty(0), np.empty(0)
    while xr.size < n:
        x, y = rng.uniform(xmin, xmax, n), rng.uniform(ymin, ymax, n)
        ok = mech.reachable(x, y)
        xr, yr = np.concatenate([xr, x[ok]]), np.concatenate([yr, y[ok]])
    xr, yr = xr[:n], yr[:n]
    frac = float(np.mean(mech.reachable(xb, yb)))

    print(f"mechopt LCI benchmark: {mech!r}")
    print(
        f"python {platform.python_version()}, numpy {np.__version__}, "
        f"numba {'yes' if fast_lci.HAVE_NUMBA else 'no'}, "
        f"machine {platform.machine()}, pinned to one core: {pinned}"
    )
    print(f"{n:,} points per run, best of {args.repeats}; bounding box {frac:.0%} reachable")
    print()

    kern = {
        "generic (closure -> J -> indices.lci)": lambda x, y: indices.lci(mech.jacobian(x, y)),
        "fused numpy (fast_lci.five_bar_lci_numpy)": lambda x, y: fast_lci.five_bar_lci_numpy(
            x, y, mech.r1, mech.r2, mech.r3, 1.0, -1.0
        ),
    }
    if fast_lci.HAVE_NUMBA:
        kern["fused numba (fast_lci.five_bar_lci_numba)"] = lambda x, y: fast_lci.five_bar_lci_numba(
            x, y, mech.r1, mech.r2, mech.r3, 1.0, -1.0
        )
    kern["FiveBar.lci (library dispatch)"] = mech.lci
    for f in kern.values():  # warm-up (numba compile or cache load)
        f(xb[:1000], yb[:1000])

    # per-point svd loops on a small sample
    m = min(args.svd_n, n)
    xs, ys = xr[:m], yr[:m]

    def svd_loop_full():
        out = np.empty(m)
        for i in range(m):
            s = np.linalg.svd(mech.jacobian(xs[i], ys[i]), compute_uv=False)
            out[i] = s[1] / s[0]
        return out

    Js = mech.jacobian(xs, ys)

    def svd_loop_only():
        out = np.empty(m)
        for i in range(m):
            s = np.linalg.svd(Js[i], compute_uv=False)
            out[i] = s[1] / s[0]
        return out

    reps_svd = max(1, min(args.repeats, 3))
    svd_full = m / best_time(svd_loop_full, reps_svd)
    svd_only = m / best_time(svd_loop_only, reps_svd)
    ref_svd = svd_loop_only()

    ref_b = indices.lci(mech.jacobian(xb, yb))
    ref_r = indices.lci(mech.jacobian(xr, yr))
    rows = []
    for name, f in kern.items():
        rate_b = n / best_time(lambda: f(xb, yb), args.repeats)
        rate_r = n / best_time(lambda: f(xr, yr), args.repeats)
        err = max(np.max(np.abs(f(xb, yb) - ref_b)), np.max(np.abs(f(xr, yr) - ref_r)))
        err_svd = np.max(np.abs(f(xs, ys) - ref_svd))
        rows.append((name, rate_b, rate_r, err, err_svd))

    w = max(len(r[0]) for r in rows + [("per-point loop: jacobian + numpy.linalg.svd",)])
    print(f"{'kernel':<{w}}  {'box pts/s':>10}  {'reach pts/s':>11}  {'x svd loop':>10}  "
          f"{'max|d| generic':>14}  {'max|d| svd':>10}")
    print(f"{'per-point loop: jacobian + numpy.linalg.svd':<{w}}  {'':>10}  {svd_full:>11.3g}  "
          f"{1.0:>10.3g}")
    print(f"{'per-point loop: numpy.linalg.svd only':<{w}}  {'':>10}  {svd_only:>11.3g}  "
          f"{svd_only / svd_full:>10.3g}")
    for name, rb, rr, err, err_svd in rows:
        print(f"{name:<{w}}  {rb:>10.3g}  {rr:>11.3g}  {rr / svd_full:>10.3g}  {err:>14.2g}  "
              f"{err_svd:>10.2g}")
    print()
    lib = rows[-1]
    verdict = "met" if min(lib[1], lib[2]) >= TARGET else "NOT met"
    print(f"target {TARGET:.0e} points/s on one core (FiveBar.lci, reachable points): {verdict} "
          f"({lib[2]:.3g} points/s)")
    numpy_row = rows[1]
    print(f"pure NumPy fused path: {numpy_row[2]:.3g} points/s "
          f"({'meets' if numpy_row[2] >= TARGET else 'below'} the target without numba)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
