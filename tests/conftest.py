"""Fixtures shared by several test modules, and the grouping of tests for pytest-xdist.

``quick_reproduction`` runs ``mechopt reproduce all --quick`` once per test session
(the command line, in this process, the papers one after another so that every
figure saved can be inspected and every script's table is kept as it returned it):
``tests/test_reproduce.py`` checks the command's files, ``tests/test_experiment_*.py``,
``tests/test_stan2008_readings.py`` and ``tests/test_liu2006.py`` each script's run inside it (the same
``run(folder, quick=True)`` call as on its own, into the paper's folder), ``tests/test_report.py``
the report of a copy of its wu2008 folder.

Under ``pytest -n 2`` (pytest-xdist) the tests that share a fixture broader than a
function (this session fixture, or a module-scoped one) go to one worker as a group
(:func:`pytest_xdist_make_scheduler`), so that the fixture is computed once (except
the modules of :data:`SPREAD`, whose tests are long beside their fixture, and those of
:data:`SPLIT`, one group per fixture), and so do the tests of :data:`TOGETHER`, which
share a session fixture across modules (``default_run``); every other test is
distributed on its own. The work units start longest first (longest processing time
first: the long tests do not end the run alone on one worker while the other waits),
by the seconds :data:`DURATIONS_FILE` records of their tests (a test it does not list
counts as :data:`UNLISTED_SECONDS`); ``pytest --store-durations`` (with ``-n 2`` or
without) writes that file anew from the run's own test times.
"""
from __future__ import annotations

import importlib
import json
import re
import time
from pathlib import Path
from types import SimpleNamespace

import pytest

#: the group of every test that uses the shared quick reproduction
QUICK_GROUP = "quick_reproduction"
#: modules whose module fixture is cheap beside their long tests (the fuzzers' scratch
#: folder): their tests are spread over the workers, each worker building the fixture.
#: (test_signals is not: its reference runs cost about as much as one of its tests, and
#: a group of a few tests starts before the single tests.)
SPREAD = {"test_fuzz"}
#: modules whose module fixtures serve disjoint sets of tests: one group per word, made
#: of the tests whose id (after the module) contains it, so that the groups (each with
#: the fixture it needs) run side by side; a test with none of the words goes alone.
#: (test_signals: an optimize and an atlas reference, each costing about one of its tests;
#: test_docs: the tiny runs of every command, about 11 s, serve the "..._listed" tests,
#: built once, while the tutorials, each longer than that, go alone)
SPLIT = {"test_signals": ("optimize", "atlas"), "test_docs": ("listed",)}
#: tests of several modules that share a session fixture, one group each (the fixture
#: is then computed once): ``{group: (node id, ...)}``, ids without their parameters
TOGETHER = {
    "le2013_default_runs": ("tests/test_problems.py::test_le_ga_finds_the_best_of_a_dense_scan",
                            "tests/test_problems.py::test_le_relaxed_is_at_least_as_good",
                            "tests/test_convergence.py::test_le_relaxed_default_optimum_is_at_least_the_tied_one"),
    "numpy_atlas": ("tests/test_signals.py::test_atlas_under_a_signal",
                    "tests/test_atlas_resume.py::test_killed_atlas_resumes_to_the_same_table"),
}

#: seconds (setup, call and teardown) of the tests of a measured run that took at least
#: :data:`LISTED_SECONDS`, by node id: the order in which the work units start
DURATIONS_FILE = Path(__file__).with_name("durations.json")
LISTED_SECONDS = 0.5
UNLISTED_SECONDS = 0.1


