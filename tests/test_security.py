"""Nothing outside the run folder is ever touched, no file runs code, no read hangs
(issue 27).

Each test names the failure it guards against (the issue's numbering). The cases
that could lose data (a crafted manifest, an unsafe key, the temp-file sweep, a
shared parent folder, two runs racing on a new folder) keep a sentinel file OUTSIDE
the run folder and check that it survives byte for byte. Reads that used to hang (a
FIFO) run in a daemon thread with a deadline, so that a regression fails instead of
hanging the suite."""
from __future__ import annotations

import errno
import fcntl
import hashlib
import hmac
import io
import json
import os
import pickle
import socket
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mechopt.cli import main
from mechopt.run import checkpoint
from mechopt.run import io as _io

RUN = ["optimize", "wu2008", "--gen", "1", "--pop", "4"]
RUN_OUTPUTS = ("front.csv", "history.csv", "run.json", "front.png", "sweep.csv", "sweep.png", "checkpoint.pkl")


@pytest.fixture(autouse=True)
def own_key(tmp_path, monkeypatch):
    """Every test with its own key folder (the user's is never read or made)."""
    monkeypatch.setenv("MECHOPT_CONFIG_DIR", str(tmp_path / "config"))
    monkeypatch.delenv("MECHOPT_RUN_TAG", raising=False)
    return tmp_path / "config" / "checkpoint.key"


@pytest.fixture
def sentinel(tmp_path):
    """A file outside every run folder, with its bytes; check with ``_intact``."""
    path = tmp_path / "outside" / "victim.txt"
    path.parent.mkdir()
    data = os.urandom(64)
    path.write_bytes(data)
    return path, data


def _intact(sentinel) -> bool:
    path, data = sentinel
    return path.is_file() and not path.is_symlink() and path.read_bytes() == data


def _one_error_line(capsys) -> str:
    err = [l for l in capsys.readouterr().err.strip().splitlines()
           if l.startswith("mechopt") and not l.startswith("mechopt: this run is estimated")]
    assert len(err) == 1 and err[0].startswith("mechopt: error: "), err
    return err[0]


def _finishes(func, seconds=20.0):
    """``func()``'s result or exception (returned, not raised); fails if it has not
    returned after ``seconds`` (a hang), leaving it in a daemon thread."""
    box = {}

    def call():
        try:
            box["value"] = func()
        except BaseException as exc:  # noqa: BLE001 - handed to the test
            box["error"] = exc

    t = threading.Thread(target=call, daemon=True)
    t.start()
    t.join(seconds)
    assert not t.is_alive(), f"still running after {seconds} s (a hang)"
    return box.get("error", box.get("value"))


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


# ---------------------------------------------------------------- 1. crafted manifests
def _crafted(folder: Path, victim: Path, form: str) -> dict:
    rel = os.path.relpath(victim, folder)
    base = {"kind": "atlas", "key": {"x": 1}, "status": "complete", "run_id": "x"}
    return {"owned absolute": {**base, "owned": [str(victim)]},
            "owned relative": {**base, "owned": [rel]},
            "files relative": {**base, "files": {rel: _sha(victim.read_bytes())}},
            "owned string": {**base, "owned": str(victim)},  # taken character by character
            "files absolute": {**base, "files": {str(victim): _sha(victim.read_bytes())}},
            }[form]


@pytest.mark.parametrize("form", ["owned absolute", "owned relative", "files relative", "owned string",
                                  "files absolute"])
def test_1_a_crafted_manifest_deletes_nothing_outside_the_folder(tmp_path, sentinel, form):
    out = tmp_path / "o"
    out.mkdir()
    (out / "notes.txt").write_text("the user's own file\n")
    (out / "manifest.json").write_text(json.dumps(_crafted(out, sentinel[0], form)))
    try:  # reproduce passes overwrite=True to its own runs: the worst case
        _io.claim_out(out, "optimize", {"seed": 1}, RUN_OUTPUTS, overwrite=True)
    except ValueError as exc:
        assert "\n" not in str(exc)
    assert _intact(sentinel)
    assert (out / "notes.txt").read_text() == "the user's own file\n"


