"""Runs end cleanly under every signal: SIGINT/SIGTERM stop with one line and exit
130/143, no worker process outlives the run (SIGKILL included), no temporary file is
left, and the resumed run equals an uninterrupted one. A second run on a locked
folder fails at once.

Workers are found by an environment tag the test gives the run (inherited by every
process it starts), so the check sees the loky workers and their resource tracker."""
import os
import random
import re
import signal
import subprocess
import sys
import time
import uuid

import pytest

from conftest import NUMPY_ATLAS

psutil = pytest.importorskip("psutil")

pytestmark = pytest.mark.skipif(sys.platform != "linux", reason="signals and /proc")

#: the runs only need to outlast the moment of the signal (at most 1.5 s after the workers
#: start) and a second command's start-up, so that they are stopped mid-way; what is
#: checked (exit status, no survivor, resumed result = uninterrupted result) does not
#: depend on their size: about 10 s each (were gen 30 and --step 0.05: 20 s)
OPT = ["optimize", "liu2006-w-gci", "--pop", "40", "--gen", "15", "--seed", "3", "--n-jobs", "2",
       "--checkpoint-every", "1"]
#: a progress line on a pipe: "liu2006-w-gci nsga2: 3/30 (1.1 s) ..." or "atlas: 1/22 (0.5 s) ..."
PROGRESS = re.compile(r"^[\w.-]+( [\w.-]+)?: \d+/\d+ \(\d")
#: (344 designs in 22 chunks, as many chunks as the 1364 designs of --step 0.05 in chunks of 64;
#: tests/conftest.py: its reference is shared with tests/test_atlas_resume.py)
ATLAS = NUMPY_ATLAS


def _tagged(tag):
    found = []
    for p in psutil.process_iter(["pid"]):
        try:
            if p.environ().get("MECHOPT_TEST_TAG") == tag:
                found.append(p)
        except (psutil.NoSuchProcess, psutil.AccessDenied, psutil.ZombieProcess):
            continue
    return found


def _default_signals():
    """In the child before exec: SIGINT and SIGTERM as a shell in the foreground gives
    them. A suite started in the background (``cmd &``, nohup) runs with SIGINT
    ignored, which every child inherits: Python then installs no KeyboardInterrupt
    handler, and a run "interrupted" by SIGINT would just go on."""
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, signal.SIG_DFL)


def _start(argv, out, tag, extra_env=None):
    env = {**os.environ, "MECHOPT_TEST_TAG": tag, **(extra_env or {})}
    return subprocess.Popen([sys.executable, "-m", "mechopt.cli", *argv, "--out", str(out)],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=_default_signals)


def _wait_for_workers(proc, tag, deadline=60.0):
    t0 = time.monotonic()
    while time.monotonic() - t0 < deadline:
        if proc.poll() is not None:
            return False
        if len(_tagged(tag)) >= 2:  # the run and at least one worker
            return True
        time.sleep(0.05)
    return False


def _no_survivors(tag, within=5.0):
    t0 = time.monotonic()
    while time.monotonic() - t0 < within:
        alive = [p for p in _tagged(tag) if p.status() != psutil.STATUS_ZOMBIE]
        if not alive:
            return True
        time.sleep(0.1)
    return False


def _kill_and_check(argv, out, sig, rng, extra_env=None):
    tag = uuid.uuid4().hex
    proc = _start(argv, out, tag, extra_env)
    assert _wait_for_workers(proc, tag), "the run ended before its workers started"
    time.sleep(rng.uniform(0.0, 1.5))
    ended_before = proc.poll() is not None
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert _no_survivors(tag), [p.cmdline() for p in _tagged(tag)]
    assert not list(out.rglob(".*.tmp")) if out.exists() else True
    if ended_before:  # finished before the signal was sent: nothing to check of it
        return proc.returncode
    # the run was alive when the signal was sent: it must have ended by it (a run that
    # ignored it and finished with 0 is a failure, not "finished before the signal")
    assert proc.returncode == {signal.SIGINT: 130, signal.SIGTERM: 143, signal.SIGKILL: -9}[sig], \
        (proc.returncode, err)
    if sig == signal.SIGKILL:
        return proc.returncode
    lines = [l for l in err.strip().splitlines() if l.strip()]
    # the progress lines printed before the signal (on a pipe, one per step), then one
    # line saying the run was interrupted, and nothing else (no traceback)
    messages = [l for l in lines if not PROGRESS.match(l)]
    assert len(messages) == 1 and "interrupted" in messages[0] and lines[-1] == messages[0], err
    assert proc.returncode == {signal.SIGINT: 130, signal.SIGTERM: 143}[sig]
    return proc.returncode


def _run_to_end(argv, out, extra_env=None):
    tag = uuid.uuid4().hex
    proc = _start(argv, out, tag, extra_env)
    _, err = proc.communicate(timeout=600)
    assert proc.returncode == 0, err
    assert _no_survivors(tag)


