"""Liu, Wang, Pritschow (2006): optimum regions of the 5R design space as pymoo Problems.

Design space (Liu 2006 sec. 2.1, Ref. [19]): ``r1 + r2 + r3 = 3``, ``0 < r1, r2 < 3``,
``0 <= r3 <= 1.5``, covered by two bounded variables ``(u, r3)`` with
``r1 = u (3 - r3)``, ``r2 = (1 - u) (3 - r3)`` (:func:`designs`) and
``r3 <= R3_MAX`` just below 1.5 (at 1.5 no design has a workspace); front.csv lists
``r1, r2, r3`` too. Every design of the box has a MIC, so the many-objective
problem has no constraint (MOEA/D runs on it); a region problem's design that
misses its region violates its thresholds, and one without a MIC (kept as a
guard, ``has_mic``) carries objective values no feasible design can beat. Indices are the global means of
:func:`mechopt.analysis.performance.global_indices` with a named quadrature, ``polar`` by
default (the one that reproduces the paper's numbers, see ``tests/test_liu2006.py``);
``quadrature="area"`` gives the true area means that ``mechopt evaluate`` reports by
default. The quadrature is part of the problem's :attr:`settings`, written to
``run.json`` and to the summary of ``mechopt problems``.

Each optimum region of sec. 3.1 is a set of constraints; the objectives of a
region problem are the MIC radius and the GCI (both maximised), so its front is
the workspace/dexterity trade-off *inside* the region. The many-objective problem
maximises r_MIC, GCI, GVI_min, GPI_min and minimises GSI_max.
"""
from __future__ import annotations

import numpy as np

from mechopt.core.quadrature import QUADRATURES

from mechopt.run.problem import MechoptProblem, Objective

__all__ = ["REGIONS", "LiuRegion", "LiuManyObjective", "liu_indices", "designs"]

#: Liu 2006 sec. 3.1: (quantity, ">" or "<", threshold) for each optimum region
REGIONS = {
    "w-gci": [("r_mic", ">", 0.8), ("gci", ">", 0.6)],  # sec. 3.1.1, Fig. 7(a)
    "w-gci-prime": [("r_mic", ">", 1.0), ("gci", ">", 0.7)],  # sec. 3.1.1, Fig. 7(b)
    "w-gci-gvi": [("r_mic", ">", 0.6), ("gci", ">", 0.55), ("gvi_min", ">", 1.0),
                  ("gvi_max", ">", 1.5)],  # sec. 3.1.2, Fig. 9
    "w-gci-gpi": [("r_mic", ">", 0.6), ("gci", ">", 0.6), ("gpi_min", ">", 1.2),
                  ("gpi_max", ">", 1.5)],  # sec. 3.1.3, Fig. 11
    "w-gci-gsi": [("r_mic", ">", 0.7), ("gci", ">", 0.6), ("gsi_min", "<", 0.7),
                  ("gsi_max", "<", 1.0)],  # sec. 3.1.4, Fig. 13
    "all": [("r_mic", ">", 0.85), ("gci", ">", 0.58), ("gvi_max", ">", 1.2), ("gvi_min", ">", 0.85),
            ("gpi_max", ">", 1.0), ("gpi_min", ">", 0.6), ("gsi_max", "<", 2.85),
            ("gsi_min", "<", 1.2)],  # sec. 3.1.5, Fig. 15
}
#: Liu's space r1 + r2 + r3 = 3
SUM = 3.0
#: smallest share u of r1 in r1 + r2 (and of r2): keeps both links positive
U_MIN = 1e-4
#: objective values no feasible design can beat, carried by designs without a MIC
#: (which violate ``has_mic``): the worst end of each index's range (r_MIC, GCI,
#: GVI_min, GPI_min >= 0); GSI_max has no upper bound, so a large finite value
WORST = {"r_mic": 0.0, "gci": 0.0, "gvi_min": 0.0, "gpi_min": 0.0, "gsi_max": 1e3}
#: range of each objective over the design space (hypervolume normalisation):
#: r_MIC: the MIC lies in each arm's annulus |r1 - r2| <= r <= r1 + r2, of width
#:   2 min(r1, r2), so r_MIC <= min(r1, r2) <= (r1 + r2)/2 <= 1.5 (r1 + r2 + r3 = 3);
#: GCI: a mean of the LCI, which lies in [0, 1];
#: GVI_min: |V|min = 1/s_max and s_max >= the norm of each row of J, 1/(r1 |sin phi|)
#:   (phi the angle between crank and distal link), so |V|min <= r1 < 3;
#: GPI_min, GSI_max: no finite bound follows from the formulation (GPI_min grows
#:   like 1/r1 as u -> U_MIN, GSI_max without bound as r3 -> 1.5, where the MIC
#:   vanishes), so the upper end 1e4 is measured: above the largest values on the
#:   box edges (401 points each) and a 121 x 121 lattice inside (5.7e3 and 2.2e3);
#:   both are >= 0. A design beyond the bound adds no hypervolume.
BOUNDS = {"r_mic": (0.0, 1.5), "gci": (0.0, 1.0), "gvi_min": (0.0, 3.0), "gpi_min": (0.0, 1e4),
          "gsi_max": (0.0, 1e4)}


