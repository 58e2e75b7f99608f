"""Where users wait: the reproduction, one evaluation, the full atlas, the test suite.

    python benchmarks/bench_pipeline.py [--only stages,reproduce,reproduce-quick,...]
                                        [--repeats 3] [--work DIR] [--json FILE]
                                        [--pytest-args "-n 2"] [--keep]

Every command runs in a fresh Python process started by a small launcher, which
reports the command's wall time, its CPU time (user + system, children included:
less sensitive to other work on a shared machine than the wall time) and its peak
resident memory (``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` of the launcher
after its one command: the largest process of the command's tree that was waited
for). Targets (issue "speed where users wait", 2 cores) are printed beside them.

Rows (``--only`` takes a comma-separated subset, default all):

``stages``           ``reproduce <paper>`` (full) for each paper alone in a fresh process,
                     split into stages by timing the calls of each kind (a call's time
                     less that of the timed calls inside it):
                     ``optimisation`` (``runner.optimize``/``runner.sweep`` and the
                     experiments' parallel optimisation jobs), ``atlas``
                     (``atlas.compute_atlas``), ``figures`` (the experiments' figure
                     builders, ``atlas.draw_atlas`` and ``io.save_figure``) and
                     ``tables`` (everything else: the curves, scans, comparisons and
                     the files of the table)
``stages-quick``     the same for ``--quick``
``reproduce``        ``mechopt reproduce all`` (full) as a user runs it, with its
                     per-paper times from its log
``reproduce-quick``  ``mechopt reproduce all --quick``
``evaluate``         ``mechopt evaluate five-bar --r1 0.85 --r2 1.6 --r3 0.55 --json``
                     (``--repeats`` times; median and best)
``atlas``            ``mechopt atlas five-bar --step 0.01`` (six indices, CSV and PNGs),
                     with the compute / figures split of its ``atlas.json`` (with worker
                     processes the figures are drawn there, side by side, while the
                     command writes the CSV: ``figures`` runs from the first figure sent
                     to the last one saved) and the rest of the wall time (``outside``:
                     the interpreter, the imports before the run starts, and the exit)
``tests``            ``python -m pytest -q -p no:cacheprovider --durations=15`` plus
                     ``--pytest-args`` (e.g. ``-n 2``): wall time, peak memory, the
                     summary line and the slowest tests

The package is whatever the children import (the installation, or a ``PYTHONPATH``
set before this script). Outputs go to a temporary folder (``--work``, removed
unless ``--keep``). No assertion on time: the figures depend on the machine and
its load; compare ratios within one run.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAPERS = ("le2013", "stan2008", "liu2006", "wu2008")
ROWS = ("stages", "stages-quick", "reproduce", "reproduce-quick", "evaluate", "atlas", "tests")
#: wall-time targets [s] of the issue (2 cores)
TARGETS = {"reproduce": 120.0, "reproduce-quick": 30.0, "atlas": 15.0, "tests": 240.0}
STAGES = ("optimisation", "atlas", "figures", "tables")
CLI = "import sys; from mechopt.cli import main; sys.exit(main())"


# --- the launcher: one command, its own rusage -----------------------------------------------
def _launch(spec_json: str) -> int:
    """Run one command (``{"argv", "cwd", "stdout", "stderr"}``) and print its wall time,
    CPU time and peak RSS as JSON (the last line of this process's stdout)."""
    spec = json.loads(spec_json)
    with open(spec["stdout"], "wb") as out, open(spec["stderr"], "wb") as err:
        t0 = time.perf_counter()
        rc = subprocess.call(spec["argv"], cwd=spec["cwd"], stdout=out, stderr=err)
        wall = time.perf_counter() - t0
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    scale = 1.0 / 2**20 if sys.platform == "darwin" else 1.0 / 1024.0  # bytes vs kB
    print(json.dumps({"rc": rc, "wall": wall, "cpu": ru.ru_utime + ru.ru_stime,
                      "rss_mb": ru.ru_maxrss * scale}))
    return 0


def measure(argv, work: Path, name: str, cwd=None) -> dict:
    """``{"rc", "wall", "cpu", "rss_mb", "stdout", "stderr"}`` of ``argv`` in a fresh
    process tree (started by the launcher, so that its rusage is its own)."""
    logs = work / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    spec = {"argv": [str(a) for a in argv], "cwd": str(cwd or work),
            "stdout": str(logs / f"{name}.out"), "stderr": str(logs / f"{name}.err")}
    res = subprocess.run([sys.executable, __file__, "--_launch", json.dumps(spec)],
                         capture_output=True, text=True, check=True)
    out = json.loads(res.stdout.strip().splitlines()[-1])
    out["stdout"] = Path(spec["stdout"]).read_text(errors="replace")
    out["stderr"] = Path(spec["stderr"]).read_text(errors="replace")
    return out


def _mechopt(*args):
    return [sys.executable, "-c", CLI, *args]


# --- the stage worker: one paper, timed by stage ---------------------------------------------
class _Clock:
    """Seconds per stage: each timed call counts its own time, less the time of the timed
    calls inside it, which count for their own stages (the atlas computed inside a
    figure function is atlas time, a front figure drawn by the runner figure time)."""

    def __init__(self):
        self.seconds = {s: 0.0 for s in STAGES}
        self.calls = {s: 0 for s in STAGES}
        self._inner = []  # per open timed call: seconds of the timed calls inside it

    def wrap(self, stage, fn):
        import functools

        @functools.wraps(fn)
        def timed(*args, **kwargs):
            self._inner.append(0.0)
            t0 = time.perf_counter()
            try:
                return fn(*args, **kwargs)
            finally:
                elapsed = time.perf_counter() - t0
                inner = self._inner.pop()
                self.seconds[stage] += elapsed - inner
                self.calls[stage] += 1
                if self._inner:
                    self._inner[-1] += elapsed

        return timed


#: functions of the experiment modules that build (or compute only for) a figure
_FIGURE_NAME = re.compile(r"^_?(fig|plot|draw)|_(map|figure|figures)$")


def _install_clock(clock: _Clock, paper: str):
    import importlib
    import inspect

    import mechopt.run.atlas as atlas
    import mechopt.run.io as mio
    import mechopt.run.runner as runner

    runner.optimize = clock.wrap("optimisation", runner.optimize)
    runner.sweep = clock.wrap("optimisation", runner.sweep)
    atlas.compute_atlas = clock.wrap("atlas", atlas.compute_atlas)
    atlas.draw_atlas = clock.wrap("figures", atlas.draw_atlas)
    mio.save_figure = clock.wrap("figures", mio.save_figure)
    names = [f"mechopt.experiments.{paper}"]
    if paper == "liu2006":
        names.append("mechopt.experiments.liu2006_figures")
    for name in names:
        mod = importlib.import_module(name)
        for attr, obj in list(vars(mod).items()):
            if not callable(obj):
                continue
            if attr in ("optimize", "sweep"):
                setattr(mod, attr, getattr(runner, attr))
            elif attr == "parallel_map":
                def pmap(func, items, *a, _pm=obj, **k):
                    stage = "optimisation" if "optimi" in getattr(func, "__name__", "") else "tables"
                    return clock.wrap(stage, _pm)(func, items, *a, **k)

                setattr(mod, attr, pmap)
            elif inspect.isfunction(obj) and obj.__module__ == name and _FIGURE_NAME.search(attr):
                setattr(mod, attr, clock.wrap("figures", obj))


def _stage_worker(paper: str, quick: bool, out: str, result: str) -> int:
    t0 = time.perf_counter()
    clock = _Clock()
    _install_clock(clock, paper)
    from mechopt.workflows.reproduce import reproduce

    t1 = time.perf_counter()
    reproduce(paper, out=out, quick=quick, force=True, log=lambda msg: None)
    total = time.perf_counter() - t1
    sec = dict(clock.seconds)
    sec["tables"] = max(total - sec["optimisation"] - sec["atlas"] - sec["figures"], 0.0)
    Path(result).write_text(json.dumps({"paper": paper, "quick": quick, "imports": t1 - t0,
                                        "total": total, "seconds": sec, "calls": clock.calls}))
    return 0


# --- rows ------------------------------------------------------------------------------------
def _fmt_mem(r):
    return f"{r['wall']:8.1f} s wall {r['cpu']:8.1f} s cpu {r['rss_mb']:7.0f} MB"


def _target(name, wall):
    if name not in TARGETS:
        return ""
    return f"  [target < {TARGETS[name]:g} s: {'met' if wall < TARGETS[name] else 'NOT met'}]"


def _check(r, what):
    if r["rc"] != 0:
        raise SystemExit(f"{what} failed (exit {r['rc']}):\n{r['stderr'][-2000:]}")


def row_stages(work: Path, quick: bool) -> dict:
    label = "stages-quick" if quick else "stages"
    print(f"\n== {label}: each paper alone, {'--quick' if quick else 'full'}, by stage", flush=True)
    print(f"{'paper':<10}{'total':>9}" + "".join(f"{s:>14}" for s in STAGES) + f"{'wall':>9}{'cpu':>9}{'RSS':>8}")
    out = {}
    for paper in PAPERS:
        res_file = work / f"{label}-{paper}.json"
        r = measure([sys.executable, __file__, "--_stage", paper, "1" if quick else "0",
                     work / label, res_file], work, f"{label}-{paper}")
        _check(r, f"stages of {paper}")
        st = json.loads(res_file.read_text())
        sec = st["seconds"]
        print(f"{paper:<10}{st['total']:8.1f}s" + "".join(f"{sec[s]:13.1f}s" for s in STAGES)
              + f"{r['wall']:8.1f}s{r['cpu']:8.1f}s{r['rss_mb']:6.0f}MB", flush=True)
        out[paper] = {**st, "wall": r["wall"], "cpu": r["cpu"], "rss_mb": r["rss_mb"]}
    tot = {s: sum(v["seconds"][s] for v in out.values()) for s in STAGES}
    print(f"{'sum':<10}{sum(v['total'] for v in out.values()):8.1f}s"
          + "".join(f"{tot[s]:13.1f}s" for s in STAGES)
          + f"{sum(v['wall'] for v in out.values()):8.1f}s{sum(v['cpu'] for v in out.values()):8.1f}s")
    return out


_PAPER_LINE = re.compile(r"\[\d+/\d+\] (\w+): .*\(([\d.]+) s\)")


def row_reproduce(work: Path, quick: bool) -> dict:
    name = "reproduce-quick" if quick else "reproduce"
    folder = work / name
    shutil.rmtree(folder, ignore_errors=True)
    args = ["reproduce", "all", "--out", folder] + (["--quick"] if quick else [])
    r = measure(_mechopt(*args), work, name)
    _check(r, name)
    papers = {m.group(1): float(m.group(2)) for m in _PAPER_LINE.finditer(r["stderr"])}
    print(f"\n== {name}: mechopt {' '.join(map(str, args[:2]))}{' --quick' if quick else ''}")
    print(f"{name:<22}{_fmt_mem(r)}{_target(name, r['wall'])}")
    if papers:
        print("  per paper (its log): " + ", ".join(f"{k} {v:.1f} s" for k, v in papers.items()))
    return {"wall": r["wall"], "cpu": r["cpu"], "rss_mb": r["rss_mb"], "papers": papers}


def row_evaluate(work: Path, repeats: int) -> dict:
    argv = _mechopt("evaluate", "five-bar", "--r1", "0.85", "--r2", "1.6", "--r3", "0.55", "--json")
    runs = []
    for i in range(repeats):
        r = measure(argv, work, f"evaluate-{i}")
        _check(r, "evaluate")
        runs.append(r)
    walls = [r["wall"] for r in runs]
    med = {"wall": statistics.median(walls), "cpu": statistics.median(r["cpu"] for r in runs),
           "rss_mb": max(r["rss_mb"] for r in runs)}
    print(f"\n== evaluate: mechopt evaluate five-bar --r1 0.85 --r2 1.6 --r3 0.55 --json "
          f"({repeats} fresh processes)")
    print(f"{'evaluate (median)':<22}{_fmt_mem(med)}  best {min(walls):.2f} s")
    return {**med, "best": min(walls), "walls": walls}


def row_atlas(work: Path) -> dict:
    folder = work / "atlas"
    shutil.rmtree(folder, ignore_errors=True)
    r = measure(_mechopt("atlas", "five-bar", "--step", "0.01", "--out", folder), work, "atlas")
    _check(r, "atlas")
    sec = json.loads((folder / "atlas.json").read_text()).get("seconds", {})
    print("\n== atlas: mechopt atlas five-bar --step 0.01 (six indices, CSV and PNGs)")
    print(f"{'atlas':<22}{_fmt_mem(r)}{_target('atlas', r['wall'])}")
    if sec:
        outside = f", outside {r['wall'] - sec['total']:.1f} s" if "total" in sec else ""
        print("  atlas.json: " + ", ".join(f"{k} {v:.1f} s" for k, v in sec.items()) + outside)
    return {"wall": r["wall"], "cpu": r["cpu"], "rss_mb": r["rss_mb"], "seconds": sec}


_DURATION = re.compile(r"^\s*([\d.]+)s (call|setup|teardown)\s+(\S+)", re.M)
_SUMMARY = re.compile(r"^=*\s*(\d+ passed.*?) in ([\d.]+)s", re.M)


def row_tests(work: Path, pytest_args: str) -> dict:
    argv = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--durations=15",
            *pytest_args.split()]
    r = measure(argv, work, "tests", cwd=ROOT)
    summary = _SUMMARY.search(r["stdout"])
    print(f"\n== tests: {' '.join(argv[1:])}")
    print(f"{'tests':<22}{_fmt_mem(r)}{_target('tests', r['wall'])}  exit {r['rc']}")
    if summary:
        print(f"  {summary.group(1)} in {summary.group(2)} s")
    slow = _DURATION.findall(r["stdout"])
    for sec, when, test in slow[:15]:
        print(f"  {float(sec):7.1f} s {when:<8} {test}")
    return {"wall": r["wall"], "cpu": r["cpu"], "rss_mb": r["rss_mb"], "rc": r["rc"],
            "summary": summary.group(1) if summary else None,
            "slowest": [(float(s), w, t) for s, w, t in slow]}