def _resume(argv, out, extra_env=None):
    if argv[0] == "optimize" and (out / "checkpoint.pkl").exists():
        tag = uuid.uuid4().hex
        env = {**os.environ, "MECHOPT_TEST_TAG": tag, **(extra_env or {})}
        r = subprocess.run([sys.executable, "-m", "mechopt.cli", "optimize", "--resume", str(out),
                            "--n-jobs", "2"], env=env, capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr
    else:
        import shutil

        if argv[0] == "optimize":
            shutil.rmtree(out, ignore_errors=True)
        _run_to_end(argv, out, extra_env)


def _case(tmp_path, argv, sig, seed, reference, file, extra_env=None):
    rng = random.Random(seed)
    out = tmp_path / f"{argv[0]}-{sig.name}-{seed}"
    _kill_and_check(argv, out, sig, rng, extra_env)
    _resume(argv, out, extra_env)
    assert (out / file).read_bytes() == reference.read_bytes()
    assert not list(out.rglob(".*.tmp"))


# one reference per command, each computed once and only where a test needs it: under
# pytest-xdist the optimize and the atlas tests form two groups (tests/conftest.py, SPLIT;
# the atlas one with tests/test_atlas_resume.py, TOGETHER, which uses the same reference)
# that run side by side, each computing its own reference
@pytest.fixture(scope="module")
def optimize_reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "opt"
    _run_to_end(OPT, out)
    return out / "front.csv"


@pytest.fixture(scope="module")
def atlas_reference(numpy_atlas_reference):
    """The session's uninterrupted NumPy-path atlas (tests/conftest.py), run to its end
    by the command with every process tagged: none of them outlives it."""
    path, tag = numpy_atlas_reference
    assert _no_survivors(tag)
    return path


#: in CI one signal per command and SIGKILL on both; every (command, signal) pair at
#: five seeded moments runs behind the ``slow`` marker (test_random_moments)
CI_CASES = [("optimize", signal.SIGINT), ("optimize", signal.SIGKILL), ("atlas", signal.SIGTERM),
            ("atlas", signal.SIGKILL)]


@pytest.mark.parametrize("sig", [s for w, s in CI_CASES if w == "optimize"], ids=lambda s: s.name)
def test_optimize_under_a_signal(tmp_path, optimize_reference, sig):
    _case(tmp_path, OPT, sig, 1, optimize_reference, "front.csv")


@pytest.mark.parametrize("sig", [s for w, s in CI_CASES if w == "atlas"], ids=lambda s: s.name)
def test_atlas_under_a_signal(tmp_path, atlas_reference, sig):
    # the NumPy kernels are slow enough to be caught mid-way
    _case(tmp_path, ATLAS, sig, 1, atlas_reference, "atlas.csv", {"MECHOPT_NO_NUMBA": "1"})


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(2, 7))
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGKILL], ids=lambda s: s.name)
@pytest.mark.parametrize("what", ["optimize", "atlas"])
def test_random_moments(tmp_path, request, what, sig, seed):
    argv, file, env = ((OPT, "front.csv", None) if what == "optimize"
                       else (ATLAS, "atlas.csv", {"MECHOPT_NO_NUMBA": "1"}))
    reference = request.getfixturevalue(f"{what}_reference")
    _case(tmp_path, argv, sig, seed, reference, file, env)


def test_the_runs_get_sigint_even_when_the_suite_ignores_it():
    """The suite run as a background job (SIGINT ignored, inherited by children): the
    runs it starts still get SIGINT as Python's KeyboardInterrupt."""
    code = "import signal; print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)"
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        inherited = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
        ours = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                              preexec_fn=_default_signals)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert inherited.stdout.strip() == "False"  # what a background suite gives a plain child
    assert ours.stdout.strip() == "True"


def test_a_second_signal_while_the_run_stops_is_ignored(tmp_path):
    """Ctrl-C pressed twice: the second SIGINT lands while the run stops its workers or
    while the interpreter exits (the pools' exit handlers join their threads); it
    printed a traceback there or ended the process by SIGINT (status -2)."""
    tag = uuid.uuid4().hex
    proc = _start(OPT, tmp_path / "twice", tag)
    assert _wait_for_workers(proc, tag), "the run ended before its workers started"
    time.sleep(1.0)
    for gap in (0.02, 0.05, 0.1):
        proc.send_signal(signal.SIGINT)
        time.sleep(gap)
    _, err = proc.communicate(timeout=60)
    assert _no_survivors(tag), [p.cmdline() for p in _tagged(tag)]
    messages = [l for l in err.strip().splitlines() if l.strip() and not PROGRESS.match(l)]
    assert proc.returncode == 130 and len(messages) == 1 and "interrupted" in messages[0], (proc.returncode, err)


def test_a_second_optimize_run_on_the_same_folder_fails_at_once(tmp_path, optimize_reference):
    """A second run on a folder in use is refused at once; a run in another folder
    meanwhile is not; the refused run leaves the first one's result as an undisturbed
    run writes it: the module's reference, the same command run alone to its end (the
    test's name holds "optimize": under pytest-xdist it runs in that reference's group)."""
    out = tmp_path / "shared"
    tag = uuid.uuid4().hex
    first = _start(OPT, out, tag)
    other = None
    try:
        assert _wait_for_workers(first, tag)
        # a small run in its own folder, started while the first runs
        other = subprocess.Popen([sys.executable, "-m", "mechopt.cli", *OPT[:2], "--pop", "4", "--gen", "1",
                                  "--n-jobs", "1", "--out", str(tmp_path / "other")],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        t0 = time.monotonic()
        second = subprocess.run([sys.executable, "-m", "mechopt.cli", *OPT, "--seed", "4", "--out",
                                 str(out)], capture_output=True, text=True, timeout=120)
        assert time.monotonic() - t0 < 20
        assert second.returncode == 2
        lines = second.stderr.strip().splitlines()
        assert len(lines) == 1 and "in use by another mechopt run" in lines[0]
        _, err = other.communicate(timeout=120)
        assert other.returncode == 0, err
        _, err = first.communicate(timeout=600)
        assert first.returncode == 0, err
    finally:
        for proc in (first, other):  # a failed check above
            if proc is not None and proc.poll() is None:
                proc.kill()
                proc.communicate()
    assert _no_survivors(tag)
    assert (out / "front.csv").read_bytes() == optimize_reference.read_bytes()
