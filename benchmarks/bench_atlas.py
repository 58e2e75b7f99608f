"""Throughput of the five-bar atlas (issue 6): prints every figure it measures.

    python benchmarks/bench_atlas.py            # all figures (about 1 min)
    python benchmarks/bench_atlas.py --no-full  # skip the full step-0.01 atlas

1. LCI kernel points/s on one core (NumPy and numba), points of a MIC disk.
2. Per-design cost of the fast MIC and of the disk means + MCI, one core.
3. Step-0.02 atlas with 1 and with 2 joblib workers: the speed-up. The first
   2-worker run starts the worker processes (cold); the pool is then reused, as
   a Dask cluster's workers are, so the warm run is the steady-state figure.
4. The full atlas at step 0.01 (about 34 000 designs, six indices) through the
   command-line path on 2 workers: compute time and total wall time including
   atlas.csv and the nine PNGs.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time

import numpy as np


def _best_of(fn, repeat=5):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times), statistics.median(times)


def bench_lci(n_points=2_000_000):
    from mechopt.mechanisms.five_bar import kernels as K
    from mechopt.core.quadrature import disk_rule

    # points of the MIC disk of Liu's example (0.85, 1.6, 0.55): all reachable
    r = int(np.sqrt(n_points / 2))
    dx, dy, _ = disk_rule(0.85, "area", n_r=r, n_theta=2 * r)
    x, y = dx.copy(), 1.5025 + dy
    print(f"LCI kernel, one core, {x.size:.2e} points inside the MIC of (0.85, 1.6, 0.55):")
    paths = [("numpy", False)] + ([("numba", True)] if K.HAVE_NUMBA else [])
    for name, compiled in paths:
        K.lci_points(0.85, 1.6, 0.55, x[:100], y[:100], compiled=compiled)  # compile / warm
        best, med = _best_of(lambda: K.lci_points(0.85, 1.6, 0.55, x, y, compiled=compiled))
        print(f"  {name:6s} {x.size / best:10.3e} points/s (best of 5; median {x.size / med:.3e})")
    if not K.HAVE_NUMBA:
        print("  numba   not installed (pip install 'mechopt[fast]')")


def bench_per_design(n=2000):
    from mechopt.mechanisms.five_bar import kernels as K
    from mechopt.run.atlas import design_grid

    g = design_grid(0.01).sample(n, random_state=0)
    r1, r2, r3 = (g[c].to_numpy() for c in ("r1", "r2", "r3"))
    print(f"Per design, one core ({n} random designs of the space, area rule 48 x 96 nodes x 2 disks):")
    paths = [("numpy", False)] + ([("numba", True)] if K.HAVE_NUMBA else [])
    for name, compiled in paths:
        m = n if compiled else n // 10
        K.mic_batch(r1[:2], r2[:2], r3[:2], compiled=compiled)
        t = time.perf_counter()
        R, yc = K.mic_batch(r1[:m], r2[:m], r3[:m], compiled=compiled)
        t_mic = (time.perf_counter() - t) / m
        ok = R > 1e-9
        t = time.perf_counter()
        K.disk_stats_batch(r1[:m], r2[:m], r3[:m], yc, np.where(ok, R, 0.0), compiled=compiled)
        t_disk = (time.perf_counter() - t) / m
        print(f"  {name:6s} MIC {1e3 * t_mic:.3f} ms, disk means + MCI {1e3 * t_disk:.3f} ms, "
              f"total {1e3 * (t_mic + t_disk):.3f} ms per design")


def bench_scaling(step=0.02):
    from mechopt.run.atlas import compute_atlas, design_grid

    n = len(design_grid(step))
    print(f"Step-{step} atlas ({n} designs, six indices, area rule), joblib workers:")
    compute_atlas(step=0.1, n_jobs=1)  # compile / load the kernels in this process
    t = time.perf_counter()
    a1 = compute_atlas(step=step, n_jobs=1)
    t1 = time.perf_counter() - t
    t = time.perf_counter()
    a2 = compute_atlas(step=step, n_jobs=2)
    t2_cold = time.perf_counter() - t
    t = time.perf_counter()
    a2 = compute_atlas(step=step, n_jobs=2)
    t2 = time.perf_counter() - t
    same = a1.equals(a2)
    print(f"  1 worker            {t1:6.2f} s")
    print(f"  2 workers (cold)    {t2_cold:6.2f} s   speed-up {t1 / t2_cold:.2f}x "
          f"(includes starting the worker processes)")
    print(f"  2 workers (warm)    {t2:6.2f} s   speed-up {t1 / t2:.2f}x")
    print(f"  results identical: {same}")
    return t1 / t2


def bench_full(step=0.01):
    from mechopt.run.atlas import run_atlas

    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        man = run_atlas(os.path.join(tmp, "atlas"), step=step, n_jobs=2, verbose=False,
                        where="r_mic > 0.8 and gci > 0.6")
        wall = time.perf_counter() - t
    s = man["seconds"]
    print(f"Full atlas, step {step}: {man['n_designs']} designs ({man['n_degenerate']} without MIC), "
          f"2 workers, {'numba' if man['compiled'] else 'numpy'}:")
    print(f"  compute {s['compute']:.1f} s, figures {s['figures']:.1f} s, "
          f"total wall {wall:.1f} s (target <= 60 s)")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--no-full", action="store_true", help="skip the full step-0.01 atlas")
    args = p.parse_args(argv)
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} CPUs")
    bench_lci()
    bench_per_design()
    bench_scaling()
    if not args.no_full:
        bench_full()
    return 0


if __name__ == "__main__":
    sys.exit(main())
