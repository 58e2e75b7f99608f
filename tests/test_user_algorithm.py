"""Issue 12, part 5: the user's pymoo algorithm and termination, operator settings on
the command line, steppable checkpoints, and the automatic number of processes."""
import json
import pickle

import numpy as np
import pytest
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.operators.crossover.sbx import SBX
from pymoo.operators.mutation.pm import PM
from pymoo.termination.default import DefaultMultiObjectiveTermination

from mechopt.cli import main
from mechopt.problems import get
from mechopt.run.runner import CHECKPOINT, _front_table, make_algorithm, optimize, resume

PROBLEM = "stan2008-bipod"  # cheap, two objectives


def _nsga2():
    return NSGA2(pop_size=10, crossover=SBX(prob=0.8, eta=10), mutation=PM(prob=0.7, eta=25))


def test_user_algorithm_same_seed_same_front_bytes(tmp_path):
    algo = _nsga2()
    a = optimize(get(PROBLEM), algo, gen=4, seed=3, n_jobs=1, out=tmp_path / "a", progress=False, plot=False)
    b = optimize(get(PROBLEM), algo, gen=4, seed=3, n_jobs=1, out=tmp_path / "b", progress=False, plot=False)
    assert (tmp_path / "a" / "front.csv").read_bytes() == (tmp_path / "b" / "front.csv").read_bytes()
    assert len(a.front) > 1 and a.info["evaluations"] == 40
    assert algo.problem is None and not algo.is_initialized  # the caller's object is not run
    c = optimize(get(PROBLEM), algo, gen=4, seed=4, n_jobs=1, out=tmp_path / "c", progress=False, plot=False)
    assert (tmp_path / "c" / "front.csv").read_bytes() != (tmp_path / "a" / "front.csv").read_bytes()
    # and through two processes: the same bytes
    optimize(get(PROBLEM), algo, gen=4, seed=3, n_jobs=2, out=tmp_path / "d", progress=False, plot=False)
    assert (tmp_path / "d" / "front.csv").read_bytes() == (tmp_path / "a" / "front.csv").read_bytes()
    info = json.loads((tmp_path / "a" / "run.json").read_text())
    assert info["algorithm"] == {"name": "NSGA2", "pop": 10, "gen": 4}
    s = info["algorithm_settings"]
    assert s["class"] == "NSGA2" and s["pop_size"] == 10
    assert s["crossover"]["class"] == "SBX" and s["crossover"]["prob"] == 0.8 and s["crossover"]["eta"] == 10
    assert s["mutation"]["class"] == "PM" and s["mutation"]["prob"] == 0.7 and s["mutation"]["eta"] == 25
    assert info["termination"] == {"class": "MaximumGenerationTermination", "n_max_gen": 4}


def test_named_algorithm_equals_the_same_object():
    """``"nsga2"`` with pop 10 is pymoo's NSGA2(pop_size=10): the same front."""
    named = optimize(get(PROBLEM), "nsga2", pop=10, gen=3, seed=2, n_jobs=1, progress=False, plot=False)
    obj = optimize(get(PROBLEM), NSGA2(pop_size=10), gen=3, seed=2, n_jobs=1, progress=False, plot=False)
    assert named.front.equals(obj.front)


@pytest.mark.parametrize("termination, generations", [
    (("n_gen", 3), 3),
    (("n_eval", 25), 3),  # 10 per generation: stops once 25 are exceeded
    (DefaultMultiObjectiveTermination(ftol=0.5, n_max_gen=40, period=2, n_skip=0), None),
])
def test_termination_objects_and_tuples(termination, generations):
    res = optimize(get(PROBLEM), _nsga2(), termination=termination, seed=1, n_jobs=1, progress=False,
                   plot=False)
    assert len(res.front)
    if generations is not None:
        assert res.info["generations"] == generations
    else:  # the tolerance stops it well before its maximum of 40
        assert 2 <= res.info["generations"] < 40
        assert res.info["termination"]["class"] == "DefaultMultiObjectiveTermination"
        assert res.info["termination"]["ftol"] == 0.5 and res.info["termination"]["n_max_gen"] == 40
    assert len(res.history) == res.info["generations"]


def test_termination_object_is_not_consumed():
    term = DefaultMultiObjectiveTermination(ftol=0.5, n_max_gen=40, period=2, n_skip=0)
    a = optimize(get(PROBLEM), _nsga2(), termination=term, seed=1, n_jobs=1, progress=False, plot=False)
    b = optimize(get(PROBLEM), _nsga2(), termination=term, seed=1, n_jobs=1, progress=False, plot=False)
    assert a.front.equals(b.front) and a.info["generations"] == b.info["generations"]


def test_tol_uses_pymoo_default_termination_with_gen_as_maximum():
    res = optimize(get(PROBLEM), pop=10, gen=5, tol=1e-12, seed=1, n_jobs=1, progress=False, plot=False)
    assert res.info["generations"] == 5  # the tolerance is never met: gen is the maximum
    assert res.info["termination"]["ftol"] == 1e-12 and res.info["termination"]["n_max_gen"] == 5
    assert res.info["algorithm"]["gen"] == 5