def designs(X):
    """``(r1, r2, r3)`` of rows ``(u, r3)``: ``r1 = u (3 - r3)``, ``r2 = (1 - u) (3 - r3)``.

    This parametrisation covers the whole design triangle of Liu sec. 2.1
    (``r1 + r2 + r3 = 3``, ``r1, r2 > 0``, ``0 <= r3 <= 1.5``) with the bounds
    ``u in [U_MIN, 1 - U_MIN]``, ``r3 in [0, 1.5]`` alone, so that every pymoo
    algorithm (MOEA/D included, which ignores constraints) stays inside it.

    Parameters
    ----------
    X : array_like
        Rows ``(u, r3)``, shape ``(n, 2)``.

    Returns
    -------
    r1, r2, r3 : ndarray
        Non-dimensional lengths (sum 3).
    """
    X = np.atleast_2d(np.asarray(X, float))
    u, r3 = X[:, 0], X[:, 1]
    rest = SUM - r3
    return u * rest, (1.0 - u) * rest, r3


def liu_indices(r1, r2, r3, quadrature: str = "polar") -> dict:
    """Global indices of designs ``(r1, r2, r3)`` (arrays); NaN where a design has no MIC.

    Vectorised over the designs through :func:`mechopt.mechanisms.five_bar.batch.evaluate_designs`
    (the explicit-locus MIC and the compiled disk means; agreement with
    :func:`mechopt.analysis.performance.global_indices` is tested in ``tests/test_atlas.py``).

    Parameters
    ----------
    r1, r2, r3 : array_like
        Non-dimensional lengths of the designs.
    quadrature : str
        ``"polar"`` (Liu's) or ``"area"``.

    Returns
    -------
    dict
        ``{index: ndarray}``: ``r_mic``, ``gci``, ``mci``, ``gvi_*``, ``gpi_*``, ``gsi_*``
        (Liu 2006 eq. 4, 11, 14, 19).
    """
    from mechopt.mechanisms.five_bar.batch import RESULT_COLUMNS

    r1, r2, r3 = (np.atleast_1d(np.asarray(v, float)) for v in (r1, r2, r3))
    res = _evaluate_memo(r1, r2, r3, quadrature)
    out = {name: res[:, j] for j, name in enumerate(RESULT_COLUMNS)}
    out["r_mic"] = np.where(out["r_mic"] > 0, out["r_mic"], np.nan)
    out.update(r1=r1, r2=r2, r3=r3)
    return out


#: designs evaluated by this process: (quadrature, r1, r2, r3) -> row of
#: :func:`mechopt.mechanisms.five_bar.batch.evaluate_designs`. A GA meets the same designs again (the
#: weighting sweep's NSGA-II run is the front run of the same seed, every weight's GA
#: starts from the same population); the kernels evaluate each design on its own, so
#: a remembered row is the row a new evaluation would give, bit for bit
_MEMO: dict = {}
#: rows kept at most (about 150 bytes each); beyond, the memo starts afresh
MEMO_SIZE = 400_000


def _evaluate_memo(r1, r2, r3, quadrature):
    from mechopt.mechanisms.five_bar.batch import RESULT_COLUMNS, evaluate_designs

    # keyed by the bits (so that -0.0 and 0.0 stay apart)
    keys = list(map(tuple, np.column_stack([r1, r2, r3]).astype(float).view(np.uint64).tolist()))
    rows = [_MEMO.get((quadrature, *k)) for k in keys]
    todo = [i for i, row in enumerate(rows) if row is None]
    if todo:
        new = evaluate_designs(r1[todo], r2[todo], r3[todo], quadrature=quadrature)
        if len(_MEMO) + len(todo) > MEMO_SIZE:
            _MEMO.clear()
        for i, row in zip(todo, new):
            rows[i] = row
            _MEMO[(quadrature, *keys[i])] = row
    return np.vstack(rows) if rows else np.empty((0, len(RESULT_COLUMNS)))


#: upper bound of r3: at r3 = 1.5 exactly, r1 + r2 = r3 and the arms meet only on the
#: base line (no workspace, no MIC); below it every design of the box has a MIC
#: (checked on 2e5 random designs and the corners in tests/test_problem_conventions.py)
R3_MAX = 1.5 - 1e-6


def _bounds():
    return [U_MIN, 0.0], [1.0 - U_MIN, R3_MAX]


def _objectives_and_mic(ex, objectives):
    """``F`` (minimisation form) with :data:`WORST` where a design has no MIC, and the
    ``has_mic`` constraint column (1 without a MIC: no index is defined; else -1)."""
    has = np.isfinite(ex["r_mic"])
    F = np.column_stack([ob.sense * np.where(has, ex[ob.name], WORST[ob.name])
                         for ob in objectives])
    return F, np.where(has, -1.0, 1.0)


