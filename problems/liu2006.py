"""Liu, Wang, Pritschow (2006): optimum regions of the 5R design space as pymoo Problems.

Design space (Liu 2006 sec. 2.1, Ref. [19]): ``r1 + r2 + r3 = 3``, two free
variables ``(r1, r3)`` with ``r2 = 3 - r1 - r3 > 0``, ``0 < r1 < 3``,
``0 <= r3 <= 1.5``. Indices are the global means of
:func:`mechopt.performance.global_indices` with a named quadrature, ``polar`` by
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

from mechopt.quadrature import QUADRATURES

from .base import MechoptProblem, Objective

__all__ = ["REGIONS", "LiuRegion", "LiuManyObjective", "liu_indices"]

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
_INDEX_KEYS = ("r_mic", "mic_center_y", "gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min",
               "gsi_max", "gsi_min")
_MIN_R2 = 1e-3


def liu_indices(X, quadrature: str = "polar") -> dict:
    """Global indices for rows ``(r1, r3)`` of ``X``; NaN where the design has no MIC.

    Vectorised over the designs through :func:`mechopt.atlas.evaluate_designs`
    (the explicit-locus MIC and the compiled disk means; agreement with
    :func:`mechopt.performance.global_indices` is tested in ``tests/test_atlas.py``).
    """
    from mechopt.atlas import RESULT_COLUMNS, evaluate_designs

    X = np.atleast_2d(np.asarray(X, float))
    r1, r3 = X[:, 0], X[:, 1]
    r2 = 3.0 - r1 - r3
    out = {k: np.full(len(X), np.nan) for k in _INDEX_KEYS}
    out["r2"] = r2
    ok = r2 >= _MIN_R2
    if ok.any():
        res = evaluate_designs(r1[ok], r2[ok], r3[ok], quadrature=quadrature)
        for j, name in enumerate(RESULT_COLUMNS):
            if name in out:
                out[name][ok] = res[:, j]
    out["r_mic"] = np.where(out["r_mic"] > 0, out["r_mic"], np.nan)
    return out


def _bounds():
    return [1e-3, 0.0], [3.0 - _MIN_R2, 1.5]


def _objective_matrix(ex, objectives, worst=1e3):
    F = np.column_stack([ob.sense * ex[ob.name] for ob in objectives])
    return np.where(np.isfinite(F), F, worst)


class LiuRegion(MechoptProblem):
    """Maximise (r_MIC, GCI) inside one optimum region of Liu 2006 sec. 3.1."""

    var_names = ("r1", "r3")
    objectives = (Objective("r_mic", -1, "L"), Objective("gci", -1))
    default_algorithm = "nsga2"
    default_pop = 24
    default_gen = 12

    def __init__(self, region: str = "w-gci", quadrature: str = "polar"):
        from mechopt import validation as _v

        self.region = _v.choice("region", region, tuple(REGIONS))
        self.quadrature = _v.choice("quadrature", quadrature, QUADRATURES)
        self.settings = {"quadrature": self.quadrature}
        self.name = f"liu2006-{region}"
        self.summary = "Liu 2006 region " + ", ".join(f"{q} {op} {t}" for q, op, t in REGIONS[region]) \
            + f"; max (r_MIC, GCI) over (r1, r3), r2 = 3 - r1 - r3; {self.quadrature} means"
        self.constr_names = ("r2_positive",) + tuple(f"{q}{'_min' if op == '>' else '_max'}"
                                                     for q, op, _ in REGIONS[region])
        super().__init__(*_bounds())

    def evaluate_designs(self, X):
        ex = liu_indices(X, self.quadrature)
        G = [(X[:, 0] + X[:, 1] - (3.0 - _MIN_R2)) / 3.0]
        for q, op, t in REGIONS[self.region]:
            v = ex[q]
            # relative violation, so thresholds of different magnitude compare
            g = (t - v) / abs(t) if op == ">" else (v - t) / abs(t)
            G.append(np.where(np.isfinite(g), g, 1.0))
        return {"F": _objective_matrix(ex, self.objectives), "G": np.column_stack(G), "extra": ex}


class LiuManyObjective(MechoptProblem):
    """Five objectives over the design space: r_MIC, GCI, GVI_min, GPI_min (max) and GSI_max (min)."""

    name = "liu2006-many"
    summary = "Liu 2006 many-objective: max r_MIC, GCI, GVI_min, GPI_min and min GSI_max over (r1, r3)"
    _summary = summary
    var_names = ("r1", "r3")
    objectives = (Objective("r_mic", -1, "L"), Objective("gci", -1), Objective("gvi_min", -1, "L"),
                  Objective("gpi_min", -1, "1/L"), Objective("gsi_max", 1, "L^2"))
    constr_names = ("r2_positive",)
    default_algorithm = "nsga3"
    default_pop = 30
    default_gen = 10

    def __init__(self, quadrature: str = "polar"):
        from mechopt import validation as _v

        self.quadrature = _v.choice("quadrature", quadrature, QUADRATURES)
        self.settings = {"quadrature": self.quadrature}
        self.summary = f"{self._summary}; {self.quadrature} means"
        super().__init__(*_bounds())

    def evaluate_designs(self, X):
        ex = liu_indices(X, self.quadrature)
        G = ((X[:, 0] + X[:, 1] - (3.0 - _MIN_R2)) / 3.0)[:, None]
        return {"F": _objective_matrix(ex, self.objectives), "G": G, "extra": ex}
