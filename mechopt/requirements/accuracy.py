"""Accuracy: the proven worst-case position error over the task under an error model
(:mod:`mechopt.analysis.accuracy`), a requirement ``--max-error 20um`` and an objective
``error`` [um].

The error model (``--error-model``: a JSON/TOML file, or ``key=value`` pairs such as
``encoder_counts=16384,clearance_um=5``) states the actuators' resolution and
backlash, the passive joints' radial clearance and the link-length and base-placement
tolerances; ``--encoder 16384`` (counts per revolution; ``16384,4096`` one per motor)
sets or overrides its encoder resolution. At each task point the bound of
:func:`~mechopt.analysis.accuracy.pose_error` is proven (the first-order map's worst
case over the tolerance box, plus a proven second-order remainder). The maximum over
the task is refined like the minima of the other requirements: located on the samples
(the boundary points and the interior grid) and refined by the zoom searches of
:mod:`mechopt.analysis.sampling` (:func:`~mechopt.analysis.sampling.region_mins` on
the negated bound), which place the maximiser to ``h/64`` inside and ``h_b/2048`` on
the boundary. Stated tolerance: the samples resolve the peaks of the bound (no peak
narrower than a grid cell); the largest bound grows towards the type-II singularities,
which the ``singular`` requirement keeps away, so it lies on the task's boundary,
mostly at a vertex (a sample). The maximum over the task is located, not proven
between the points (``proven = False``); ``tests/test_accuracy_task.py`` checks it
against a 401 x 401 grid and a dense boundary. A point without a proof (unreachable,
or so close to a type-II singularity that the perturbed mechanism may not assemble)
has an infinite bound.
"""
from __future__ import annotations

import math
from dataclasses import asdict

import numpy as np

from mechopt.core import validation as _v
from mechopt.analysis import accuracy as _acc
from mechopt.requirements.base import Objective, Option, Requirement

__all__ = ["MaxError", "ErrorObjective", "error_um", "model_of", "MEMBERS"]

#: the normalised constraint of a design whose bound is infinite somewhere (no proof)
G_UNPROVEN = 1e3


#: a design whose largest sampled error exceeds ``need / SCREEN`` is not refined
SCREEN = 0.9


def model_of(req) -> "_acc.ErrorModel":
    """The error model of the requirements ``req``: ``req.error_model`` (none: every
    tolerance 0) with the encoder resolution of ``req.encoder`` when it is given.

    Parameters
    ----------
    req : mechopt.requirements.Requirements
        The requirements.

    Returns
    -------
    mechopt.analysis.accuracy.ErrorModel
        The tolerances.
    """
    model = _acc.ErrorModel.from_dict(dict(req.error_model or {}))
    if req.encoder is not None:
        model = _acc.ErrorModel.from_dict({**asdict(model), "encoder_counts": req.encoder})
    return model


def _sampled(ctx) -> np.ndarray:
    """Minus the bound [L] at the task samples (boundary, then grid; -inf without a proof)."""
    def compute():
        b = _acc.pose_error(ctx.mech, model_of(ctx.req), *ctx.to_mech(ctx.samples["allx"], ctx.samples["ally"]),
                            ctx.unit)["bound"]
        return -np.where(np.isnan(b), np.inf, b)
    return ctx.memo("error_samples", compute)


def error_um(ctx) -> float:
    """The largest proven position error [um] over the task (inf without a proof):
    located on the samples and refined by zooming when ``ctx.refine``
    (:func:`mechopt.analysis.accuracy.task_max_error`).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The largest bound over the task [um] (inf where not proven).
    """
    return ctx.memo("error_um", lambda: _acc.UM_PER_UNIT[ctx.unit] * _acc.task_max_error(
        ctx.mech, model_of(ctx.req), ctx.samples, ctx.to_mech, ctx.unit, ctx.refine, _sampled(ctx)))


def _model(value, spec) -> dict:
    """The error model as plain data (``{field: value}``: run.json records it)."""
    return asdict(_acc.parse_error_model(value))


def _encoder(value, spec):
    """Counts per revolution [-]: one positive number, or one per motor (a pair, or the
    text ``16384,4096``)."""
    if not spec.angular:
        raise ValueError(f"encoder (counts per revolution) applies to cranks, not the {spec.name}: "
                         "give resolution_um in --error-model")
    if isinstance(value, str):
        value = [v for v in value.replace("/", ",").split(",") if v.strip()]
    vals = [_v.finite_number("encoder [counts/rev]", v) for v in np.atleast_1d(np.asarray(value, dtype=object))]
    if any(v <= 0 for v in vals):
        raise ValueError(f"encoder [counts/rev] must be positive, got {_v.show(value)}")
    if len(vals) not in (1, 2):
        raise ValueError(f"encoder takes one count per revolution or one per motor (2), got {_v.show(value)}")
    return vals[0] if len(vals) == 1 else tuple(vals)


class MaxError(Requirement):
    name = "error"
    options = (Option("max_error", "proven worst-case position error <= this everywhere on the task, a length "
                                   "with its unit (20um, 0.05mm); needs --error-model or --encoder",
                      check=lambda v, spec: _v.positive_length("max_error [um]", v),
                      parse=_acc.parse_length_um, metavar="LENGTH"),
               Option("error_model", "tolerances of --max-error and the error objective: a JSON or TOML file, "
                                     "or key=value pairs (encoder_counts=16384,clearance_um=5; keys as in "
                                     "`mechopt accuracy`)",
                      check=_model, parse=_acc.parse_error_model, metavar="FILE|KEY=VALUE,..."),
               Option("encoder", "encoder resolution of --max-error and the error objective, counts per "
                                 "revolution of each crank (16384), or one per motor (16384,4096); sets "
                                 "encoder_counts of --error-model",
                      check=_encoder, parse=str, metavar="COUNTS"))
    needs = ("points",)
    margin_text = "`--max-error`: the allowed position error minus the proven worst case over the task"
    margin_unit = "um"
    #: the value "no design satisfies" names (the least-violating design's error)
    reached_key = "error_um"
    certificate = ("each point's bound proven (first order over the tolerance box plus a proven second-order "
                   "remainder, mechopt.analysis.accuracy); the maximum over the task located on the samples and "
                   "refined by zooming (mechopt.analysis.sampling)")

    def precheck(self, req, spec, unit) -> None:
        if req.error_model is None and req.encoder is None:
            raise ValueError("max_error needs error_model (--error-model) or encoder (--encoder)")

    def screen(self, ctx) -> bool:
        return float(-_sampled(ctx).min()) * _acc.UM_PER_UNIT[ctx.unit] * SCREEN <= ctx.req.max_error

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