class LiuRegion(MechoptProblem):
    """Maximise (r_MIC, GCI) inside one optimum region of Liu 2006 sec. 3.1.

    Parameters
    ----------
    region : str
        A region of :data:`REGIONS` (Liu 2006 sec. 3.1, Fig. 7-13).
    quadrature : str
        ``"polar"`` (Liu's) or ``"area"``.
    **kwargs : 
        pymoo's :class:`~pymoo.core.problem.Problem` keywords (``elementwise_runner``,
        ``callback``).

    Raises
    ------
    ValueError
        For an unknown region or quadrature.
    """

    var_names = ("u", "r3")
    objectives = (Objective("r_mic", -1, "L", BOUNDS["r_mic"]), Objective("gci", -1, "-", BOUNDS["gci"]))
    #: the feasible regions are thin: the slowest (``all``) meets IGD+ 0.01 and HV ratio
    #: 0.98 at generation 46 of 100 from seeds 1-2, and 0.0027 / 0.993 at 100 (100
    #: designs: 0.98 at 81; 24 x 12: IGD+ 0.07; benchmarks/bench_fronts.py)
    default_algorithm = "nsga2"
    default_pop = 200
    default_gen = 100
    options = ("region", "quadrature")

    def __init__(self, region: str = "w-gci", quadrature: str = "polar", **kwargs):
        from mechopt.core import validation as _v

        self.region = _v.choice("region", region, tuple(REGIONS))
        self.quadrature = _v.choice("quadrature", quadrature, QUADRATURES)
        self.name = f"liu2006-{region}"
        self.summary = "Liu 2006 region " + ", ".join(f"{q} {op} {t}" for q, op, t in REGIONS[region]) \
            + f"; max (r_MIC, GCI) over r1 + r2 + r3 = 3; {self.quadrature} means"
        self.constr_names = ("has_mic",) + tuple(f"{q}{'_min' if op == '>' else '_max'}"
                                                     for q, op, _ in REGIONS[region])
        super().__init__(*_bounds(), **kwargs)

    def evaluate_designs(self, X):
        ex = liu_indices(*designs(X), self.quadrature)
        F, has_mic = _objectives_and_mic(ex, self.objectives)
        G = [has_mic]
        for q, op, t in REGIONS[self.region]:
            v = ex[q]
            # relative violation, so thresholds of different magnitude compare
            g = (t - v) / abs(t) if op == ">" else (v - t) / abs(t)
            G.append(np.where(np.isfinite(g), g, 1.0))
        return {"F": F, "G": np.column_stack(G), "extra": ex}


class LiuManyObjective(MechoptProblem):
    """Five objectives over the design space: r_MIC, GCI, GVI_min, GPI_min (max) and GSI_max (min).

    Parameters
    ----------
    quadrature : str
        ``"polar"`` (Liu's) or ``"area"``.
    **kwargs : 
        pymoo's :class:`~pymoo.core.problem.Problem` keywords (``elementwise_runner``,
        ``callback``).

    Raises
    ------
    ValueError
        For an unknown quadrature.
    """

    name = "liu2006-many"
    summary = "Liu 2006 many-objective: max r_MIC, GCI, GVI_min, GPI_min and min GSI_max over r1 + r2 + r3 = 3"
    _summary = summary
    var_names = ("u", "r3")
    objectives = tuple(Objective(n, sense, unit, BOUNDS[n]) for n, sense, unit in (
        ("r_mic", -1, "L"), ("gci", -1, "-"), ("gvi_min", -1, "L"), ("gpi_min", -1, "1/L"),
        ("gsi_max", 1, "L^2")))
    #: the front is a 2-D set in 5 objectives: NSGA-III fills it slowly (HV ratio 0.983
    #: after 60 generations of 300) and NSGA-II's crowding distance lets the population
    #: cluster (IGD+ drifts from 0.005 to 0.013 with 300 designs); the M-nearest-neighbour
    #: crowding keeps IGD+ at 0.004-0.005 from generation 10 on, HV ratio 0.99 from 20
    #: (benchmarks/bench_fronts.py)
    default_algorithm = "nsga2-mnn"
    default_pop = 300
    default_gen = 40
    options = ("quadrature",)

    def __init__(self, quadrature: str = "polar", **kwargs):
        from mechopt.core import validation as _v

        self.quadrature = _v.choice("quadrature", quadrature, QUADRATURES)
        self.summary = f"{self._summary}; {self.quadrature} means"
        super().__init__(*_bounds(), **kwargs)

    def evaluate_designs(self, X):
        ex = liu_indices(*designs(X), self.quadrature)
        F, has_mic = _objectives_and_mic(ex, self.objectives)
        if np.any(has_mic > 0):  # unconstrained (so that MOEA/D runs): R3_MAX guarantees a MIC
            raise RuntimeError(f"a design inside the bounds has no MIC: {X[has_mic > 0][0]!r}")
        return {"F": F, "extra": ex}