def test_1_a_manifest_naming_a_users_file_by_its_sha256_does_not_remove_it(tmp_path):
    """A sha256 anyone can compute vouches for nothing: only a manifest authenticated
    with the user's key does."""
    out = tmp_path / "o"
    out.mkdir()
    mine = b"results the user typed in\n"
    (out / "front.csv").write_bytes(mine)
    (out / "manifest.json").write_text(json.dumps(
        {"kind": "atlas", "key": {}, "status": "complete", "run_id": "x", "files": {"front.csv": _sha(mine)}}))
    with pytest.raises(ValueError, match="not authenticated by your key"):
        _io.claim_out(out, "optimize", {"seed": 1}, RUN_OUTPUTS, overwrite=True)
    assert (out / "front.csv").read_bytes() == mine


def test_1_the_issues_repro_end_to_end(tmp_path, sentinel, capsys):
    out = tmp_path / "o"
    out.mkdir()
    (out / "manifest.json").write_text(json.dumps({"kind": "optimize", "key": {}, "status": "complete",
                                                   "run_id": "x", "owned": [str(sentinel[0])]}))
    assert main([*RUN, "--out", str(out), "--overwrite"]) == 2
    assert "not a mechopt run manifest" in _one_error_line(capsys)
    assert _intact(sentinel)


def test_1_an_authentic_manifest_still_lets_overwrite_replace_its_own_files(tmp_path, sentinel):
    """The legitimate case keeps working, and even an authentic manifest removes only
    regular files of the run's output names (a link is left, its target untouched)."""
    out = tmp_path / "o"
    out.mkdir()
    (out / "front.png").symlink_to(sentinel[0])
    (out / "run.json").write_text("{}")
    m = {"kind": "atlas", "key": {"x": 1}, "status": "complete", "run_id": "x",
         "files": {"run.json": _sha(b"{}"), "front.png": _sha(sentinel[1])}}
    _io.write_manifest(m, out)
    _io.claim_out(out, "optimize", {"seed": 1}, RUN_OUTPUTS, overwrite=True)
    assert not (out / "run.json").exists()  # ours: removed
    assert (out / "front.png").is_symlink() and _intact(sentinel)


# ---------------------------------------------------------------- 2. the key
class _Marker:
    """Unpickling it creates a file: proof that a checkpoint's code ran."""

    def __init__(self, path):
        self.path = str(path)

    def __reduce__(self):
        return (Path.touch, (Path(self.path),))


def _forge(path: Path, key: bytes, obj, magic=b"MECHOPT-CHECKPOINT 1\n"):
    """A checkpoint of the filed format (HMAC over header and payload) under ``key``."""
    payload = pickle.dumps({"algorithm_state": obj, "state": {}})
    head = json.dumps({"payload_bytes": len(payload), "run_id": None}).encode()
    mac = hmac.new(key, magic + head + b"\n" + payload, hashlib.sha256).hexdigest().encode()
    path.write_bytes(magic + mac + b"\n" + head + b"\n" + payload)


def test_2_an_empty_key_is_refused_and_a_checkpoint_forged_with_it_never_runs(tmp_path, own_key, sentinel,
                                                                             capsys):
    own_key.parent.mkdir()
    own_key.write_bytes(b"")
    os.chmod(own_key, 0o600)
    run = tmp_path / "run"
    run.mkdir()
    marker = tmp_path / "outside" / "code-ran"
    _forge(run / "checkpoint.pkl", b"", _Marker(marker))
    assert main(["optimize", "--resume", str(run)]) == 2
    assert "is empty" in _one_error_line(capsys)
    assert not marker.exists() and _intact(sentinel)