@pytest.fixture(scope="session")
def quick_reproduction(tmp_path_factory):
    """``SimpleNamespace(out, runs, figures)``: the folder of one quick reproduction of
    all papers; ``runs[paper] = (folder, table, seconds)`` as the paper's
    ``experiments.<paper>.run(folder, quick=True)`` returned it (without the parts
    ``run_part`` writes, ``parts=False``, where the paper has parts) and how long it took;
    ``figures``: every ``(path, matplotlib Figure)`` the run saved."""
    from mechopt.run import io as _io
    from mechopt.workflows import reproduce as rep
    from mechopt.cli import main

    out = tmp_path_factory.mktemp("quick_reproduction")
    figures, runs = [], {}
    save = _io.save_figure

    def capture(fig, path, dpi=120):
        figures.append((str(path), fig))
        return save(fig, path, dpi)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(_io, "save_figure", capture)
        # the papers in this process (not in worker processes), so that the figures
        # and the scripts' own tables are seen here
        mp.setattr(rep, "default_jobs", lambda n: 1)
        for paper in rep.PAPERS:
            module = importlib.import_module(f"mechopt.experiments.{paper}")

            def timed(folder, quick=False, _run=module.run, _paper=paper, **parts):
                t0 = time.perf_counter()
                table = _run(folder, quick=quick, **parts)
                runs[_paper] = (Path(folder), table, time.perf_counter() - t0)
                return table

            mp.setattr(module, "run", timed)
        assert main(["reproduce", "all", "--quick", "--out", str(out)]) == 0
    assert set(runs) == set(rep.PAPERS)
    return SimpleNamespace(out=out, runs=runs, figures=figures)


@pytest.fixture(scope="session")
def default_run():
    """``default_run(name)``: the run of the registered problem ``name`` with its
    default algorithm and sizes, seed 1 (``mechopt.run.runner.optimize``, nothing
    written), made once per session (the same run gives the same front for any
    ``n_jobs``: tests/test_runner.py)."""
    from mechopt.problems import get
    from mechopt.run.runner import optimize

    runs = {}

    def run(name):
        if name not in runs:
            runs[name] = optimize(get(name), seed=1, progress=False, plot=False)
        return runs[name]

    return run


#: the atlas that tests/test_signals.py and tests/test_atlas_resume.py interrupt and resume,
#: on the pure-NumPy path (``MECHOPT_NO_NUMBA=1``: slow enough to be stopped half-way):
#: 344 designs in 22 chunks
NUMPY_ATLAS = ["atlas", "five-bar", "--step", "0.1", "--n-jobs", "2", "--chunk-size", "16", "--no-figures"]


