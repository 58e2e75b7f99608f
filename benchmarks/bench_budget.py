"""How good is the estimate a run prints before it starts (mechopt.run.budget)?

    python benchmarks/bench_budget.py

For a few runs of growing population it prints the estimate (memory, time) beside
what the run then took (peak resident memory of a fresh process, wall time), and
their ratios. The estimate is meant to err on the large side (ratio estimate /
measured >= 1 for memory at large populations, where the pairwise term dominates);
no assertion: the figures depend on the machine and its load.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

RUNS = [  # problem, algorithm, pop, gen
    ("le2013", "ga", 500, 3),
    ("le2013", "ga", 4000, 3),
    ("stan2008-bipod", "nsga2", 2000, 3),
    ("stan2008-bipod", "nsga2", 6000, 3),
    ("liu2006-w-gci", "nsga2", 200, 5),
]

CHILD = r"""
import json, resource, sys, time
from mechopt import budget
from mechopt.problems import get
from mechopt.run.runner import make_algorithm, optimize
name, algo, pop, gen = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
problem = get(name)
a = make_algorithm(algo, pop, problem.n_obj)
est = budget.estimate(problem, pop, pop, gen)
t0 = time.perf_counter()
optimize(problem, algo, pop, gen, seed=1, n_jobs=1, progress=False, plot=False)
wall = time.perf_counter() - t0
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024.0
print(json.dumps({"est_mem": est.memory_bytes, "est_s": est.seconds, "mem": rss, "s": wall}))
"""


def main() -> int:
    print(f"{'run':<32} {'est. MB':>9} {'peak MB':>9} {'ratio':>6} {'est. s':>8} {'wall s':>8} {'ratio':>6}")
    for problem, algo, pop, gen in RUNS:
        with tempfile.TemporaryDirectory() as d:
            done = subprocess.run([sys.executable, "-c", CHILD, problem, algo, str(pop), str(gen)],
                                  capture_output=True, text=True, cwd=d, env={**os.environ})
        if done.returncode:
            print(f"{problem} {algo} pop {pop}: failed\n{done.stderr}")
            continue
        r = json.loads(done.stdout.strip().splitlines()[-1])
        label = f"{problem} {algo} pop {pop} gen {gen}"
        print(f"{label:<32} {r['est_mem'] / 1e6:9.0f} {r['mem'] / 1e6:9.0f} {r['est_mem'] / r['mem']:6.2f} "
              f"{r['est_s']:8.2f} {r['s']:8.2f} {r['est_s'] / r['s']:6.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
