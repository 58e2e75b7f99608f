"""A killed atlas resumes by skipping the chunks it had finished: same table, no duplicates."""
import os
import signal
import subprocess
import sys
import time

import pandas as pd
import pytest

from mechopt.cli import main

# 344 designs in 22 chunks, one after another (about 0.1 s each on the NumPy path)
ARGS = ["atlas", "five-bar", "--step", "0.1", "--n-jobs", "1", "--chunk-size", "16", "--no-figures"]


def _run(out, env):
    return subprocess.Popen([sys.executable, "-m", "mechopt.cli", *ARGS, "--out", str(out)], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


@pytest.mark.skipif(os.name != "posix", reason="SIGKILL")
def test_killed_atlas_resumes_to_the_same_table(tmp_path, numpy_atlas_reference):
    # the pure-NumPy path is slow enough to be killed half-way, and both runs use it; the
    # uninterrupted reference is the session's (tests/conftest.py: the same atlas on two
    # worker processes, which test_signals interrupts too; the table does not depend on
    # the workers, so the resumed one-process run must equal it byte for byte)
    env = {**os.environ, "MECHOPT_NO_NUMBA": "1"}
    ref, run = numpy_atlas_reference[0], tmp_path / "run"
    proc = _run(run, env)
    try:
        chunks = run / ".atlas_chunks"
        deadline = time.time() + 300
        while len(list(chunks.glob("chunk_*.npz"))) < 3:
            assert proc.poll() is None, "the atlas finished before it could be killed"
            assert time.time() < deadline
            time.sleep(0.05)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    finally:
        if proc.poll() is None:  # a failed check above
            proc.kill()
            proc.wait()
    saved = len(list(chunks.glob("chunk_*.npz")))
    assert not (run / "atlas.csv").exists()
    assert _run(run, env).wait() == 0
    assert (run / "atlas.csv").read_bytes() == ref.read_bytes()
    table = pd.read_csv(run / "atlas.csv")
    assert not table.duplicated(["r1", "r2", "r3"]).any()
    assert not chunks.exists() and saved >= 3


def test_chunks_of_other_settings_are_refused(tmp_path, capsys):
    out = tmp_path / "a"
    (out / ".atlas_chunks").mkdir(parents=True)
    (out / ".atlas_chunks" / "settings.json").write_text('{"step": 0.5}')
    assert main(["atlas", "five-bar", "--step", "0.1", "--no-figures", "--out", str(out)]) == 2
    assert "holds chunks of an atlas with other settings" in capsys.readouterr().err