@pytest.fixture(scope="session")
def numpy_atlas_reference(tmp_path_factory):
    """``(atlas.csv, tag)``: :data:`NUMPY_ATLAS` run to its end, uninterrupted, by the
    command line in a process of its own (``MECHOPT_NO_NUMBA=1``), made once per session:
    the reference the interrupted and resumed atlases must equal byte for byte. Every
    process of the run carried ``MECHOPT_TEST_TAG=tag`` (tests/test_signals.py checks
    that none outlived it)."""
    import os
    import subprocess
    import sys
    import uuid

    out = tmp_path_factory.mktemp("numpy_atlas") / "atlas"
    tag = uuid.uuid4().hex
    env = {**os.environ, "MECHOPT_NO_NUMBA": "1", "MECHOPT_TEST_TAG": tag}
    done = subprocess.run([sys.executable, "-m", "mechopt.cli", *NUMPY_ATLAS, "--out", str(out)], env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return out / "atlas.csv", tag


def pytest_configure(config):
    """Compile the numba kernels once, before any worker process starts (in the main
    process of ``pytest -n 2``, or of a plain run): otherwise the two workers, and the
    subprocesses and pools the tests start meanwhile, each compile the same kernels
    (about 11 s of CPU each) until one of them has written numba's cache. Nothing
    when the cache of this state of the sources is complete (a marker file in it)."""
    if hasattr(config, "workerinput"):  # an xdist worker: the main process did it
        return
    import subprocess
    import sys

    from mechopt.core import jit

    if not jit.HAVE_NUMBA:
        return
    marker = jit.cache_dir() / "compiled-by-the-test-suite"
    if marker.exists():
        return
    # in two processes: the disk means and MCI take about as long as the rest
    code = "import sys; from mechopt.mechanisms.five_bar.kernels import compile_all; compile_all(sys.argv[1:])"
    procs = [subprocess.Popen([sys.executable, "-c", code, *groups]) for groups in (["disk"], ["mic", "points"])]
    if any(p.wait() != 0 for p in procs):
        raise RuntimeError("compiling the numba kernels failed (see above)")
    marker.parent.mkdir(parents=True, exist_ok=True)
    marker.touch()


def pytest_addoption(parser):
    parser.addoption("--store-durations", action="store_true", default=False,
                     help=f"write the seconds of every test of this run that took at least {LISTED_SECONDS} s "
                          f"to tests/{DURATIONS_FILE.name} (the order in which pytest -n N starts them)")


_measured: dict = {}


def pytest_runtest_logreport(report):
    """Sum each test's setup, call and teardown seconds (for ``--store-durations``)."""
    _measured[report.nodeid] = _measured.get(report.nodeid, 0.0) + report.duration


def pytest_sessionfinish(session):
    """``--store-durations``: write :data:`DURATIONS_FILE` (in the main process)."""
    config = session.config
    if hasattr(config, "workerinput") or not config.getoption("store_durations"):
        return
    kept = {k: round(v, 2) for k, v in sorted(_measured.items(), key=lambda kv: -kv[1]) if v >= LISTED_SECONDS}
    tmp = DURATIONS_FILE.with_suffix(".tmp")
    tmp.write_text(json.dumps(kept, indent=0) + "\n")
    tmp.replace(DURATIONS_FILE)


def durations() -> dict:
    """``{node id: seconds}`` of :data:`DURATIONS_FILE` (empty if it is missing or unreadable)."""
    try:
        return {str(k): float(v) for k, v in json.loads(DURATIONS_FILE.read_text()).items()}
    except (OSError, ValueError, AttributeError):
        return {}


def _groups():
    """``{module: scope}`` of the test modules whose tests go to one worker together:
    those that use the quick reproduction (one scope for all of them) and those with a
    module-scoped fixture (a scope each), read from the sources."""
    out = {}
    for path in sorted(Path(__file__).parent.glob("test_*.py")):
        text = path.read_text(errors="replace")
        if "quick_reproduction" in text:
            out[path.stem] = QUICK_GROUP
        elif path.stem not in SPREAD and re.search(r"scope\s*=\s*[\"'](module|package|session)[\"']", text):
            out[path.stem] = path.stem
    return out


def scope_of(nodeid: str, groups: dict) -> str:
    """The xdist work unit of a test: its group (``groups``, or an ``@name`` suffix of
    ``--dist loadgroup``), else the test alone."""
    if nodeid.rfind("@") > nodeid.rfind("]"):
        return nodeid.split("@")[-1]
    bare = nodeid.split("[", 1)[0]
    group = next((g for g, ids in TOGETHER.items() if bare in ids), None)
    if group is not None:
        return group
    module = Path(nodeid.split("::", 1)[0]).stem
    if module in SPLIT:
        name = nodeid.split("::", 1)[-1]
        return next((f"{module}:{word}" for word in SPLIT[module] if word in name), nodeid)
    return groups.get(module, nodeid)


try:  # the scheduler hook exists only with pytest-xdist
    import xdist  # noqa: F401
except ImportError:  # pragma: no cover
    pass
else:
    def pytest_xdist_make_scheduler(config, log):
        """``-n N`` (``--dist load`` or ``loadgroup``): xdist's load-scope scheduling over
        the work units of :func:`scope_of` (largest first). xdist's own ``loadgroup``
        reads an ``@group`` suffix that it appends to the node ids, which pytest 9 no
        longer lets a plugin change, so the groups are formed here."""
        if config.getvalue("dist") not in ("load", "loadgroup"):
            return None
        from xdist.scheduler import LoadScopeScheduling

        groups = _groups()
        seconds = durations()

        class GroupScheduling(LoadScopeScheduling):
            _ordered = False

            def _split_scope(self, nodeid):
                return scope_of(nodeid, groups)

            def _assign_work_unit(self, node):
                # the first assignment comes after the whole queue is built: order it
                # once, longest unit first (a stable sort: equal units keep their order)
                if not self._ordered:
                    self._ordered = True
                    cost = {scope: sum(seconds.get(n, UNLISTED_SECONDS) for n in unit)
                            for scope, unit in self.workqueue.items()}
                    for scope in sorted(self.workqueue, key=lambda s: -cost[s]):
                        self.workqueue.move_to_end(scope)
                super()._assign_work_unit(node)

        return GroupScheduling(config, log)