def main(argv=None) -> int:
    if argv is None:
        argv = sys.argv[1:]
    if argv[:1] == ["--_launch"]:
        return _launch(argv[1])
    if argv[:1] == ["--_stage"]:
        return _stage_worker(argv[1], argv[2] == "1", argv[3], argv[4])
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=",".join(ROWS), help=f"comma-separated rows of {', '.join(ROWS)}")
    ap.add_argument("--repeats", type=int, default=3, help="fresh processes of the evaluate row")
    ap.add_argument("--work", default=None, help="folder for the outputs (default: a temporary one)")
    ap.add_argument("--keep", action="store_true", help="keep the work folder")
    ap.add_argument("--json", default=None, help="write every figure to this JSON file")
    ap.add_argument("--pytest-args", default="", help="extra arguments of the tests row, e.g. '-n 2'")
    args = ap.parse_args(argv)
    rows = [s.strip() for s in args.only.split(",") if s.strip()]
    bad = [s for s in rows if s not in ROWS]
    if bad or not rows:
        ap.error(f"--only takes a comma-separated subset of {', '.join(ROWS)}, got {args.only!r}")
    if args.repeats < 1:
        ap.error("--repeats must be >= 1")
    work = Path(args.work) if args.work else Path(tempfile.mkdtemp(prefix="bench_pipeline_"))
    work.mkdir(parents=True, exist_ok=True)
    print(f"python {sys.version.split()[0]} on {os.cpu_count()} CPUs, load average "
          f"{', '.join(f'{v:.2f}' for v in os.getloadavg())}; work folder {work}", flush=True)
    results = {}
    t0 = time.perf_counter()
    try:
        for name in rows:
            if name in ("stages", "stages-quick"):
                results[name] = row_stages(work, name.endswith("quick"))
            elif name in ("reproduce", "reproduce-quick"):
                results[name] = row_reproduce(work, name.endswith("quick"))
            elif name == "evaluate":
                results[name] = row_evaluate(work, args.repeats)
            elif name == "atlas":
                results[name] = row_atlas(work)
            elif name == "tests":
                results[name] = row_tests(work, args.pytest_args)
    finally:
        if not args.keep and not args.work:
            shutil.rmtree(work, ignore_errors=True)
    print(f"\nbenchmark wall time {time.perf_counter() - t0:.0f} s; load average now "
          f"{', '.join(f'{v:.2f}' for v in os.getloadavg())}")
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1, default=str))
    return 0


if __name__ == "__main__":
    sys.exit(main())
