"""Link angle: the angle of each link from the slider direction stays within
``[lo, hi]`` over the task (the biglide and the gantry; Wu 2008 eq. 1, 13).

The link angles of these mechanisms depend on x alone (``d/dy = 0``, no interior
extremum of x), so their extremes lie on ``dT``: the boundary samples refined by the
boundary zoom (:mod:`mechopt.analysis.sampling`).
"""
from __future__ import annotations

import math

from mechopt.core import validation as _v
from mechopt.requirements.base import Option, Requirement

__all__ = ["LinkAngle", "MEMBERS"]


def _check(value, spec):
    lo, hi = _v.finite_numbers("link_angle", value, 2, "(lo, hi) in rad")
    if not 0 <= lo < hi <= math.pi / 2:
        raise ValueError(f"link_angle must satisfy 0 <= lo < hi <= 90 deg, got {_v.show(value)}")
    return (lo, hi)


def _parse(text):
    """``LO,HI`` [deg] -> ``(lo, hi)`` [rad]."""
    vals = [math.radians(_v.finite_number("--link-angle (deg)", v)) for v in str(text).split(",")]
    if len(vals) != 2:
        raise ValueError(f"--link-angle (deg) must be 2 comma-separated numbers, got {text!r}")
    return tuple(vals)


class LinkAngle(Requirement):
    name = "link_angle"
    options = (Option("link_angle", "|link angle from the slider axis| limits [deg] (Wu: 15,75)",
                      check=_check, parse=_parse, metavar="LO,HI"),)
    needs = ("points", "joints")
    margin_text = "`--link-angle`: smallest distance of the link angles to their limits"
    margin_unit = "rad"
    certificate = "extremes on the task's boundary (angles depend on x alone), boundary samples refined by zooming"

    def applies(self, spec) -> bool:
        return spec.link_angles is not None

    def describe(self, req, unit) -> str:
        lo, hi = req.link_angle
        return f"link angles within [{math.degrees(lo):g}, {math.degrees(hi):g}] deg"

    def evaluate(self, ctx):
        lo_req, hi_req = ctx.req.link_angle
        ranges = ctx.leg_ranges(lambda x, y: ctx.spec.link_angles(ctx.mech, x, y), (0.0, -math.pi / 2))
        m = math.inf
        for leg, (lo, hi) in enumerate(ranges):
            ctx.derived[f"link_angle{leg + 1}"] = (lo, hi)
            m = min(m, lo - lo_req, hi_req - hi)
        return m, -m / (math.pi / 2)

    def columns(self, derived) -> dict:
        out = {}
        for leg in (1, 2):
            if f"link_angle{leg}" in derived:
                lo, hi = derived[f"link_angle{leg}"]
                out[f"link{leg}_angle_min_deg"], out[f"link{leg}_angle_max_deg"] = math.degrees(lo), math.degrees(hi)
        return out

    def record(self, derived) -> dict:
        return {f"link{leg}_angle_deg": [math.degrees(a) for a in derived[f"link_angle{leg}"]]
                for leg in (1, 2) if f"link_angle{leg}" in derived}


MEMBERS = (LinkAngle(),)