@pytest.mark.parametrize("kwargs, message", [
    (dict(termination=("n_gen", 3), gen=3), "not both"),
    (dict(termination=("nope", 3)), "not a pymoo termination"),
    (dict(termination=5), "termination must be"),
    (dict(tol=0.0), "tol must be a positive"),
    (dict(tol=float("nan")), "tol must be finite"),
    (dict(crossover_prob=1.5), "crossover_prob must lie in"),
    (dict(mutation_prob=-0.1), "mutation_prob must lie in"),
    (dict(mutation_eta=0), "mutation_eta must be a positive"),
    (dict(algorithm=NSGA2(pop_size=4), pop=8), "set them on the algorithm object"),
    (dict(algorithm=NSGA2(pop_size=4), crossover_prob=0.5), "set them on the algorithm object"),
    (dict(algorithm=object()), "or a pymoo algorithm object"),
    (dict(algorithm="de"), "needs a single objective"),
])
def test_bad_algorithm_or_termination(kwargs, message):
    with pytest.raises(ValueError, match=message):
        optimize(get(PROBLEM), **{"seed": 1, "n_jobs": 1, "progress": False, "plot": False, **kwargs})


def test_used_algorithm_object_is_refused():
    algo = NSGA2(pop_size=4)
    algo.setup(get(PROBLEM), termination=("n_gen", 1), seed=1)
    with pytest.raises(ValueError, match="already been set up"):
        optimize(get(PROBLEM), algo, gen=1, progress=False, plot=False)


def test_shared_pymoo_defaults_are_not_changed():
    """pymoo's default operators are shared by every NSGA2(): settings make new ones."""
    make_algorithm("nsga2", 10, 2, crossover_prob=0.3, mutation_prob=0.2)
    fresh = NSGA2(pop_size=10)
    assert fresh.mating.crossover.prob.value == 0.9 and fresh.mating.mutation.prob.value == 0.9


def test_checkpoint_is_steppable_with_next(tmp_path):
    """The saved algorithm continues with ``next()`` alone to the uninterrupted front."""
    ref = optimize(get(PROBLEM), _nsga2(), gen=6, seed=7, n_jobs=1, progress=False, plot=False)

    p = get(PROBLEM)
    from mechopt.run.runner import _save_checkpoint

    algo = _nsga2()
    algo.setup(p, termination=("n_gen", 6), seed=7, verbose=False)
    for _ in range(2):
        algo.next()
    state = {"algorithm": "NSGA2", "pop": 10, "gen": 6, "seed": 7, "rows": [], "elapsed": 0.0,
             "checkpoint_every": 1}
    _save_checkpoint(algo, state, tmp_path)
    from mechopt.run import checkpoint

    loaded = checkpoint.read(tmp_path / CHECKPOINT)[1]["algorithm_state"]  # authenticated, then loaded
    assert loaded.callback is not None and loaded.display is not None
    while loaded.has_next():
        loaded.next()
    res = loaded.result()
    X = res.opt.get("X")[res.opt.get("FEAS")[:, 0]]
    assert _front_table(loaded.problem, X).equals(ref.front)


def test_checkpoint_written_by_a_run_resumes_and_steps(tmp_path):
    """A checkpoint written by ``optimize(checkpoint_every=...)`` of a user's algorithm:
    resumed by :func:`resume` and stepped by hand, both reach the uninterrupted front."""
    import shutil

    import mechopt.run.runner as R

    ref = optimize(get(PROBLEM), _nsga2(), gen=5, seed=11, n_jobs=1, out=tmp_path / "ref", progress=False,
                   plot=False)
    calls = []
    real = R._save_checkpoint

    def stop_after_second(algo, state, out):  # "killed" right after the checkpoint of generation 2
        real(algo, state, out)
        calls.append(algo.n_gen)
        if len(calls) == 2:
            shutil.copy(out / CHECKPOINT, tmp_path / "saved.pkl")
            raise KeyboardInterrupt

    R._save_checkpoint = stop_after_second
    try:
        with pytest.raises(KeyboardInterrupt):
            optimize(get(PROBLEM), _nsga2(), gen=5, seed=11, n_jobs=1, out=tmp_path / "run",
                     checkpoint_every=1, progress=False, plot=False)
    finally:
        R._save_checkpoint = real
    from mechopt.run import checkpoint

    loaded = checkpoint.read(tmp_path / "saved.pkl")[1]["algorithm_state"]
    while loaded.has_next():
        loaded.next()
    X = loaded.result().opt.get("X")
    assert _front_table(loaded.problem, X).equals(ref.front)
    res = resume(tmp_path / "run", progress=False, plot=False)
    assert (tmp_path / "run" / "front.csv").read_bytes() == (tmp_path / "ref" / "front.csv").read_bytes()
    assert res.info["algorithm_settings"] == ref.info["algorithm_settings"]
    hist = (tmp_path / "run" / "history.csv").read_text().splitlines()
    assert hist == (tmp_path / "ref" / "history.csv").read_text().splitlines()