@pytest.mark.parametrize("bad", ["empty", "one byte", "mode 0666", "mode 0640", "symlink", "not hex"])
def test_2_an_unsafe_key_is_refused_in_one_line_before_the_run(tmp_path, own_key, capsys, monkeypatch, bad):
    from mechopt.run import runner

    own_key.parent.mkdir()
    good = os.urandom(32).hex() + "\n"
    text = {"empty": "", "one byte": "ab\n", "not hex": "zz" * 32 + "\n"}.get(bad, good)
    if bad == "symlink":
        real = tmp_path / "real.key"
        real.write_text(good)
        os.chmod(real, 0o600)
        own_key.symlink_to(real)
    else:
        own_key.write_text(text)
        os.chmod(own_key, {"mode 0666": 0o666, "mode 0640": 0o640}.get(bad, 0o600))
    monkeypatch.setattr(runner, "_drive", lambda *a, **k: pytest.fail("evaluated with an unsafe key"))
    assert main([*RUN, "--out", str(tmp_path / "o"), "--checkpoint-every", "1"]) == 2
    assert "checkpoint key" in _one_error_line(capsys)
    assert not (tmp_path / "o").exists()


def test_2_a_key_folder_where_no_key_can_be_made_is_found_before_the_first_evaluation(tmp_path, capsys,
                                                                                       monkeypatch):
    from mechopt.run import runner

    blocker = tmp_path / "a-file"
    blocker.write_text("")
    monkeypatch.setenv("MECHOPT_CONFIG_DIR", str(blocker / "sub"))
    monkeypatch.setattr(runner, "_drive", lambda *a, **k: pytest.fail("evaluated before the key was checked"))
    assert main([*RUN, "--out", str(tmp_path / "o"), "--checkpoint-every", "1"]) == 2
    assert "cannot create the checkpoint key" in _one_error_line(capsys)


def test_2_a_new_key_is_whole_and_private(own_key):
    from mechopt.run import keys

    key = keys.load_key(create=True)
    assert len(key) == 32 and bytes.fromhex(own_key.read_text().strip()) == key
    assert (own_key.stat().st_mode & 0o777) == 0o600
    assert [p.name for p in own_key.parent.iterdir()] == ["checkpoint.key"]  # no temporary left


# ---------------------------------------------------------------- 3. the sweep
def test_3_the_sweep_removes_only_its_own_temporaries(tmp_path, sentinel):
    out = tmp_path / "o"
    (out / "sub").mkdir(parents=True)
    others = [out / ".notes.tmp",  # another program's
              out / ".front.csv.k3j4l5.tmp",  # the filed naming: no run tag, so not provably ours
              out / "sub" / ".front.csv.0123456789abcdef0123.x1y2.tmp"]  # a live run's in a sub-folder
    for p in others:
        p.write_text("live")
    (out / ".staging-foreign").mkdir()
    (sentinel[0].parent / ".data.tmp").write_bytes(b"outside")
    (out / "link").symlink_to(sentinel[0].parent, target_is_directory=True)
    with _io.out_lock(out):
        mine = out / f".front.csv.{_io.run_tag()}.abc.tmp"
        mine.write_text("ours")
        stage = out / f".staging-{_io.run_tag()}-q"
        stage.mkdir()
    assert all(p.read_text() == "live" for p in others)
    assert (out / ".staging-foreign").is_dir()
    assert (sentinel[0].parent / ".data.tmp").read_bytes() == b"outside" and _intact(sentinel)
    assert not mine.exists() and not stage.exists()


def test_3_temporary_names_carry_the_run_tag(tmp_path, monkeypatch):
    monkeypatch.setenv(_io.TAG_ENV, "abc123")
    seen = []
    with _io.atomic_path(tmp_path / "x.csv") as tmp:
        seen.append(tmp.name)
        tmp.write_text("1")
    assert seen[0].startswith(".x.csv.abc123.") and seen[0].endswith(".tmp")


# ---------------------------------------------------------------- 4. shared parent
def test_4_a_failed_run_never_removes_a_parent_folder_another_run_writes_into(tmp_path, sentinel,
                                                                             monkeypatch, capsys):
    """B (--out new/b) creates new/, then fails while A writes new/a: B removes only
    its own empty folder."""
    from mechopt.cli import optimize

    new = tmp_path / "new"
    a_result = new / "a" / "front.csv"

    def b_fails(args):
        a_result.parent.mkdir(parents=True)  # A, started meanwhile
        a_result.write_bytes(sentinel[1])
        raise ValueError("B failed")

    monkeypatch.setattr(optimize, "run", b_fails)
    assert main([*RUN, "--out", str(new / "b")]) == 2
    assert "B failed" in _one_error_line(capsys)
    assert a_result.read_bytes() == sentinel[1] and _intact(sentinel)
    assert not (new / "b").exists()


