"""Run folders that cannot lie (issues 17 and 19): checkpoints that run no code,
resume that checks what it continues, a folder holding one run at a time, outputs
committed as a set, runs refused before they start when they cannot fit.

Every refusal is one line on stderr and exit status 2 through ``mechopt.cli.main``."""
from __future__ import annotations

import errno
import hashlib
import json
import os
import pickle
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mechopt.run import checkpoint
from mechopt.cli import main

FAST = ["le2013-relaxed", "--pop", "12", "--gen", "6", "--seed", "3", "--n-jobs", "1"]


def _mechopt_lines(stderr: str) -> list[str]:
    """What mechopt says on stderr, without the progress lines of a run."""
    return [line for line in stderr.strip().splitlines() if line.startswith("mechopt")
            and not line.startswith("mechopt: this run is estimated")]


def _err_line(capsys) -> str:
    err = _mechopt_lines(capsys.readouterr().err)
    assert len(err) == 1 and err[0].startswith("mechopt: error: "), err
    return err[0]


def _digests(folder: Path) -> dict:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.iterdir()) if p.is_file()}


@pytest.fixture(scope="module")
def interrupted_once(tmp_path_factory):
    """A folder of a run stopped right after its checkpoint of generation 2 (by a
    KeyboardInterrupt raised where a kill would land), made once per module: each test
    gets a copy (:func:`interrupted`)."""
    import mechopt.run.runner as R

    out = tmp_path_factory.mktemp("once") / "interrupted"
    real = R._save_checkpoint
    calls = []

    def stop_after_second(algo, state, folder):
        real(algo, state, folder)
        calls.append(algo.n_gen)
        if len(calls) == 2:
            raise KeyboardInterrupt

    R._save_checkpoint = stop_after_second
    try:
        assert main(["optimize", *FAST, "--checkpoint-every", "1", "--out", str(out)]) == 130
    finally:
        R._save_checkpoint = real
    assert (out / "checkpoint.pkl").exists()
    return out


@pytest.fixture(scope="module")
def reference_once(tmp_path_factory):
    """The folder of the same run to its end, made once per module (each test gets a
    copy: :func:`reference`)."""
    out = tmp_path_factory.mktemp("once") / "reference"
    assert main(["optimize", *FAST, "--out", str(out)]) == 0
    return out


def _copy(folder, tmp_path):
    """A copy of a run folder in the test's own ``tmp_path`` (the tests edit, resume,
    rerun or refuse runs in it), byte for byte, with its modification times."""
    out = tmp_path / folder.name
    shutil.copytree(folder, out)
    assert _digests(out) == _digests(folder)
    return out


@pytest.fixture()
def interrupted(interrupted_once, tmp_path):
    """A fresh copy of :func:`interrupted_once`'s folder."""
    return _copy(interrupted_once, tmp_path)


@pytest.fixture()
def reference(reference_once, tmp_path):
    """A fresh copy of :func:`reference_once`'s folder."""
    return _copy(reference_once, tmp_path)


# ------------------------------------------------------------------ checkpoints
class _Payload:
    """Unpickling this creates ``marker``: the proof that a file's code ran."""

    def __init__(self, marker):
        self.marker = str(marker)

    def __reduce__(self):
        return (open, (self.marker, "w"))


def test_a_crafted_pickle_runs_no_code(tmp_path, capsys):
    marker = tmp_path / "ran"
    pickle.loads(pickle.dumps(_Payload(marker)))  # the payload works ...
    assert marker.exists()
    marker.unlink()
    run = tmp_path / "run"
    run.mkdir()
    (run / "checkpoint.pkl").write_bytes(pickle.dumps({"algorithm_state": _Payload(marker), "state": {}}))
    assert main(["optimize", "--resume", str(run)]) == 2
    assert "unreadable checkpoint.pkl (not a mechopt checkpoint)" in _err_line(capsys)
    assert not marker.exists()  # ... but not through --resume


