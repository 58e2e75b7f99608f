"""LCI: the local conditioning index over the task (Liu 2006 eq. 3), a requirement
``min_T LCI >= gamma`` and the objectives ``min-lci`` and ``mean-lci``.

The minimum over the task is attained on ``dT`` or at an interior critical point:
both are located on the samples and refined by zooming
(:mod:`mechopt.analysis.sampling`). The mean is over the interior grid (the points of a
point task).
"""
from __future__ import annotations

from mechopt.core import validation as _v
from mechopt.requirements.base import Objective, Option, Requirement

__all__ = ["MinLCI", "MinLCIObjective", "MeanLCIObjective", "lci_min", "lci_mean", "MEMBERS"]

#: a design whose sampled LCI minimum is below ``SCREEN * gamma`` is not refined
SCREEN = 0.9
#: the search leaves the LCI minimum unrefined when the samples' minimum is at least
#: ``gamma + SETTLE`` (:meth:`MinLCI.settled`): refinement lowered it by at most 0.0036
#: on 800 random five-bar designs of a rectangle and a star polygon
SETTLE = 0.05


def lci_min(ctx) -> float:
    """The minimum LCI over the task, refined (shared by the requirement and the objective).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The minimum LCI over the task (dimensionless), the samples' minimum refined by
        zooming; memoised in ``ctx``.
    """
    return ctx.memo("lci_min", lambda: ctx.quantity_min("lci", ctx.lci))


def lci_mean(ctx) -> float:
    """The mean LCI over the interior grid (over the points of a point task).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The mean LCI (dimensionless).
    """
    lci, nb = ctx.lci, ctx.n_boundary
    return float(lci[nb:].mean() if ctx.samples["ix"].size else lci[:nb].mean())


class MinLCI(Requirement):
    name = "lci"
    options = (Option("min_lci", "LCI >= this everywhere on the task (dimensionless, in (0, 1))",
                      check=lambda v, spec: _v.open_unit_interval("min_lci", v)),)
    needs = ("points", "jacobian")
    margin_text = "`--min-lci`: minimum LCI over the task minus the required level"
    certificate = ("boundary and interior critical points located on the samples and refined by zooming "
                   "(mechopt.analysis.sampling)")

    def describe(self, req, unit) -> str:
        return f"LCI >= {req.min_lci} over the task"

    def screen(self, ctx) -> bool:
        return float(ctx.lci.min()) >= SCREEN * ctx.req.min_lci

    def settled(self, ctx) -> bool:
        # the min-lci objective reads the refined minimum: never settled with it
        return "min-lci" not in ctx.objectives and float(ctx.lci.min()) >= ctx.req.min_lci + SETTLE

    def evaluate(self, ctx):
        gamma = ctx.req.min_lci
        m = lci_min(ctx) if self.name not in ctx.settled else float(ctx.lci.min())
        return m - gamma, (gamma - m) / gamma

    def report(self, ctx) -> dict:
        # the refined minimum where a member asked for it, else the samples' minimum
        low = lci_min(ctx) if ctx.has("lci_min") else float(ctx.lci.min())
        return {"lci_min": low, "lci_mean": lci_mean(ctx)}


class MinLCIObjective(Objective):
    name = "min-lci"
    sense = -1
    description = "minimum LCI over the task"
    needs = ("points", "jacobian")

    def value(self, ctx) -> float:
        return lci_min(ctx)

    def invalid_value(self, ev, lengths) -> float:
        return 0.0


class MeanLCIObjective(Objective):
    name = "mean-lci"
    sense = -1
    description = "mean LCI over the task (interior grid)"
    needs = ("points", "jacobian")

    def value(self, ctx) -> float:
        return lci_mean(ctx)

    def invalid_value(self, ev, lengths) -> float:
        return 0.0


MEMBERS = (MinLCI(), MinLCIObjective(), MeanLCIObjective())