def test_4_a_failed_run_removes_the_empty_folders_it_made(tmp_path, capsys):
    assert main(["optimize", "wu2008", "--pop", "1", "--out", str(tmp_path / "n1" / "n2")]) == 2
    _one_error_line(capsys)
    assert not (tmp_path / "n1").exists()


# ---------------------------------------------------------------- 5. the race
def test_5_the_loser_of_a_race_on_a_new_folder_leaves_the_winners_folder(tmp_path, sentinel, monkeypatch,
                                                                         capsys):
    import mechopt.cli as cli

    out = tmp_path / "new"
    original = cli._run_locked
    held = []

    def winner_first(args, where):
        out.mkdir()  # the winner makes the folder and takes its lock between our look and our lock
        fd = os.open(out / _io.LOCK_NAME, os.O_RDWR | os.O_CREAT, 0o644)
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        os.write(fd, f"{os.getppid()} elsewhere 0 abc\n".encode())
        held.append(fd)
        (out / "front.csv").write_bytes(sentinel[1])
        return original(args, where)

    monkeypatch.setattr(cli, "_run_locked", winner_first)
    try:
        assert main([*RUN, "--out", str(out)]) == 2
        assert "in use by another mechopt run" in _one_error_line(capsys)
        assert (out / "front.csv").read_bytes() == sentinel[1] and (out / _io.LOCK_NAME).exists()
    finally:
        for fd in held:
            os.close(fd)
    assert _intact(sentinel)


# ---------------------------------------------------------------- 6. stdout
class _BrokenPipe(io.StringIO):
    def write(self, s):
        raise BrokenPipeError(errno.EPIPE, "Broken pipe")


def test_6_results_stay_when_the_final_line_cannot_be_written(tmp_path, monkeypatch, capsys):
    out = tmp_path / "o"
    monkeypatch.setattr(sys, "stdout", _BrokenPipe())
    status = main([*RUN, "--out", str(out)])
    line = _one_error_line(capsys)
    assert status == 2 and "standard output" in line and "in place" in line
    assert json.loads((out / "manifest.json").read_text())["status"] == "complete"
    assert all((out / n).is_file() for n in ("front.csv", "history.csv", "run.json", "front.png"))


def test_6_a_path_the_terminal_cannot_encode_is_escaped_not_fatal(tmp_path, monkeypatch):
    out = tmp_path / "résultats"
    buf = io.BytesIO()
    monkeypatch.setattr(sys, "stdout", io.TextIOWrapper(buf, encoding="ascii"))
    assert main([*RUN, "--out", str(out)]) == 0
    sys.stdout.flush()
    assert b"r\\xe9sultats" in buf.getvalue()
    assert (out / "front.csv").is_file()


# ---------------------------------------------------------------- 7. reproduce --out
@pytest.mark.parametrize("planted", ["README.md", "wu2008/notes.txt"])
def test_7_reproduce_writes_only_into_a_folder_it_may_claim(tmp_path, monkeypatch, planted):
    from mechopt.workflows import reproduce as rep

    out = tmp_path / "home"
    (out / planted).parent.mkdir(parents=True, exist_ok=True)
    (out / planted).write_text("the user's\n")
    monkeypatch.setattr(rep, "_run_units", lambda *a, **k: pytest.fail("ran into a foreign folder"))
    with pytest.raises(ValueError, match="no mechopt run manifest accounts for") as exc:
        rep.reproduce("wu2008", out, quick=True, log=lambda *a: None)
    assert "\n" not in str(exc.value)
    assert (out / planted).read_text() == "the user's\n"


# ---------------------------------------------------------------- 8, 9, 13: report
def _results(tmp_path) -> Path:
    from mechopt.core.published import TABLE_COLUMNS

    d = tmp_path / "results"
    (d / "wu2008").mkdir(parents=True)
    row = {c: "" for c in TABLE_COLUMNS}
    row.update(quantity="k", source="eq. 1", paper=1.0, reproduced=1.0, status="match", kind="computed")
    pd.DataFrame([row]).to_csv(d / "wu2008" / "table.csv", index=False)
    return d


