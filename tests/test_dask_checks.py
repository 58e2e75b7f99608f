"""A Dask run cannot hang: a cluster without workers, or whose worker cannot import
mechopt, ends with one line within the timeout (exit 3, a runtime failure); a run that loses its
cluster mid-way keeps its finished chunks."""
import subprocess
import sys
import textwrap
import time

import pytest

distributed = pytest.importorskip("dask.distributed")

from mechopt.cli import main  # noqa: E402

ATLAS = ["atlas", "five-bar", "--step", "0.1", "--no-figures", "--dask-timeout", "3"]


def test_cluster_without_workers(tmp_path, capsys):
    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        t0 = time.monotonic()
        assert main([*ATLAS, "--dask", cluster.scheduler_address, "--out", str(tmp_path / "a")]) == 3  # a runtime failure
        assert time.monotonic() - t0 < 30
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "no workers" in err


BLOCK = textwrap.dedent('''
    """Dask worker preload: this worker cannot import mechopt."""
    import sys

    class _Block:
        def find_spec(self, name, path=None, target=None):
            if name == "mechopt" or name.startswith("mechopt."):
                raise ModuleNotFoundError(f"No module named {name!r}")
            return None

    for key in [k for k in sys.modules if k == "mechopt" or k.startswith("mechopt.")]:
        del sys.modules[key]
    sys.meta_path.insert(0, _Block())
''')


def test_worker_without_mechopt(tmp_path, capsys):
    pre = tmp_path / "no_mechopt.py"
    pre.write_text(BLOCK)
    with distributed.LocalCluster(n_workers=0, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        worker = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", cluster.scheduler_address,
             "--nworkers", "1", "--nthreads", "1", "--no-dashboard", "--preload", str(pre)],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            out = tmp_path / "b"
            assert main([*ATLAS, "--dask", cluster.scheduler_address, "--dask-timeout", "30",
                         "--out", str(out)]) == 3  # a runtime failure
        finally:
            worker.terminate()
            worker.wait(30)
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "cannot run mechopt" in err, err
    assert not (out / "atlas.csv").exists()
