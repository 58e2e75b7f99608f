"""The local pool of :mod:`mechopt.run.parallel`: nested maps clean up after themselves.

``mechopt reproduce`` runs each paper in a worker process, and a paper maps its own
runs on two processes there: a pool inside a worker. The worker is killed when its
parent exits, so a pool it kept would leave its semaphores to the resource tracker,
which then prints "leaked semlock objects" when the command ends.
"""
from __future__ import annotations

import os
import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent("""
    import os
    from mechopt.run.parallel import parallel_map

    def inner(i):
        return (os.getpid(), i * i)

    def outer(k):
        got = parallel_map(inner, range(4), n_jobs=2)
        return os.getpid(), [v for _, v in got], sorted({p for p, _ in got})

    if __name__ == "__main__":
        res = parallel_map(outer, range(3), n_jobs=2)
        me = os.getpid()
        assert all(v == [0, 1, 4, 9] for _, v, _ in res), res
        outer_pids = {p for p, _, _ in res}
        inner_pids = {p for _, _, ps in res for p in ps}
        assert me not in outer_pids and not (outer_pids & inner_pids), (me, outer_pids, inner_pids)
        print("ok", len(outer_pids), len(inner_pids))
""")


def test_a_pool_inside_a_worker_leaves_no_leaked_semaphores(tmp_path):
    script = tmp_path / "nested.py"
    script.write_text(SCRIPT)
    # without the filter the command line sets for loky's tracker (mechopt.cli), which
    # an in-process CLI test of this worker may have put into the environment
    env = {k: v for k, v in os.environ.items() if k != "PYTHONWARNINGS"}
    run = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300,
                         cwd=tmp_path, env=env)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("ok "), run.stdout
    # the inner maps ran on pools of their own (processes neither this one nor the outer workers)
    n_outer, n_inner = map(int, run.stdout.split()[1:3])
    assert n_outer >= 1 and n_inner >= 2
    assert "leaked" not in run.stderr and "Traceback" not in run.stderr, run.stderr
