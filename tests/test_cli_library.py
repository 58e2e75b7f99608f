"""Library habits of the command line: --quiet/--verbose (logging), --json summaries of
optimize, sweep and atlas, MECHOPT_DEBUG/--traceback, and the exit statuses: 0 done,
1 unexpected error (a bug), 2 bad input, 3 runtime failure (the cluster, the disk)."""
import json
import logging

import pandas as pd
import pytest

from mechopt.cli import EXIT_INTERNAL, EXIT_RUNTIME, EXIT_USAGE, main
from mechopt.run.parallel import RunFailure

OPT = ["optimize", "wu2008", "--pop", "6", "--gen", "2", "--n-jobs", "1"]


def test_quiet_drops_progress_verbose_keeps_it(tmp_path, capsys):
    assert main([*OPT, "--out", str(tmp_path / "a")]) == 0
    out, err = capsys.readouterr()
    assert "wu2008 nsga2: 2/2" in err and "designs on the front" in out
    for argv in ([*OPT, "--quiet", "--out", str(tmp_path / "a")], ["-q", *OPT, "--out", str(tmp_path / "a")]):
        assert main(argv) == 0
        out, err = capsys.readouterr()
        assert err == "" and "designs on the front" in out
    assert main([*OPT, "--verbose", "--out", str(tmp_path / "a")]) == 0
    assert "wu2008 nsga2" in capsys.readouterr().err
    assert logging.getLogger("mechopt").level == logging.NOTSET  # put back after the command


def test_json_summaries_agree_with_the_files(tmp_path, capsys):
    assert main([*OPT, "--json", "--out", str(tmp_path / "o")]) == 0
    s = json.loads(capsys.readouterr().out)
    run = json.loads((tmp_path / "o" / "run.json").read_text())
    assert s["n_front"] == len(pd.read_csv(tmp_path / "o" / "front.csv"))
    assert (s["evaluations"], s["settings"], s["infeasible"]) == (run["evaluations"], run["settings"], None)
    assert set(s["files"]) == {"front.csv", "history.csv", "run.json", "front.png"}
    assert main(["sweep", "wu2008", "--weights", "0,1", "--pop", "4", "--gen", "2", "--n-jobs", "1",
                 "--json", "--out", str(tmp_path / "s")]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["weights"] == [0.0, 1.0] and s["feasible_weights"] == len(pd.read_csv(tmp_path / "s" / "sweep.csv"))
    assert main(["atlas", "five-bar", "--step", "0.25", "--no-figures", "--n-jobs", "1", "--json",
                 "--out", str(tmp_path / "at")]) == 0
    out = capsys.readouterr().out
    s = json.loads(out)  # one object, nothing else on stdout
    assert s["n_designs"] == len(pd.read_csv(tmp_path / "at" / "atlas.csv"))
    assert {k: v for k, v in s.items() if k not in ("command", "out")} == \
        json.loads(json.dumps(json.loads((tmp_path / "at" / "atlas.json").read_text())))


def test_bad_input_exit_2_traceback_on_request(tmp_path, capsys, monkeypatch):
    assert main([*OPT, "--pop", "1", "--out", str(tmp_path / "b")]) == EXIT_USAGE
    err = capsys.readouterr().err
    assert err.strip() == "mechopt: error: pop must be at least 2, got 1"
    monkeypatch.setenv("MECHOPT_DEBUG", "1")
    assert main([*OPT, "--pop", "1", "--out", str(tmp_path / "b")]) == EXIT_USAGE
    err = capsys.readouterr().err
    assert err.startswith("Traceback") and err.strip().splitlines()[-1] == "mechopt: error: pop must be at least 2, got 1"


@pytest.mark.parametrize("exc, status, line", [
    (RuntimeError("boom"), EXIT_INTERNAL, "mechopt: internal error: RuntimeError: boom"),
    (RunFailure("no result for 10 s: 0 of 4 work units finished"), EXIT_RUNTIME,
     "mechopt: error: no result for 10 s: 0 of 4 work units finished"),
    (OSError(28, "No space left on device"), EXIT_RUNTIME, "mechopt: error: cannot write in"),
])
def test_runtime_and_internal_failures(tmp_path, capsys, monkeypatch, exc, status, line):
    import mechopt.run.runner as R

    def fail(*a, **k):
        raise exc

    monkeypatch.setattr(R, "optimize", fail)
    assert main([*OPT, "--out", str(tmp_path / "c")]) == status
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and err.startswith(line), err
    assert not (tmp_path / "c").exists()  # nothing left behind
    assert main([*OPT, "--traceback", "--out", str(tmp_path / "c")]) == status
    err = capsys.readouterr().err
    assert err.startswith("Traceback") and f"{type(exc).__name__}" in err
