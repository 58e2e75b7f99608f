"""The seeded runner: files written, determinism across runs, n_jobs and backends."""
import json

import numpy as np
import pandas as pd
import pytest

from mechopt.cli import main
from mechopt.problems import get
from mechopt.run.runner import optimize, parse_weights, sweep

SMALL = dict(pop=8, gen=2, seed=1)


def _run(tmp_path, name, problem="liu2006-w-gci", **kw):
    out = tmp_path / name
    optimize(get(problem), out=out, progress=False, **{**SMALL, **kw})
    return out


def test_run_folder_contents(tmp_path):
    out = _run(tmp_path, "a", n_jobs=1)
    assert {p.name for p in out.iterdir()} == {"front.csv", "history.csv", "run.json", "front.png",
                                              "manifest.json"}
    import hashlib
    import json

    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["status"] == "complete" and manifest["kind"] == "optimize"
    assert manifest["files"] == {n: hashlib.sha256((out / n).read_bytes()).hexdigest()
                                 for n in ("front.csv", "history.csv", "run.json", "front.png")}
    front = pd.read_csv(out / "front.csv")
    for col in ("r1", "r3", "r_mic", "gci", "g_r_mic_min", "g_gci_min", "gvi_max", "r2"):
        assert col in front.columns
    assert (front[[c for c in front.columns if c.startswith("g_")]] <= 0).all().all()
    hist = pd.read_csv(out / "history.csv")
    assert list(hist["generation"]) == [1, 2]
    assert {"evaluations", "best_r_mic", "best_gci", "hypervolume"} <= set(hist.columns)
    assert hist["hypervolume"].is_monotonic_increasing
    info = json.loads((out / "run.json").read_text())
    assert info["seed"] == 1 and info["algorithm"] == {"name": "nsga2", "pop": 8, "gen": 2}
    assert set(info["versions"]) == {"mechopt", "pymoo", "numpy"} and info["wall_time_s"] > 0


def test_same_seed_same_bytes_for_any_n_jobs(tmp_path):
    a = (_run(tmp_path, "a", n_jobs=1) / "front.csv").read_bytes()
    b = (_run(tmp_path, "b", n_jobs=1) / "front.csv").read_bytes()
    c = (_run(tmp_path, "c", n_jobs=2) / "front.csv").read_bytes()
    assert a == b == c
    d = (_run(tmp_path, "d", n_jobs=2, seed=2) / "front.csv").read_bytes()
    assert d != a  # the seed matters


def test_dask_local_cluster_gives_the_same_front(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    ref = (_run(tmp_path, "ref", n_jobs=1) / "front.csv").read_bytes()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        code = main(["optimize", "liu2006-w-gci", "--pop", "8", "--gen", "2", "--seed", "1",
                     "--dask", cluster.scheduler_address, "--out", str(tmp_path / "dask")])
    assert code == 0
    assert (tmp_path / "dask" / "front.csv").read_bytes() == ref
    assert json.loads((tmp_path / "dask" / "run.json").read_text())["backend"] == "dask"


def test_ga_path_single_objective(tmp_path):
    out = _run(tmp_path, "le", problem="le2013", pop=4, gen=2)
    front = pd.read_csv(out / "front.csv")
    assert len(front) == 1 and {"rho", "a_max", "r_mic", "l0", "lci_min"} <= set(front.columns)
    assert front["lci_min"].iloc[0] >= 0.5 - 1e-9
    assert front["l0"].iloc[0] == pytest.approx(np.sqrt(2) / 2 * (front["rho"].iloc[0] - 1))


@pytest.mark.parametrize("text, expected", [("0:1:0.25", [0, 0.25, 0.5, 0.75, 1.0]),
                                             ("0.2,0.8", [0.2, 0.8]), ("0:1:0.1", np.arange(11) / 10)])
def test_parse_weights(text, expected):
    assert np.allclose(parse_weights(text), expected)


@pytest.mark.parametrize("text", ["0:2:0.5", "-0.1,0.5", "a:b:c", "1:0:0.1", "0:1:0", "", "nan"])
def test_parse_weights_rejects(text):
    with pytest.raises(ValueError, match="weights"):
        parse_weights(text)


def test_sweep_writes_table_and_plot(tmp_path):
    table = sweep(get("le2013-gamma"), parse_weights("0,0.5,1"), pop=6, gen=2, seed=1, n_jobs=2,
                  out=tmp_path / "s", progress=False)
    assert list(table["weight"]) == [0.0, 0.5, 1.0]
    assert {"rho", "gamma", "a_max", "z"} <= set(table.columns)
    assert {p.name for p in (tmp_path / "s").iterdir()} >= {"sweep.csv", "sweep.png", "front.csv"}
    # w = 1 weighs only the square side, w = 0 only gamma
    assert table["a_max"].iloc[-1] >= table["a_max"].iloc[0]
    assert table["gamma"].iloc[0] >= table["gamma"].iloc[-1]


@pytest.mark.parametrize("argv, message", [
    (["optimize", "nope", "--out", "{out}"], "problem must be one of"),
    (["optimize", "le2013", "--algorithm", "cmaes", "--out", "{out}"], "algorithm must be one of"),
    (["optimize", "le2013", "--pop", "1", "--out", "{out}"], "pop must be at least 2"),
    (["optimize", "le2013", "--gen", "0", "--out", "{out}"], "gen must be at least 1"),
    (["optimize", "liu2006-many", "--algorithm", "ga", "--out", "{out}"], "needs a single objective"),
    (["sweep", "le2013-gamma", "--weights", "0:1.5:0.5", "--out", "{out}"], "weights must lie in [0, 1]"),
    (["sweep", "le2013", "--out", "{out}"], "needs a 2-objective problem"),
    (["optimize", "le2013", "--pop", "x", "--out", "{out}"], "invalid int value"),
])
def test_bad_input_exit_2_nothing_written(tmp_path, capsys, argv, message):
    out = tmp_path / "never"
    assert main([a.replace("{out}", str(out)) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err
    assert not out.exists()


def test_unwritable_out(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["optimize", "le2013", "--out", str(blocker / "sub")]) == 2
    assert "not writable" in capsys.readouterr().err


@pytest.mark.parametrize("argv", [["optimize", "le2013"], ["sweep", "le2013"],
                                  ["design", "five-bar", "--task", "rect:100,60@0,250"]])
def test_unreachable_scheduler(argv, tmp_path, capsys, monkeypatch):
    # --dask-timeout: the default 10 s would be waited out in full (nothing listens on port 9)
    pytest.importorskip("dask.distributed")
    from mechopt.run import parallel

    timeouts = []

    def connect(address, timeout=10.0):  # the real one, seeing the timeout it is given
        timeouts.append(timeout)
        return real(address, timeout)

    real = parallel.connect
    monkeypatch.setattr(parallel, "connect", connect)
    assert main([*argv, "--dask", "tcp://127.0.0.1:9", "--dask-timeout", "0.5", "--out", str(tmp_path / "o")]) == 3  # a runtime failure
    err = capsys.readouterr().err
    assert "cannot reach the Dask scheduler" in err and err.count("\n") == 1
    assert not (tmp_path / "o").exists()
    assert timeouts == [0.5]