def test_8_report_never_embeds_a_file_outside_the_results_through_a_link(tmp_path, sentinel):
    from mechopt.workflows.report import build_report

    d = _results(tmp_path)
    (d / "wu2008" / "fig1.png").symlink_to(sentinel[0])
    result = _finishes(lambda: build_report(d))
    assert isinstance(result, ValueError) and "symbolic link" in str(result)
    (d / "wu2008" / "fig1.png").unlink()
    (d / "wu2008" / "front").symlink_to(sentinel[0].parent, target_is_directory=True)
    (sentinel[0].parent / "front.png").write_bytes(sentinel[1])
    result = _finishes(lambda: build_report(d))
    assert isinstance(result, ValueError) and "outside" in str(result)


def test_9_report_does_not_hang_on_a_fifo(tmp_path):
    from mechopt.workflows.report import build_report

    d = _results(tmp_path)
    os.mkfifo(d / "wu2008" / "fig1.png")
    result = _finishes(lambda: build_report(d), 10)
    assert isinstance(result, ValueError) and "not a regular file" in str(result)


@pytest.mark.parametrize("gen", [[1], {}, "1e999", None, 3.5, True])
def test_13_report_reads_any_run_json(tmp_path, gen):
    from mechopt.workflows.report import build_report

    d = _results(tmp_path)
    run = d / "wu2008" / "front"
    run.mkdir()
    (run / "front.png").write_bytes(b"\x89PNG\r\n\x1a\n")
    text = json.dumps({"problem": "wu2008", "algorithm": {"name": "nsga2", "pop": 4, "gen": gen}})
    (run / "run.json").write_text(text.replace('"1e999"', "1e999"))
    html = build_report(d)
    assert "Pareto front of problem wu2008" in html or "Convergence" in html


