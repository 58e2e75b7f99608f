"""pymoo's conventions on mechopt's problems: ``name()``, ``pareto_front()`` (the
brute-force front; the default run within IGD+ 0.01 of it), pymoo's parallelisation
(``elementwise_runner``: used, or refused with a warning naming ``use_parallel``),
``optimize(callback=)`` and pymoo's ``Result``; ``mechopt.evaluate`` of a gantry made
by its own constructor."""
from __future__ import annotations

import itertools
import json
import warnings
from multiprocessing.pool import ThreadPool

import numpy as np
import pytest
from pymoo.core.callback import Callback
from pymoo.core.problem import Problem
from pymoo.parallelization import StarmapParallelization
from pymoo.core.result import Result

import mechopt
from mechopt.problems import get, names
from mechopt.run.runner import optimize


# --- name() -----------------------------------------------------------------------
@pytest.mark.parametrize("name", names())
def test_name_is_callable_and_a_string(name):
    p = get(name)
    assert p.name() == name and p.name == name and isinstance(p.name, str)
    assert json.loads(json.dumps({"problem": p.name})) == {"problem": name}
    # pymoo's own printing calls self.name()
    assert Problem.__str__(p).startswith(f"# name: {name}\n")


def test_weighted_sum_name_is_callable():
    from mechopt.run.weighted import WeightedSum

    w = WeightedSum(get("stan2008-bipod"), 0.25)
    assert w.name() == "stan2008-bipod-w0.25" == w.name


# --- pareto_front() ---------------------------------------------------------------
def test_pareto_front_none_beyond_two_variables():
    p = get("le2013-gamma-relaxed")
    assert p.n_var == 3 and p.pareto_front() is None


def test_pareto_front_of_the_bipod_against_the_mechanism_and_the_default_run():
    """The brute-force front (computed on demand) is non-dominated, is reproduced by an
    independent per-design lattice of :class:`mechopt.Bipod` (its own area and GTQI
    methods), and the default run lies within IGD+ 0.01 of it."""
    from pymoo.indicators.igd_plus import IGDPlus

    p = get("stan2008-bipod")
    pf = p.pareto_front()
    assert pf.shape[1] == 2 and len(pf) > 50
    assert pf is p.pareto_front()  # kept by the instance (pymoo's cache)
    # no point dominates another (pairwise, in minimisation form)
    le = np.all(pf[:, None, :] <= pf[None, :, :], axis=2) & np.any(pf[:, None, :] < pf[None, :, :], axis=2)
    assert not le.any()
    # an independent lattice of the mechanism: every one of its designs is weakly
    # dominated by the front within a small tolerance (the front is not beaten)
    us = np.linspace(p.xl[0], p.xu[0], 97)
    F = np.array([[-m.workspace_area(), -m.gtqi()] for m in (mechopt.Bipod(1.0, u, 1.6 * u) for u in us)])
    span = np.ptp(pf, axis=0)
    gap = np.min(np.max((pf[None, :, :] - F[:, None, :]) / span, axis=2), axis=1)
    assert gap.max() < 2e-3, gap.max()
    run = optimize(p, seed=1, n_jobs=1, progress=False, plot=False)
    Frun = p.natural(run.result.F) * -1  # back to minimisation form: the identity of natural()
    np.testing.assert_array_equal(Frun, run.result.F)
    ideal, span = pf.min(axis=0), np.ptp(pf, axis=0)
    igd = IGDPlus((pf - ideal) / span)((run.result.F - ideal) / span)
    assert igd < 0.01, igd
    print(f"stan2008-bipod: IGD+ of the default run against pareto_front() {igd:.5f} ({len(pf)} points)")


def test_natural_is_the_sign_of_each_objective():
    p = get("wu2008")  # k_av maximised, l minimised
    F = np.array([[-1.5, 600.0]])
    assert p.natural(F).tolist() == [[1.5, 600.0]]


# --- pymoo's parallelisation -------------------------------------------------------
class _Counting:
    def __init__(self, starmap):
        self.starmap, self.calls, self.items = starmap, 0, 0

    def __call__(self, f, args):
        args = list(args)
        self.calls += 1
        self.items += len(args)
        return list(self.starmap(f, args))


