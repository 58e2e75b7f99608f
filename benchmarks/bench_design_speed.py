"""CPU and wall time of ``mechopt design`` commands, two installations side by side.

    python benchmarks/bench_design_speed.py [--baseline PYTHON] [--cases tutorial,star,...] [--cold]

Runs each case's command with this interpreter (``sys.executable``) and, with
``--baseline``, with another one (for example the virtual environment of a checkout of
the landed code), one after the other in one run, so that both see the same machine
load; prints one line per case and installation: wall time [s], CPU time [s] (user +
system of the command and every process it started, from ``resource.getrusage``), the
stages the command reports (optimisation, polish, certification, files) and the
smallest size on the front, then the CPU ratio baseline / this and whether the two
front.csv files are byte-identical. With ``--cold`` each case first runs with an empty
numba cache (the compiled twins of :class:`mechopt.core.jit.Twin` compile in every
process that uses them), then warm from it: the cold compile's extra CPU and wall
time. The machine is shared
and noisy: compare the ratios of one run, not figures across runs.

Cases (the issue's: the tutorial's command, a star polygon with free-y placement, the
same with ``--place free``, a gantry with speed and force; and the gantry with speed and
force as requirements of a size search):
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

STAR = "polygon:0,200;12,166;47,166;19,145;29,111;0,131;-29,111;-19,145;-47,166;-12,166"
CASES = {
    "tutorial": ["five-bar", "--task", "rect:100,60@0,180", "--min-lci", "0.4", "--joint-limits=-60,240",
                 "--max-length", "250", "--objectives", "size,min-lci", "--seed", "1"],
    "star-free-y": ["five-bar", "--task", STAR, "--min-lci", "0.3", "--place", "free-y", "--objectives", "size",
                    "--max-length", "300", "--seed", "1"],
    "star-free": ["five-bar", "--task", STAR, "--min-lci", "0.3", "--place", "free", "--objectives", "size",
                  "--max-length", "300", "--seed", "1"],
    "gantry-speed-force": ["gantry", "--task", "rect:500,400@0,500", "--actuator-speed", "500",
                           "--actuator-torque", "500", "--objectives", "size,speed,force", "--seed", "1"],
    # speed and force as requirements, the size the objective (the settled requirements' case)
    "gantry-speed-force-req": ["gantry", "--task", "rect:500,400@0,500", "--actuator-speed", "500",
                               "--actuator-torque", "500", "--min-speed", "300", "--min-force", "200",
                               "--objectives", "size", "--seed", "1"],
}
__doc__ += "".join(f"\n* ``{k}``: ``mechopt design {' '.join(v)}``" for k, v in CASES.items()) + "\n"


def run(python: str, args: list, n_jobs: int, numba_cache: str | None = None) -> dict:
    """One command's wall and CPU time [s], its stages and smallest size; with
    ``numba_cache``, numba's cache in that folder (an empty one: a cold compile)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=numba_cache) if numba_cache else None
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "run"
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        # run in the empty folder: ``-m`` puts the working directory first on sys.path, and
        # a checkout's mechopt/ there would shadow the installation being measured
        proc = subprocess.run([python, "-m", "mechopt.cli", "design", *args, "--n-jobs", str(n_jobs),
                               "--out", str(out)], capture_output=True, text=True, cwd=d, env=env)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if proc.returncode != 0:
            raise SystemExit(f"{python}: {' '.join(args)} failed: {proc.stderr.strip().splitlines()[-1:]}")
        info = json.loads((out / "run.json").read_text())
        import pandas as pd

        size = float(pd.read_csv(out / "front.csv")["size"].min()) if (out / "front.csv").exists() else None
        front = (out / "front.csv").read_bytes() if (out / "front.csv").exists() else b""
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"wall_s": wall, "cpu_s": cpu, "stages_s": info.get("stage_times_s", {}), "smallest_size": size,
            "front": front}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", help="another installation's python (e.g. a checkout of the landed code)")
    ap.add_argument("--cases", default=",".join(CASES), help=f"comma-separated, of {', '.join(CASES)}")
    ap.add_argument("--n-jobs", type=int, default=2, help="--n-jobs of every command (default 2)")
    ap.add_argument("--cold", action="store_true",
                    help="first run each case with this installation and an empty numba cache (its compiled twins "
                         "compile), then warm from that cache; prints both")
    args = ap.parse_args(argv)
    names = [c.strip() for c in args.cases.split(",") if c.strip()]
    for c in names:
        if c not in CASES:
            ap.error(f"unknown case {c!r}; known: {', '.join(CASES)}")
    pythons = [("this", sys.executable)] + ([("baseline", args.baseline)] if args.baseline else [])
    cache = tempfile.TemporaryDirectory() if args.cold else None
    for c in names:
        res = {}
        runs = ([("cold", sys.executable)] if args.cold else []) + pythons
        for label, py in runs:
            if cache is not None and label == "cold":  # empty the cache: every kernel compiles
                for f in Path(cache.name).iterdir():
                    shutil.rmtree(f) if f.is_dir() else f.unlink()
            r = res[label] = run(py, CASES[c], args.n_jobs, cache.name if cache is not None else None)
            stages = ", ".join(f"{k} {v:.1f}" for k, v in r["stages_s"].items())
            print(f"{c:20s} {label:8s} wall {r['wall_s']:7.1f} s  CPU {r['cpu_s']:7.1f} s  ({stages})  "
                  f"smallest size {r['smallest_size']:.2f}", flush=True)
        if "cold" in res:
            print(f"{c:20s} cold numba cache: +{res['cold']['cpu_s'] - res['this']['cpu_s']:.1f} s CPU, "
                  f"+{res['cold']['wall_s'] - res['this']['wall_s']:.1f} s wall", flush=True)
        if "baseline" in res:
            same = res["baseline"]["front"] == res["this"]["front"]
            print(f"{c:20s} CPU baseline / this = {res['baseline']['cpu_s'] / res['this']['cpu_s']:.2f}, "
                  f"wall {res['baseline']['wall_s'] / res['this']['wall_s']:.2f}; front.csv "
                  f"{'byte-identical' if same else 'DIFFERS'}", flush=True)


if __name__ == "__main__":
    main()