def test_a_crafted_pickle_in_our_format_fails_authentication(tmp_path, capsys):
    marker = tmp_path / "ran"
    payload = pickle.dumps(_Payload(marker))
    head = json.dumps({"payload_bytes": len(payload), "run_id": None}).encode()
    run = tmp_path / "run"
    run.mkdir()
    (run / "checkpoint.pkl").write_bytes(checkpoint.MAGIC + b"0" * 64 + b"\n" + head + b"\n" + payload)
    assert main(["optimize", "--resume", str(run)]) == 2
    assert "authentication failed" in _err_line(capsys)
    assert not marker.exists()


@pytest.mark.parametrize("edit", ["payload byte", "header", "truncated", "appended", "empty", "folder"])
def test_an_edited_checkpoint_is_refused_in_one_line(interrupted, capsys, edit):
    path = interrupted / "checkpoint.pkl"
    data = bytearray(path.read_bytes())
    if edit == "payload byte":
        data[-100] ^= 0x01
    elif edit == "header":
        import re

        data = bytearray(re.sub(rb'"generation": (\d+)', lambda m: b'"generation": %d' % (int(m[1]) + 1),
                                bytes(data), count=1))
        assert bytes(data) != path.read_bytes()
    elif edit == "truncated":
        data = data[: len(data) // 2]
    elif edit == "appended":
        data += b"\x00"
    elif edit == "empty":
        data = bytearray()
    if edit == "folder":
        path.unlink()
        path.mkdir()
    else:
        path.write_bytes(bytes(data))
    before = _digests(interrupted)
    assert main(["optimize", "--resume", str(interrupted)]) == 2
    assert "unreadable checkpoint.pkl" in _err_line(capsys)
    assert _digests(interrupted) == before


@pytest.mark.parametrize("content", ["not an algorithm", "rows not a list", "missing key", "not unpicklable"])
def test_an_authentic_checkpoint_of_a_bad_state_is_refused(interrupted, capsys, content):
    """A state signed with the user's own key but not what the runner wrote: one line."""
    path = interrupted / "checkpoint.pkl"
    header, ck = checkpoint.read(path)
    if content == "not an algorithm":
        ck["algorithm_state"] = 42
    elif content == "rows not a list":
        ck["state"]["rows"] = "x"
    elif content == "missing key":
        del ck["state"]["elapsed"]
    checkpoint.write(path, ck, header)
    if content == "not unpicklable":  # authentic bytes that are not a pickle
        import hmac

        raw = path.read_bytes()
        magic, rest = raw[: len(checkpoint.MAGIC)], raw[len(checkpoint.MAGIC) + 65:]
        head, _, payload = rest.partition(b"\n")
        payload = b"\x80\x05garbage" + b"\x00" * (len(payload) - 9)
        header = json.loads(head)
        header["payload_sha256"] = hashlib.sha256(payload).hexdigest()
        head = json.dumps(header, sort_keys=True).encode()
        key = bytes.fromhex(checkpoint.key_path().read_text().strip())
        mac = hmac.new(key, magic + head, hashlib.sha256).hexdigest().encode()  # the header's HMAC
        path.write_bytes(magic + mac + b"\n" + head + b"\n" + payload)
    assert main(["optimize", "--resume", str(interrupted)]) == 2
    line = _err_line(capsys)
    assert "unreadable checkpoint.pkl" in line
    if content == "not unpicklable":  # authentic: it got as far as unpickling
        assert "written by other library versions" in line


def test_the_key_is_private(interrupted):
    assert (checkpoint.key_path().stat().st_mode & 0o777) == 0o600


def test_a_checkpoint_resumes_to_the_uninterrupted_front(interrupted, reference):
    assert main(["optimize", "--resume", str(interrupted), "--seed", "3", "--pop", "12"]) == 0
    assert (interrupted / "front.csv").read_bytes() == (reference / "front.csv").read_bytes()
    assert not (interrupted / "checkpoint.pkl").exists()
    assert json.loads((interrupted / "manifest.json").read_text())["status"] == "complete"


# ------------------------------------------------------------------ resume
def test_resume_of_a_finished_run_says_it_is_complete(reference, capsys):
    before = _digests(reference)
    assert main(["optimize", "--resume", str(reference)]) == 2
    assert "this run is complete" in _err_line(capsys)
    assert _digests(reference) == before


@pytest.mark.parametrize("given, named", [(["--pop", "1"], "pop 1 (the run's: 12)"),
                                          (["--seed", "4"], "seed 4 (the run's: 3)"),
                                          (["--gen", "7", "--tol", "0.1"], "gen 7 (the run's: 6), tol 0.1"),
                                          (["le2013"], "problem 'le2013' (the run's: 'le2013-relaxed')"),
                                          (["--algorithm", "ga"], "algorithm 'ga'")])
def test_resume_refuses_other_options(interrupted, capsys, given, named):
    before = _digests(interrupted)
    assert main(["optimize", *given, "--resume", str(interrupted)]) == 2
    line = _err_line(capsys)
    assert "options differ from the checkpointed run" in line and named in line, line
    assert _digests(interrupted) == before


def test_a_stale_checkpoint_of_another_run_is_refused(interrupted, tmp_path, capsys):
    other = tmp_path / "other"
    assert main(["optimize", "le2013-relaxed", "--pop", "12", "--gen", "6", "--seed", "99", "--n-jobs", "1",
                 "--out", str(other)]) == 0
    shutil.copy(interrupted / "checkpoint.pkl", other / "checkpoint.pkl")
    before = _digests(other)
    assert main(["optimize", "--resume", str(other)]) == 2
    line = _err_line(capsys)
    assert "belongs to another run than manifest.json" in line and "seed 99 -> 3" in line, line
    assert _digests(other) == before


def test_a_checkpoint_of_another_problem_than_run_json_is_refused(tmp_path, capsys):
    """A wu2008 checkpoint in a folder whose run.json (no manifest: an older mechopt's)
    is a stan2008 run."""
    import mechopt.run.runner as R

    stan = tmp_path / "stan"
    assert main(["optimize", "stan2008-bipod", "--pop", "6", "--gen", "2", "--n-jobs", "1", "--out", str(stan)]) == 0
    (stan / "manifest.json").unlink()
    wu = tmp_path / "wu"
    real = R._save_checkpoint

    def stop(algo, state, folder):
        real(algo, state, folder)
        raise KeyboardInterrupt

    R._save_checkpoint = stop
    try:
        assert main(["optimize", "wu2008", "--pop", "6", "--gen", "3", "--n-jobs", "1", "--checkpoint-every",
                     "1", "--out", str(wu)]) == 130
    finally:
        R._save_checkpoint = real
    capsys.readouterr()
    shutil.copy(wu / "checkpoint.pkl", stan / "checkpoint.pkl")
    assert main(["optimize", "--resume", str(stan)]) == 2
    line = _err_line(capsys)
    assert "is a run of wu2008, run.json one of stan2008-bipod" in line, line


@pytest.mark.skipif(os.name != "posix", reason="SIGKILL")
def test_a_run_killed_before_its_first_checkpoint_is_recognised(tmp_path, reference, capsys):
    out = tmp_path / "early"
    proc = subprocess.Popen([sys.executable, "-m", "mechopt.cli", "optimize", *FAST, "--checkpoint-every", "5",
                             "--out", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while not (out / "manifest.json").exists():
        assert proc.poll() is None and time.time() < deadline
        time.sleep(0.005)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert not (out / "checkpoint.pkl").exists()
    assert main(["optimize", "--resume", str(out)]) == 2
    assert "stopped before its first checkpoint; run it again without --resume" in _err_line(capsys)
    # and running it again does
    assert main(["optimize", *FAST, "--checkpoint-every", "5", "--out", str(out)]) == 0
    assert (out / "front.csv").read_bytes() == (reference / "front.csv").read_bytes()


# ------------------------------------------------------------------ one run per folder
def test_a_foreign_checkpoint_is_refused_not_removed(tmp_path, capsys):
    out = tmp_path / "run"
    out.mkdir()
    (out / "checkpoint.pkl").write_bytes(b"someone else's")
    assert main(["optimize", *FAST, "--out", str(out)]) == 2
    assert "holds checkpoint.pkl, which no mechopt run manifest accounts for" in _err_line(capsys)
    assert (out / "checkpoint.pkl").read_bytes() == b"someone else's"
    assert sorted(p.name for p in out.iterdir()) == ["checkpoint.pkl"]


def test_a_second_run_with_other_options_is_refused_then_overwrites(reference, tmp_path, capsys):
    (reference / "notes.txt").write_text("mine")
    before = _digests(reference)
    argv = ["optimize", *FAST, "--seed", "4", "--out", str(reference)]
    assert main(argv) == 2
    line = _err_line(capsys)
    assert "holds another optimize run (seed 3 -> 4)" in line and "--overwrite" in line, line
    assert _digests(reference) == before
    assert main([*argv, "--overwrite"]) == 0
    lone = tmp_path / "lone"
    assert main(["optimize", *FAST, "--seed", "4", "--out", str(lone)]) == 0
    assert (reference / "front.csv").read_bytes() == (lone / "front.csv").read_bytes()
    assert (reference / "notes.txt").read_text() == "mine"  # not the run's: never touched


def test_the_same_run_again_replaces_its_own_outputs(reference, capsys):
    front = (reference / "front.csv").read_bytes()
    assert main(["optimize", *FAST, "--out", str(reference)]) == 0
    assert (reference / "front.csv").read_bytes() == front


def test_a_sweep_in_an_optimize_folder_is_refused(reference, capsys):
    assert main(["sweep", "le2013-gamma", "--weights", "0,1", "--pop", "6", "--gen", "2", "--n-jobs", "1",
                 "--out", str(reference)]) == 2
    line = _err_line(capsys)
    assert "holds an optimize run; pass --overwrite" in line, line


def test_an_atlas_of_other_settings_is_refused(tmp_path, capsys):
    out = tmp_path / "atlas"
    assert main(["atlas", "five-bar", "--step", "0.25", "--n-jobs", "1", "--no-figures", "--out", str(out)]) == 0
    capsys.readouterr()
    before = _digests(out)
    assert main(["atlas", "five-bar", "--step", "0.2", "--n-jobs", "1", "--no-figures", "--out", str(out)]) == 2
    line = _err_line(capsys)
    assert "holds another atlas run (step 0.25 -> 0.2)" in line, line
    assert _digests(out) == before
    assert main(["atlas", "five-bar", "--step", "0.2", "--n-jobs", "1", "--no-figures", "--overwrite",
                 "--out", str(out)]) == 0
    m = json.loads((out / "manifest.json").read_text())
    assert m["status"] == "complete" and m["key"]["step"] == 0.2
    assert set(m["files"]) == {"atlas.csv", "atlas.json"}


# ------------------------------------------------------------------ a full disk
def _small_filesystem(tmp_path, free_bytes):
    """A tmpfs with about ``free_bytes`` left, or None where this process cannot mount."""
    mnt = tmp_path / "small"
    mnt.mkdir()
    if os.geteuid() != 0 or shutil.which("mount") is None:
        return None
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(mnt)], capture_output=True)
    if done.returncode != 0:
        return None
    stat = os.statvfs(mnt)
    filler = stat.f_bavail * stat.f_frsize - free_bytes
    with open(mnt / "filler", "wb") as fh:
        fh.write(b"\0" * filler)
    return mnt


@pytest.mark.parametrize("argv, outputs", [
    (["optimize", *FAST], ("front.csv", "history.csv", "run.json", "front.png")),
    (["atlas", "five-bar", "--step", "0.1", "--n-jobs", "1"], ("atlas.csv", "atlas.json", "atlas_gci.png")),
])
def test_a_full_disk_gives_one_line_and_no_partial_set(tmp_path, argv, outputs):
    mnt = _small_filesystem(tmp_path, free_bytes=40_000)
    env = {**os.environ}
    if mnt is None:  # a fault-injecting writer instead: figures fail with ENOSPC
        mnt = tmp_path / "small"
        env["MECHOPT_TEST_ENOSPC_AFTER"] = "40000"
    out = mnt / "run"
    try:
        done = subprocess.run([sys.executable, "-c", _FAULTY, *argv, "--out", str(out)], env=env,
                              capture_output=True, text=True, timeout=300)
        lines = _mechopt_lines(done.stderr)
        assert done.returncode == 3, done.stderr  # a runtime failure (the disk)
        assert "Traceback" not in done.stderr
        assert len(lines) == 1 and "No space left on device" in lines[0] and str(out) in lines[0], done.stderr
        left = {p.name for p in out.iterdir()} if out.exists() else set()
        assert not left & set(outputs), left  # nothing of the set under a final name
        assert not any(p.name.startswith(".") and p.name != ".atlas_chunks" for p in out.iterdir()) \
            if out.exists() else True
    finally:
        subprocess.run(["umount", str(mnt)], capture_output=True)


#: runs the CLI; with MECHOPT_TEST_ENOSPC_AFTER=N every file write past N bytes in
#: total fails as a full disk would (for machines where the test cannot mount)
_FAULTY = r"""
import errno, os, sys
limit = os.environ.get("MECHOPT_TEST_ENOSPC_AFTER")
if limit:
    import mechopt.run.io as io
    real = io.atomic_path
    used = [0]
    import contextlib
    @contextlib.contextmanager
    def faulty(path):
        with real(path) as tmp:
            yield tmp
            used[0] += os.path.getsize(tmp)
            if used[0] > int(limit):
                raise OSError(errno.ENOSPC, "No space left on device", str(tmp))
    io.atomic_path = faulty
from mechopt.cli import main
sys.exit(main(sys.argv[1:]))
"""


# ------------------------------------------------------------------ limits from resources
def test_a_run_that_cannot_fit_in_memory_is_refused_before_it_starts(tmp_path, capsys, monkeypatch):
    import pymoo.core.problem

    def no_evaluation(*args, **kwargs):
        raise AssertionError("a design was evaluated")

    monkeypatch.setattr(pymoo.core.problem.Problem, "evaluate", no_evaluation)
    out = tmp_path / "huge"
    assert main(["optimize", "le2013", "--pop", "100000", "--gen", "2", "--out", str(out)]) == 2
    line = _err_line(capsys)
    assert "of memory available; lower --pop" in line and "GB" in line, line
    assert not out.exists()


def test_a_run_of_months_is_refused_with_its_estimate(tmp_path):
    from mechopt.run import budget

    out = tmp_path / "long"
    argv = ["optimize", "liu2006-many", "--pop", "6000", "--gen", "1000000", "--out", str(out)]
    # in a process of its own: were it accepted, it would run for months
    done = subprocess.run([sys.executable, "-m", "mechopt.cli", *argv], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 2, done.stderr
    lines = _mechopt_lines(done.stderr)
    assert len(lines) == 1, done.stderr
    line = lines[0]
    assert "this run would take about" in line and ("days" in line or "years" in line), line
    assert not out.exists()
    # the thresholds: above an hour a line, above 30 days a refusal
    est = budget.Estimate(1e6, 2 * 3600.0, 10, 720.0)
    assert budget.check(est, memory=1e9).startswith("mechopt: this run is estimated at about 1 MB")
    assert budget.check(budget.Estimate(1e6, 60.0, 10, 6.0), memory=1e9) is None
    with pytest.raises(ValueError, match="would take about 1 MB of memory and 1.0[0-9]* years"):
        budget.check(budget.Estimate(1e6, 365.25 * 86400 * 1.04, 10, 1.0), memory=1e9)