def test_starmap_parallelization_is_used():
    """A StarmapParallelization (a counter around a thread pool's starmap) maps slices of
    the population; the values equal the serial evaluation."""
    X = np.linspace(0.6, 1.3, 40)[:, None]
    serial = get("stan2008-bipod").evaluate(X)
    with ThreadPool(2) as pool:
        counter = _Counting(pool.starmap)
        p = get("stan2008-bipod", elementwise_runner=StarmapParallelization(counter))
        F = p.evaluate(X)
    assert counter.calls == 1 and counter.items == 2  # the pool's two threads, a slice each
    np.testing.assert_array_equal(F, serial)


def test_starmap_parallelization_in_pymoo_minimize():
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.optimize import minimize

    counter = _Counting(itertools.starmap)
    p = get("wu2008", elementwise_runner=StarmapParallelization(counter))
    res = minimize(p, NSGA2(pop_size=10), ("n_gen", 3), seed=1)
    assert counter.calls == 3 and len(res.F) >= 1  # one map per generation
    ref = minimize(get("wu2008"), NSGA2(pop_size=10), ("n_gen", 3), seed=1)
    np.testing.assert_array_equal(res.F, ref.F)


def test_runner_refused_with_a_warning_naming_use_parallel():
    counter = _Counting(itertools.starmap)
    p = get("wu2008", elementwise_runner=StarmapParallelization(counter)).use_parallel(2)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            p.evaluate(np.array([[10.0], [20.0], [30.0]]))
            p.evaluate(np.array([[10.0], [20.0], [30.0]]))
    finally:
        p.use_parallel(1)
    msgs = [str(w.message) for w in caught]
    assert len(msgs) == 1 and "use_parallel" in msgs[0] and "\n" not in msgs[0], msgs
    assert counter.calls == 0


def test_a_problem_with_a_runner_pickles_without_it():
    import pickle

    with ThreadPool(1) as pool:
        p = get("wu2008", elementwise_runner=StarmapParallelization(pool.starmap))
        q = pickle.loads(pickle.dumps(p))
    assert q.name() == "wu2008" and q.evaluate(np.array([[10.0]])).shape == (1, 2)


# --- optimize(callback=) and pymoo's Result ------------------------------------------
def test_optimize_callback_and_result():
    class Count(Callback):
        def __init__(self):
            super().__init__()
            self.gens = []

        def notify(self, algorithm):
            self.gens.append(algorithm.n_gen)

    seen = []
    cb = Count()
    r = optimize(get("stan2008-bipod"), pop=10, gen=4, seed=1, n_jobs=1, progress=False, plot=False,
                 callback=cb)
    assert cb.gens == [1, 2, 3, 4]
    assert isinstance(r.result, Result) and len(r.result.pop) == 10
    # pymoo's optimum is on mechopt's front (natural sign)
    front = r.front[["W", "T"]].to_numpy()
    for row in get("stan2008-bipod").natural(r.result.F):
        assert np.any(np.all(np.isclose(front, row, rtol=0, atol=1e-12), axis=1))
    optimize(get("wu2008"), pop=6, gen=2, seed=1, n_jobs=1, progress=False, plot=False,
             callback=lambda algorithm: seen.append(algorithm.n_gen))
    assert seen == [1, 2]
    with pytest.raises(ValueError, match="callback"):
        optimize(get("wu2008"), pop=6, gen=2, progress=False, plot=False, callback=3)


# --- mechopt.evaluate of a gantry however made ----------------------------------------
def test_evaluate_a_gantry_from_its_constructor():
    """A gantry with the dimensions and task rectangle of Wu's synthesis, made by the
    constructor, has the same numbers (d from the geometry, not eq. 14) as the
    synthesised one; without a task rectangle the task-based numbers are NaN."""
    from mechopt.mechanisms.gantry import Gantry

    g = Gantry.from_parameters(500.0, 400.0, 10.0)
    same = Gantry(g.d1, g.l, g.stroke, g.q_min, g.l2, g.d2, g.mode, g.task_workspace)
    a, b = g.summary(), same.summary(length_unit="mm")
    for k in g.summary_keys[:-1]:
        assert b[k] == pytest.approx(a[k], rel=1e-12, abs=1e-9), k
    bare = Gantry(300.0, 700.0, 800.0)
    ev = mechopt.evaluate(bare)
    values = ev.values if hasattr(ev, "values") else ev
    assert values["d1"] == 300.0 and values["l"] == 700.0 and values["workspace_area"] > 0
    assert np.isnan(values["k_av"]) and np.isnan(values["eta_d"])
