"""Every registered problem follows pymoo's conventions: infeasible is a constraint
(G > 0), never a placeholder in F; print/repr, empty batches, keyword arguments and
derived quantities work as a pymoo user expects; any algorithm, MOEA/D included, runs."""
import itertools
import pickle

import numpy as np
import pytest
from pymoo.algorithms.moo.moead import MOEAD
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.optimize import minimize
from pymoo.util.ref_dirs import get_reference_directions

from mechopt.problems import get, names

#: the placeholder the Liu problems used to put in F for undefined objectives
PLACEHOLDER = 1e3


def _designs(problem, n, seed):
    rng = np.random.default_rng(seed)
    X = rng.uniform(problem.xl, problem.xu, (n, problem.n_var))
    corners = np.array(list(itertools.product(*zip(problem.xl, problem.xu))), float)
    return np.vstack([X, corners])


@pytest.mark.parametrize("name", names())
def test_feasible_rows_hold_no_placeholder_and_undefined_rows_are_infeasible(name):
    p = get(name)
    n = 6 if name.startswith(("le2013", "wu2008-dynamic")) else 60
    X = _designs(p, n, 7)
    out = p.evaluate(X, return_as_dictionary=True)
    F = out["F"]
    assert F.shape == (len(X), p.n_obj) and np.all(np.isfinite(F))
    feasible = np.all(out["G"] <= 0, axis=1) if p.n_ieq_constr else np.ones(len(X), bool)
    # a design whose objective is undefined violates a constraint
    if name.startswith("liu2006"):
        assert np.all(np.abs(F[feasible]) < PLACEHOLDER)
        undefined = ~np.isfinite(out["r_mic"])
        if p.n_ieq_constr:
            assert np.all(out["G"][undefined, 0] > 0)
        else:  # liu2006-many: no undefined design inside its bounds
            assert not undefined.any()
    if name.startswith("le2013"):
        assert np.all((out["a_max"] > 0) == (out["G"][:, 0] <= 0))


def test_every_liu_design_in_the_box_has_a_mic():
    """Why liu2006-many needs no constraint: r3 <= R3_MAX < 1.5 keeps a MIC everywhere."""
    from mechopt.problems.liu2006 import designs, liu_indices

    p = get("liu2006-many")
    rng = np.random.default_rng(3)
    # the MIC shrinks toward the box's edges (r3 -> R3_MAX, r1 or r2 -> 0): 250 designs
    # on each edge, the corners, and 4000 uniform ones inside
    t = np.linspace(0.0, 1.0, 250)[:, None]
    (u0, r0), (u1, r1) = p.xl, p.xu
    edges = [np.column_stack([u0 + (u1 - u0) * t[:, 0], np.full(len(t), r)]) for r in (r0, r1)]
    edges += [np.column_stack([np.full(len(t), u), r0 + (r1 - r0) * t[:, 0]]) for u in (u0, u1)]
    X = np.vstack([rng.uniform(p.xl, p.xu, (4000, 2)), *edges, _designs(p, 0, 0)])
    assert np.all(np.isfinite(liu_indices(*designs(X))["r_mic"]))
    # the excluded edge r3 = 1.5 has none: the region problems' guard catches it
    out = get("liu2006-w-gci").evaluate_designs(np.array([[0.5, 1.5]]))
    assert not np.isfinite(out["extra"]["r_mic"][0]) and out["G"][0, 0] > 0


def test_le_designs_without_a_square_are_infeasible():
    p = get("le2013-gamma-relaxed")
    # l0 = 2 with rho = 1.2: the MIC is tiny or absent, gamma 0.95 is out of reach
    out = p.evaluate(np.array([[1.2, 0.95, 2.0]]), return_as_dictionary=True)
    assert out["a_max"][0] == 0.0 and out["G"][0, 0] > 0


@pytest.mark.parametrize("name", names())
def test_pymoo_conventions(name):
    p = get(name)
    assert name in str(p) and "n_var" in str(p) and type(p).__name__ in repr(p)
    out = p.evaluate(np.empty((0, p.n_var)), return_as_dictionary=True)
    assert out["F"].shape == (0, p.n_obj)
    if p.n_ieq_constr:
        assert out["G"].shape == (0, p.n_ieq_constr)
    with pytest.raises(ValueError, match="finite"):
        p.evaluate(np.full((1, p.n_var), np.nan))
    with pytest.raises(ValueError, match="outside"):
        p.evaluate((p.xu + 1.0)[None, :])
    assert pickle.loads(pickle.dumps(p)).name == name


def test_keyword_arguments_reach_pymoo_and_derived_quantities_reach_the_population():
    seen = []
    from mechopt.problems.liu2006 import LiuRegion

    p = LiuRegion("w-gci", callback=lambda X, out: seen.append(len(X)))
    res = minimize(p, NSGA2(pop_size=8), ("n_gen", 2), seed=1)
    assert seen and sum(seen) == 16
    r_mic = res.pop.get("r_mic")
    assert r_mic.shape == (8,) and np.all(np.isfinite(r_mic) | np.isnan(r_mic))
    r1, r2, r3 = (res.pop.get(k) for k in ("r1", "r2", "r3"))
    np.testing.assert_allclose(r1 + r2 + r3, 3.0, rtol=1e-12)


def test_moead_runs_on_a_liu_problem_inside_the_design_triangle():
    p = get("liu2006-many")
    ref = get_reference_directions("das-dennis", p.n_obj, n_partitions=3)
    res = minimize(p, MOEAD(ref, n_neighbors=5), ("n_gen", 3), seed=1)
    X = res.pop.get("X")
    assert np.all((X >= p.xl) & (X <= p.xu))
    r1, r2, _ = (res.pop.get(k) for k in ("r1", "r2", "r3"))
    assert np.all(r1 > 0) and np.all(r2 > 0)
