"""Weighted-sum scalarisation of a two-objective Problem (for weighting sweeps)."""
from __future__ import annotations

import numpy as np

from mechopt.run.problem import MechoptProblem, Objective

__all__ = ["WeightedSum"]


class WeightedSum(MechoptProblem):
    """``Z = w f1/s1 + (1 - w) f2/s2`` (minimised; ``f`` in pymoo's minimisation form).

    If the wrapped problem defines ``weighted_sum(F, w) -> Z`` (its paper's own
    scalarisation), that is used instead and ``scales`` are ignored.

    Parameters
    ----------
    base : MechoptProblem
        The two-objective problem.
    weight : float
        ``w``, in [0, 1].
    scales : tuple of float
        ``(s1, s2)``: the objectives' spans.
    **kwargs : 
        pymoo's :class:`~pymoo.core.problem.Problem` keywords.
    """

    objectives = (Objective("z", 1),)

    def __init__(self, base: MechoptProblem, weight: float, scales=(1.0, 1.0), **kwargs):
        self.base, self.weight, self.scales = base, float(weight), np.asarray(scales, float)
        self.name = f"{base.name}-w{self.weight:g}"
        self.summary = f"weighted sum of {base.name}, w = {self.weight:g}"
        self.var_names = base.var_names
        self.constr_names = base.constr_names
        super().__init__(base.xl, base.xu, **kwargs)

    def evaluate_designs(self, X):
        res = self.base.evaluate_designs(X)
        F = res["F"]
        if hasattr(self.base, "weighted_sum"):
            z = self.base.weighted_sum(F, self.weight)
        else:
            z = self.weight * F[:, 0] / self.scales[0] + (1 - self.weight) * F[:, 1] / self.scales[1]
        extra = dict(res.get("extra", {}))
        for j, ob in enumerate(self.base.objectives):
            extra[ob.name] = ob.sense * F[:, j]
        out = {"F": z[:, None], "extra": extra}
        if "G" in res:
            out["G"] = res["G"]
        return out