# ---------------------------------------------------------------- 9. FIFOs and giants
def test_9_a_fifo_manifest_or_checkpoint_is_refused_not_read(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    os.mkfifo(out / "manifest.json")
    os.mkfifo(out / "checkpoint.pkl")
    r = _finishes(lambda: _io.read_manifest(out), 10)
    assert isinstance(r, ValueError) and "not a regular file" in str(r)
    r = _finishes(lambda: checkpoint.read(out / "checkpoint.pkl"), 10)
    assert isinstance(r, ValueError) and "not a regular file" in str(r)


def test_9_a_checkpoint_linked_to_a_device_is_refused(tmp_path):
    (tmp_path / "checkpoint.pkl").symlink_to("/dev/zero")
    r = _finishes(lambda: checkpoint.read(tmp_path / "checkpoint.pkl"), 10)
    assert isinstance(r, checkpoint.UnreadableCheckpoint) and "symbolic link" in str(r)


@pytest.mark.parametrize("size", [200 << 20, 20 << 30])
def test_9_an_unauthenticated_checkpoint_is_refused_before_its_payload_is_read(tmp_path, size):
    """A sparse giant behind a plausible first line: only the header is read (peak
    memory far below the file's size), and it fails authentication."""
    import tracemalloc

    path = tmp_path / "checkpoint.pkl"
    with open(path, "wb") as fh:
        fh.write(checkpoint.MAGIC + b"0" * 64 + b"\n" + b'{"payload_bytes": 1}\n')
        fh.truncate(size)
    tracemalloc.start()
    try:
        r = _finishes(lambda: checkpoint.read(path), 20)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert isinstance(r, checkpoint.UnreadableCheckpoint)
    # the header fails its HMAC; a file too large for any payload is refused by its size
    assert ("authentication failed" if size < checkpoint.MAX_PAYLOAD else "larger than") in str(r)
    assert peak < 8 << 20


def test_9_bounded_reads(tmp_path):
    big = tmp_path / "big.json"
    with open(big, "wb") as fh:
        fh.truncate(_io.MAX_JSON_BYTES + 1)
    with pytest.raises(ValueError, match="larger than"):
        _io.read_json(big)
    with pytest.raises(ValueError, match="not a regular file"):
        _io.read_bytes("/dev/zero", 100)
    with pytest.raises(ValueError, match="folder"):
        _io.read_bytes(tmp_path, 100)


# ---------------------------------------------------------------- 10. dask
def test_10_the_dask_timeout_covers_an_endpoint_that_never_answers():
    pytest.importorskip("distributed")
    from mechopt.run.parallel import connect

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    held = []

    def accept():
        while True:
            try:
                held.append(server.accept()[0])
            except OSError:
                return

    threading.Thread(target=accept, daemon=True).start()
    try:
        t0 = time.monotonic()
        r = _finishes(lambda: connect(f"tcp://127.0.0.1:{server.getsockname()[1]}", timeout=1.0), 30)
        assert isinstance(r, ValueError) and "\n" not in str(r)
        assert time.monotonic() - t0 < 10
    finally:
        server.close()
        for c in held:
            c.close()


# ---------------------------------------------------------------- 13. one line
def _deep(n=200_000) -> str:
    return "[" * n + "]" * n


@pytest.mark.parametrize("case", ["256-byte component", "27-digit pid", "deep manifest", "files a list",
                                  "owned a dict", "key not a dict"])
def test_13_one_line_where_a_traceback_was(tmp_path, capsys, case):
    out = tmp_path / "o"
    if case == "256-byte component":
        out = tmp_path / ("x" * 256)
    else:
        out.mkdir()
    manifest = {"kind": "optimize", "key": {}, "status": "running", "run_id": "x"}
    if case == "27-digit pid":
        (out / _io.LOCK_NAME).write_text("1" * 27 + "\n")
    elif case == "deep manifest":
        (out / "manifest.json").write_text(_deep())
    elif case == "files a list":
        (out / "manifest.json").write_text(json.dumps({**manifest, "files": ["front.csv"]}))
    elif case == "owned a dict":
        (out / "manifest.json").write_text(json.dumps({**manifest, "owned": {"a": 1}}))
    elif case == "key not a dict":
        (out / "manifest.json").write_text(json.dumps({**manifest, "key": [1]}))
    status = main([*RUN, "--out", str(out), "--overwrite"])
    if case == "27-digit pid":  # a lock nobody holds: taken over
        assert status == 0 and (out / "front.csv").is_file()
    else:
        assert status == 2
        _one_error_line(capsys)


# ---------------------------------------------------------------- 14. locks
def test_14_a_stale_lock_naming_a_live_process_is_taken_over(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    (out / _io.LOCK_NAME).write_text(f"{os.getppid()}\n")  # alive, but not holding the folder
    with _io.out_lock(out):
        holder = (out / _io.LOCK_NAME).read_text().split()
    assert holder[0] == str(os.getpid()) and holder[1] == socket.gethostname()
    assert not (out / _io.LOCK_NAME).exists()


def test_14_a_lock_held_elsewhere_is_refused_whatever_pid_it_names(tmp_path):
    """A process on another host (a pid that means nothing here) holding the OS lock."""
    out = tmp_path / "o"
    out.mkdir()
    fd = os.open(out / _io.LOCK_NAME, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        os.write(fd, b"999999999 otherhost 0 abc\n")
        with pytest.raises(ValueError, match=r"in use by another mechopt run \(pid 999999999 on otherhost\)"):
            with _io.out_lock(out):
                pass
    finally:
        os.close(fd)
    with _io.out_lock(out):  # released: taken at once
        pass


# ---------------------------------------------------------------- 15. sweep limits
def test_15_a_comma_list_of_weights_has_the_same_limit():
    from mechopt.core import validation as v
    from mechopt.run.runner import parse_weights

    text = ",".join(["0.5"] * (v.MAX_WEIGHTS + 1))
    with pytest.raises(ValueError, match=f"more than {v.MAX_WEIGHTS}"):
        parse_weights(text)
    assert len(parse_weights(",".join(["0.5"] * v.MAX_WEIGHTS))) == v.MAX_WEIGHTS


def test_15_a_sweep_is_budgeted_as_a_whole(monkeypatch):
    """1001 weights of runs of 3000 s each: every run alone is under the hour's
    warning, the sweep (1002 runs, 35 days) is refused before any run."""
    from mechopt.problems import get
    from mechopt.run import budget, runner

    monkeypatch.setattr(budget, "_seconds_per_evaluation", lambda problem: 0.3)
    monkeypatch.setattr(runner, "optimize", lambda *a, **k: pytest.fail("a run started"))
    with pytest.raises(ValueError, match=r"the sweep \(1002 runs\)"):
        runner.sweep(get("wu2008"), runner.parse_weights("0:1:0.001"), pop=100, gen=100,
                     progress=False)


# ---------------------------------------------------------------- 16. garbage
def test_16_a_killed_runs_nested_staging_is_swept_when_its_lock_is_taken_over(tmp_path, sentinel):
    out = tmp_path / "o"
    nested = out / "le2013" / "front" / ".staging-deadbeef-x1"
    nested.mkdir(parents=True)
    (nested / "front.csv").write_text("half")
    tmp = out / "le2013" / ".table.csv.deadbeef.q.tmp"
    tmp.write_text("half")
    other = out / "le2013" / ".staging-cafe-x1"  # another run's: stays
    other.mkdir()
    (out / _io.LOCK_NAME).write_text("123 host 0 deadbeef\n")  # the killed run's lock, nobody holds it
    with _io.out_lock(out):
        assert not nested.exists() and not tmp.exists()
    assert other.is_dir() and _intact(sentinel)


def test_16_a_full_disk_leaves_no_empty_lock(tmp_path, monkeypatch):
    def full(fd, data, offset):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "pwrite", full)
    out = tmp_path / "o"
    out.mkdir()
    with pytest.raises(OSError):
        with _io.out_lock(out):
            pass
    assert not (out / _io.LOCK_NAME).exists()


def test_16_a_refused_out_through_a_link_leaves_no_folder(tmp_path, capsys, monkeypatch):
    deep = tmp_path / "a" / "b"
    deep.mkdir(parents=True)
    (tmp_path / "link").symlink_to(deep, target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    before = sorted(str(p) for p in tmp_path.rglob("*"))
    assert main(["optimize", "wu2008", "--pop", "1", "--out", "link/../x"]) == 2
    _one_error_line(capsys)
    assert sorted(str(p) for p in tmp_path.rglob("*")) == before


def test_16_a_planted_chunk_folder_link_writes_nothing_outside(tmp_path, sentinel):
    from mechopt.run.atlas import _ChunkStore

    out = tmp_path / "o"
    out.mkdir()
    (out / ".atlas_chunks").symlink_to(sentinel[0].parent, target_is_directory=True)
    with pytest.raises(ValueError, match="not a folder of atlas chunks"):
        _ChunkStore(out / ".atlas_chunks", {"step": 0.1})
    assert sorted(p.name for p in sentinel[0].parent.iterdir()) == ["victim.txt"] and _intact(sentinel)


# ---------------------------------------------------------------- 17. lci(nan)
def test_17_five_bar_lci_of_nan_is_nan():
    from mechopt.core import indices
    from mechopt.mechanisms.five_bar import FiveBar

    m = FiveBar(1.0, 1.0, 1.0)
    assert np.isnan(m.lci(np.nan, 1.5)) and np.isnan(m.lci(0.0, np.nan))
    got = m.lci(np.array([0.0, np.nan, np.inf, 50.0]), np.array([1.5, 1.5, 1.5, 0.0]))
    assert np.isnan(got[1]) and got[2] == 0.0 and got[3] == 0.0  # beyond reach stays 0
    # the finite point as the generic index of the Jacobian (an independent path)
    assert got[0] == pytest.approx(float(indices.lci(m.jacobian(0.0, 1.5))), abs=1e-12)


def test_4_a_failed_run_leaves_the_empty_folders_of_a_run_started_inside_its_new_folder(tmp_path):
    """The folder this run made now holds another run (its lock): that run's empty
    staging folder, about to be written, is not removed from under it."""
    start = len(_io.created_folders())
    top = _io.prepare_out_dir(tmp_path / "new" / "b")
    inner = top / "other"
    (inner / ".staging-abc-1").mkdir(parents=True)
    (inner / _io.LOCK_NAME).write_text("1 host 0 abc\n")
    (top / "empty").mkdir()
    _io.remove_created(start)
    assert (inner / ".staging-abc-1").is_dir() and not (top / "empty").exists()
