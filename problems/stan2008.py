"""Stan, Maties, Balan (2008): workspace W and transmission quality T of the
Bipod (RPRPR) and the Biglide (PRRRP).

Bipod (sec. 5.1, eq. 11-13): design variable ``u = q1_min/b`` in ``(0.52, 1.35)``,
``q1_min = q2_min = u b``, ``q_max = 1.6 q_min``, ``b = 1`` (the problem is
scale-free: W scales as b^2 and T not at all); the workspace is the half ``y > 0``.

Biglide (sec. 5.2): design variable ``L2`` in ``(1, 1.2)``. The paper gives neither
the guide half-distance ``L1`` nor the slider strokes; we use ``L1 = 1`` and
strokes ``q in [0, 1]`` (constructor arguments), mode ``"--"``.

Objectives (both maximised): ``W`` (exact workspace area, Stan eq. 8) and ``T``
(area mean of the TQI of Stan eq. 9 over that workspace).

Normalisation of W in ``Z = W1 T + W2 W`` (Tables 2-3) is not stated by the
paper. We use ``W_n = W / W_ref`` with ``W_ref`` the area at the upper bound of
the design variable (the largest workspace of the design range, W grows
monotonically with it), so that both terms lie in [0, 1].
"""
from __future__ import annotations

import numpy as np

from mechopt.mechanisms.biglide import Biglide
from mechopt.mechanisms.bipod import Bipod

from .base import MechoptProblem, Objective

__all__ = ["StanBipod", "StanBiglide", "BIPOD_BOUNDS", "BIGLIDE_BOUNDS"]

#: Stan eq. (12)
BIPOD_BOUNDS = (0.52, 1.35)
#: Stan eq. (13)
Q_MAX_OVER_Q_MIN = 1.6
#: Stan sec. 5.2
BIGLIDE_BOUNDS = (1.0, 1.2)


class _StanProblem(MechoptProblem):
    #: T is a mean of the TQI, 2 LCI / (1 + LCI^2) in [0, 1]; W >= 0 and it grows with
    #: the design variable (module docstring), so its largest value is :attr:`w_ref`
    #: (the instance's bounds of W are set in ``__init__``)
    objectives = (Objective("W", -1, "L^2"), Objective("T", -1, "-", (0.0, 1.0)))
    #: one variable: converged by generation 3, the front's spread is the population
    #: (HV ratio 0.981 with 60 designs, 0.990 with 100; benchmarks/bench_fronts.py)
    default_algorithm = "nsga2"
    default_pop = 100
    default_gen = 20

    def __init__(self, xl, xu, **kwargs):
        super().__init__(xl, xu, **kwargs)
        self.objectives = (self.objectives[0].with_bounds(0.0, self.w_ref), *self.objectives[1:])

    def _mechanism(self, v):
        raise NotImplementedError

    def _indices(self, values):
        W = np.empty(len(values))
        T = np.empty(len(values))
        for i, v in enumerate(values):
            m = self._mechanism(v)
            W[i] = m.workspace_area()
            T[i] = m.gtqi(method="gauss") if isinstance(m, Biglide) else m.gtqi()
        return W, T

    @property
    def w_ref(self) -> float:
        """Area at the upper bound of the design variable (normalisation of W)."""
        return float(self._mechanism(self.xu[0]).workspace_area())

    def evaluate_designs(self, X):
        W, T = self._indices(X[:, 0])
        return {"F": np.column_stack([-W, -T]), "extra": {"W_n": W / self.w_ref}}

    def weighted_sum(self, F, w):
        """Stan's ``Z = W1 T + W2 W_n`` with ``W1 = 1 - w``, ``W2 = w`` (w weighs W,
        the first objective), returned negated for minimisation."""
        return -((1.0 - w) * (-F[:, 1]) + w * (-F[:, 0]) / self.w_ref)


class StanBipod(_StanProblem):
    name = "stan2008-bipod"
    summary = "Stan 2008 Bipod: max workspace W and global TQI T over q1_min/b in (0.52, 1.35), q_max = 1.6 q_min"
    var_names = ("q1_min_over_b",)

    def __init__(self, **kwargs):
        super().__init__([BIPOD_BOUNDS[0]], [BIPOD_BOUNDS[1]], **kwargs)

    def _mechanism(self, u):
        return Bipod(1.0, u, Q_MAX_OVER_Q_MIN * u)


class StanBiglide(_StanProblem):
    name = "stan2008-biglide"
    summary = "Stan 2008 Biglide: max workspace W and global TQI T over L2 in (1, 1.2), L1 = 1, strokes [0, 1]"
    var_names = ("L2",)
    single_optimum = ("with L1 = 1 and strokes [0, 1] (the paper states neither) W and T both grow "
                      "with L2, so the front is the upper bound L2 = 1.2")

    def __init__(self, l1: float = 1.0, q_min: float = 0.0, q_max: float = 1.0, **kwargs):
        self.l1, self.q_min, self.q_max = float(l1), float(q_min), float(q_max)
        # L2 = L1 exactly leaves no workspace: keep the open interval open
        super().__init__([BIGLIDE_BOUNDS[0] + 1e-6], [BIGLIDE_BOUNDS[1]], **kwargs)

    def _mechanism(self, l2):
        return Biglide(self.l1, l2, self.q_min, self.q_max)
