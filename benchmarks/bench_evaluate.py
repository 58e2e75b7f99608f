"""Start-up to answer: ``mechopt evaluate <mechanism> ... --json`` in fresh processes.

    python benchmarks/bench_evaluate.py [--repeats 5] [--only five-bar] [--pythonpath DIR]
                                        [--check-json FILE]

Each command runs ``--repeats`` times in a new Python process (what a user typing it
pays: interpreter start-up, imports, the evaluation, printing). Per command it prints
the median and the best wall time, the median CPU time (user + system: less sensitive
to other work on a shared machine than the wall time) and the largest peak resident
memory of its runs (``ru_maxrss`` of each child, from ``os.wait4``). Targets from the
issue for the five-bar: under 1 s wall and under 200 MB.

Commands: the five-bar of the issue (``--r1 0.85 --r2 1.6 --r3 0.55``) and every other
mechanism with the README's example (the gantry with its defaults). One more row,
``five-bar (API)``, times ``mechopt.analysis.evaluate.evaluate`` called from a fresh process
without the command line (so the cost of building the CLI's parser shows apart).

``--pythonpath DIR`` runs the children with ``DIR`` first on ``PYTHONPATH`` (e.g. an
export of another revision of the package, to compare before and after); with
``--check-json FILE`` the five-bar's JSON output must equal the bytes in ``FILE``.
No assertion on time: the figures depend on the machine and its load.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

TARGET_WALL = 1.0  # s, five-bar
TARGET_RSS = 200.0  # MB, five-bar

CLI = "import sys; from mechopt.cli import main; sys.exit(main())"
API = ("from mechopt.analysis.evaluate import evaluate; from mechopt.mechanisms.five_bar.model import FiveBar; "
       "print(evaluate(FiveBar(0.85, 1.6, 0.55)).as_dict())")

COMMANDS = [
    ("five-bar", ["five-bar", "--r1", "0.85", "--r2", "1.6", "--r3", "0.55"]),
    ("asymmetric-five-bar", ["asymmetric-five-bar", "--a1", "1", "--c1", "1.5", "--a2", "0.8",
                             "--c2", "1.7", "--r3", "0.5"]),
    ("biglide", ["biglide", "--l1", "1", "--l2", "1.1", "--q1-min", "0", "--q1-max", "1"]),
    ("bipod", ["bipod", "--b", "60", "--q1-min", "80", "--q1-max", "130"]),
    ("gantry", ["gantry"]),
]


def run_once(argv, env, cwd):
    """``(wall s, cpu s, max RSS MB, stdout bytes)`` of one fresh child process."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, cwd=cwd)
    out = proc.stdout.read()
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    proc.stdout.close()
    proc.stderr.close()
    if proc.returncode != 0:
        raise SystemExit(f"{argv!r} failed ({proc.returncode}): {err.decode(errors='replace')[-500:]}")
    rss_mb = usage.ru_maxrss / 1024.0 if sys.platform != "darwin" else usage.ru_maxrss / 2**20
    return wall, usage.ru_utime + usage.ru_stime, rss_mb, out


def _row(name, child, env, cwd, repeats):
    """Run one command ``repeats`` times; print and return its figures and output."""
    runs = [run_once(child, env, cwd) for _ in range(repeats)]
    wall = statistics.median(r[0] for r in runs)
    best = min(r[0] for r in runs)
    cpu = statistics.median(r[1] for r in runs)
    rss = max(r[2] for r in runs)
    outs = {r[3] for r in runs}
    if len(outs) != 1:
        raise SystemExit(f"{name}: the output differs between runs")
    print(f"{name:<22} {wall:>10.3f} s {best:>8.3f} s {cpu:>9.3f} s {rss:>6.0f} MB", flush=True)
    return wall, best, cpu, rss, outs.pop()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--only", default=None, help="one row (e.g. five-bar)")
    ap.add_argument("--pythonpath", default=None, help="prepended to the children's PYTHONPATH")
    ap.add_argument("--check-json", default=None, help="expected bytes of the five-bar's JSON output")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be >= 1")
    env = dict(os.environ)
    if args.pythonpath:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (args.pythonpath, env.get("PYTHONPATH")) if p)
    rows = [(name, [sys.executable, "-c", CLI, "evaluate", *cmd, "--json"]) for name, cmd in COMMANDS]
    rows.insert(1, ("five-bar (API)", [sys.executable, "-c", API]))
    if args.only:
        rows = [r for r in rows if r[0] == args.only]
        if not rows:
            ap.error(f"--only must be one of {', '.join(n for n, _ in COMMANDS)} or 'five-bar (API)'")

    print(f"python {sys.version.split()[0]} on {os.cpu_count()} CPUs, {args.repeats} fresh processes "
          f"per row{', PYTHONPATH=' + args.pythonpath if args.pythonpath else ''}")
    print(f"{'command':<22} {'median wall':>12} {'best wall':>10} {'median cpu':>11} {'max RSS':>9}")
    results = {}
    # an empty working folder: ``python -c`` puts it first on sys.path, so the package
    # comes from --pythonpath or the installation, not from where this is started
    with tempfile.TemporaryDirectory(prefix="bench_evaluate_") as cwd:
        for name, child in rows:
            results[name] = _row(name, child, env, cwd, args.repeats)
    if "five-bar" in results:
        wall, best, cpu, rss, out = results["five-bar"]
        ok = wall < TARGET_WALL and rss < TARGET_RSS
        print(f"five-bar target (< {TARGET_WALL:g} s wall, < {TARGET_RSS:g} MB): "
              f"{'met' if ok else 'not met'} (median {wall:.3f} s, {rss:.0f} MB)")
        if args.check_json:
            with open(args.check_json, "rb") as fh:
                expected = fh.read()
            same = out == expected
            print(f"five-bar JSON {'equals' if same else 'DIFFERS FROM'} {args.check_json}")
            if not same:
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
