"""Runs that survive SIGKILL: checkpoint, kill, resume, same bytes as an uninterrupted run."""
import os
import signal
import subprocess
import sys
import time

import pytest

from mechopt.cli import main

# about 6 ms per design: slow enough to be killed after its first checkpoint; the
# generations after it only need to be more than one for the resumed run to have some
# left (killed, resumed and uninterrupted runs compare byte for byte at any length):
# 5 (were 10)
ARGS = ["le2013-relaxed", "--pop", "40", "--gen", "5", "--seed", "3", "--n-jobs", "1"]


def _cli(*argv):
    return [sys.executable, "-m", "mechopt.cli", *argv]


def _kill_after_first_checkpoint(run, found):
    """Start the run of ``ARGS`` in ``run``, SIGKILL it once its first checkpoint is on
    disk, record what the killed run left (``found``) and resume it to the end."""
    proc = subprocess.Popen(_cli("optimize", *ARGS, "--checkpoint-every", "1", "--out", str(run)),
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.time() + 120
        while not (run / "checkpoint.pkl").exists():
            if proc.poll() is not None:
                found["error"] = "the run ended before its first checkpoint"
                return
            if time.time() > deadline:
                found["error"] = "no checkpoint within 120 s"
                return
            time.sleep(0.05)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    import json

    found["finals"] = {p.name for p in run.iterdir() if not p.name.startswith(".")}
    found["status"] = json.loads((run / "manifest.json").read_text())["status"]
    found["resumed"] = subprocess.run(_cli("optimize", "--resume", str(run)), capture_output=True, text=True)


@pytest.mark.skipif(os.name != "posix", reason="SIGKILL")
def test_killed_run_resumes_to_the_same_front(tmp_path):
    import threading

    ref, run = tmp_path / "ref", tmp_path / "run"
    found = {}
    # the killed and resumed run goes on beside the uninterrupted one (in this process,
    # whose main thread the command's signal handling needs)
    def side_run():
        try:
            _kill_after_first_checkpoint(run, found)
        except Exception as exc:  # noqa: BLE001 - reported below, in the test's thread
            found["error"] = f"{type(exc).__name__}: {exc}"

    side = threading.Thread(target=side_run, daemon=True)
    side.start()
    try:
        assert main(["optimize", *ARGS, "--out", str(ref)]) == 0
    finally:
        side.join(600)
    assert not side.is_alive() and "error" not in found, found.get("error")
    # a killed run leaves no output under a final name but the checkpoint, and its
    # manifest says it is still running
    assert found["finals"] == {"checkpoint.pkl", "manifest.json"}
    assert found["status"] == "running"

    done = found["resumed"]
    assert done.returncode == 0, done.stderr
    assert (run / "front.csv").read_bytes() == (ref / "front.csv").read_bytes()
    assert (run / "history.csv").read_text().splitlines()[1:] == (ref / "history.csv").read_text().splitlines()[1:]
    assert not (run / "checkpoint.pkl").exists()


def test_resume_without_checkpoint(tmp_path, capsys):
    assert main(["optimize", "--resume", str(tmp_path)]) == 2
    assert "holds no checkpoint.pkl" in capsys.readouterr().err


def test_resume_with_garbage_checkpoint(tmp_path, capsys):
    (tmp_path / "checkpoint.pkl").write_bytes(b"not a pickle")
    assert main(["optimize", "--resume", str(tmp_path)]) == 2
    assert "unreadable checkpoint.pkl" in capsys.readouterr().err


def test_checkpoint_every_must_be_positive(tmp_path, capsys):
    assert main(["optimize", "le2013", "--checkpoint-every", "0", "--out", str(tmp_path / "o")]) == 2
    assert "checkpoint_every must be a positive integer" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("problem, algorithm", [("stan2008-bipod", "nsga2"), ("le2013", "ga"),
                                                ("liu2006-many", "nsga3")])
def test_every_algorithm_checkpoints_and_resumes_identically(tmp_path, problem, algorithm):
    from mechopt.problems import get
    from mechopt.run.runner import _save_checkpoint, make_algorithm, optimize, resume

    ref = optimize(get(problem), algorithm, pop=8, gen=3, seed=5, n_jobs=1, progress=False)
    p = get(problem)
    algo = make_algorithm(algorithm, 8, p.n_obj)
    algo.setup(p, termination=("n_gen", 3), seed=5, verbose=False)
    algo.next()  # generation 1, then "killed"
    state = {"algorithm": algorithm, "pop": 8, "gen": 3, "seed": 5, "rows": [], "ref": None,
             "elapsed": 0.0, "checkpoint_every": 1}
    _save_checkpoint(algo, state, tmp_path)
    res = resume(tmp_path, n_jobs=1, progress=False, plot=False)
    assert res.front.equals(ref.front)
