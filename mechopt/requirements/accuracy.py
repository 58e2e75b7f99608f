"""Accuracy: the proven worst-case position error over the task under an error model
(:mod:`mechopt.analysis.accuracy`), a requirement ``--max-error 20um`` and an objective
``error`` [um].

The error model (``--error-model``: a JSON/TOML file, or ``key=value`` pairs such as
``encoder_counts=16384,clearance_um=5``) states the actuators' resolution and
backlash, the passive joints' radial clearance and the link-length and base-placement
tolerances. At each task sample the bound of
:func:`~mechopt.analysis.accuracy.pose_error` is proven (the first-order map's worst
case over the tolerance box, plus a proven second-order remainder); the maximum over
the region is taken on the samples of the evaluation (the boundary points and the
interior grid; the fine sampling of the certification for the front's designs), not
refined: the error varies slowly over a task far from type-II singularities, which
the ``singular`` requirement keeps away. A sample without a proof (unreachable, or so
close to a type-II singularity that the perturbed mechanism may not assemble) has an
infinite bound.
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import validation as _v
from mechopt.analysis import accuracy as _acc
from mechopt.requirements.base import Objective, Option, Requirement

__all__ = ["MaxError", "ErrorObjective", "error_um", "MEMBERS"]

#: the normalised constraint of a design whose bound is infinite somewhere (no proof)
G_UNPROVEN = 1e3


def error_um(ctx) -> float:
    """The largest proven position error [um] over the task samples (inf without a proof).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The error [um].
    """
    def compute():
        x, y = ctx.to_mech(ctx.samples["allx"], ctx.samples["ally"])
        model = _acc.ErrorModel.from_dict(ctx.req.error_model)
        return _acc.max_error(ctx.mech, model, x, y, ctx.unit) * _acc.UM_PER_UNIT[ctx.unit]
    return ctx.memo("error_um", compute)


def _model(value, spec) -> dict:
    """The error model as plain data (``{field: value}``: run.json records it)."""
    from dataclasses import asdict

    return asdict(_acc.parse_error_model(value))


class MaxError(Requirement):
    name = "error"
    options = (Option("max_error", "proven worst-case position error <= this everywhere on the task, a length "
                                   "with its unit (20um, 0.05mm); needs --error-model",
                      check=lambda v, spec: _v.positive_length("max_error [um]", v),
                      parse=_acc.parse_length_um, metavar="LENGTH"),
               Option("error_model", "tolerances of --max-error and the error objective: a JSON or TOML file, "
                                     "or key=value pairs (encoder_counts=16384,clearance_um=5; keys as in "
                                     "`mechopt accuracy`)",
                      check=_model, parse=_acc.parse_error_model, metavar="FILE|KEY=VALUE,..."))
    needs_options = ("error_model",)
    needs = ("points",)
    margin_text = "`--max-error`: the allowed position error minus the proven worst case over the task"
    margin_unit = "um"
    certificate = ("each sample's bound proven (first order over the tolerance box plus a proven second-order "
                   "remainder, mechopt.analysis.accuracy); the maximum over the task taken on the samples")

    def describe(self, req, unit) -> str:
        return f"position error <= {req.max_error:g} um over the task"

    def evaluate(self, ctx):
        need, e = ctx.req.max_error, error_um(ctx)
        return need - e, min((e - need) / need, G_UNPROVEN) if not math.isnan(e) else math.nan

    def report(self, ctx) -> dict:
        return {"error_um": error_um(ctx)} if ctx.has("error_um") else {}


class ErrorObjective(Objective):
    name = "error"
    sense = 1
    unit = "um"
    description = "proven worst-case position error over the task (--error-model)"
    requires = ("error_model",)
    needs = ("points",)

    def value(self, ctx) -> float:
        return error_um(ctx)

    def bounds(self, ev):
        top = ev.req.max_error if ev.req.max_error is not None else 1e3
        return (0.0, 10.0 * top)


MEMBERS = (MaxError(), ErrorObjective())