def test_cli_operator_settings_and_tol_reach_the_algorithm(tmp_path):
    out = tmp_path / "run"
    assert main(["optimize", PROBLEM, "--pop", "8", "--gen", "4", "--crossover-prob", "0.65",
                 "--mutation-prob", "0.35", "--crossover-eta", "12", "--mutation-eta", "30",
                 "--tol", "0.002", "--out", str(out)]) == 0
    info = json.loads((out / "run.json").read_text())
    s = info["algorithm_settings"]
    assert s["class"] == "NSGA2" and s["pop_size"] == 8
    assert s["crossover"] == {**s["crossover"], "class": "SBX", "prob": 0.65, "eta": 12.0}
    assert s["mutation"] == {**s["mutation"], "class": "PM", "prob": 0.35, "eta": 30.0}
    t = info["termination"]
    assert t["class"] == "DefaultMultiObjectiveTermination" and t["ftol"] == 0.002 and t["n_max_gen"] == 4
    assert info["n_jobs_auto"] is True and info["n_jobs"] == 1  # a cheap problem: one process


def test_cli_operator_settings_for_ga_and_de(tmp_path):
    for alg, cls in (("ga", "GA"), ("de", "DE")):
        out = tmp_path / alg
        assert main(["optimize", "le2013", "--algorithm", alg, "--pop", "6", "--gen", "2",
                     "--crossover-prob", "0.55", "--mutation-prob", "0.25", "--n-jobs", "1",
                     "--out", str(out)]) == 0
        s = json.loads((out / "run.json").read_text())["algorithm_settings"]
        assert s["class"] == cls
        if alg == "ga":
            assert s["crossover"]["prob"] == 0.55 and s["mutation"]["prob"] == 0.25
        else:  # DE: the crossover rate CR and its polynomial mutation
            assert s["mating"]["CR"] == 0.55 and s["mating"]["mutation"]["prob"] == 0.25


@pytest.mark.parametrize("argv, message", [
    (["--crossover-prob", "2"], "crossover_prob must lie in [0, 1]"),
    (["--mutation-prob", "x"], "invalid float value"),
    (["--tol", "-1"], "tol must be a positive number"),
])
def test_cli_bad_settings_exit_2(tmp_path, capsys, argv, message):
    out = tmp_path / "never"
    assert main(["optimize", PROBLEM, *argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err
    assert not out.exists()


def test_sweep_passes_the_settings(tmp_path):
    assert main(["sweep", PROBLEM, "--weights", "0,1", "--pop", "6", "--gen", "2", "--crossover-prob", "0.7",
                 "--out", str(tmp_path / "s")]) == 0
    info = json.loads((tmp_path / "s" / "run.json").read_text())
    assert info["algorithm_settings"]["crossover"]["prob"] == 0.7


def test_n_jobs_auto_measures_and_records(monkeypatch):
    import mechopt.run.runner as R

    cheap = optimize(get(PROBLEM), pop=6, gen=3, seed=1, progress=False, plot=False)
    assert cheap.info["n_jobs"] == 1 and cheap.info["n_jobs_auto"] is True
    assert 0 < cheap.info["seconds_per_generation"] < R.PARALLEL_SECONDS
    monkeypatch.setattr(R, "PARALLEL_SECONDS", 0.0)  # every problem "slow": two processes
    slow = optimize(get(PROBLEM), pop=6, gen=3, seed=1, progress=False, plot=False)
    assert slow.info["n_jobs"] == 2 and slow.front.equals(cheap.front)
    fixed = optimize(get(PROBLEM), pop=6, gen=3, seed=1, n_jobs=1, progress=False, plot=False)
    assert fixed.info["n_jobs"] == 1 and fixed.info["n_jobs_auto"] is False
    assert "seconds_per_generation" not in fixed.info


def test_history_hypervolume_is_normalised_and_comparable():
    """The reference point no longer comes from the first population: the same front
    has the same hypervolume in any run, and it lies in [0, 1.1^2]."""
    p = get(PROBLEM)
    res = optimize(p, pop=10, gen=5, seed=1, n_jobs=1, progress=False, plot=False)
    hv = res.history["hypervolume"].to_numpy()
    assert np.all((hv > 0) & (hv <= 1.1 ** 2))
    F = np.column_stack([ob.sense * res.front[ob.name].to_numpy(float) for ob in p.objectives])
    assert hv[-1] == pytest.approx(p.hypervolume(F), rel=1e-12)
    other = optimize(p, pop=10, gen=5, seed=2, n_jobs=1, progress=False, plot=False)
    F2 = np.column_stack([ob.sense * other.front[ob.name].to_numpy(float) for ob in p.objectives])
    assert other.history["hypervolume"].iloc[-1] == pytest.approx(p.hypervolume(F2), rel=1e-12)
    # the ideal point (every objective at its best bound) has the whole box: 1.1^2
    best = np.array([[-p.objectives[0].bounds[1], -p.objectives[1].bounds[1]]])
    assert p.hypervolume(best) == pytest.approx(1.1 ** 2)
