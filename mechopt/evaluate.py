"""One-call evaluation of a five-bar design: every number of ``mechopt evaluate five-bar``."""
from __future__ import annotations

import numpy as np

from . import validation as _v
from .performance import global_indices, region_indices
from .quadrature import QUADRATURES
from .workspace import gcw, joint_ranges, largest_square, mic, usable_region

__all__ = ["FIVE_BAR_KEYS", "evaluate_five_bar"]

FIVE_BAR_KEYS = (
    "r_mic", "mic_center_y", "gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min",
    "gsi_max", "gsi_min", "usable_area", "gcw_area", "gcw_gci", "gcw_gsi_max", "gcw_gsi_min",
    "gcw_square_side", "gcw_square_center_y", "theta1_range_deg", "theta2_range_deg",
    "quadrature", "mode", "gamma",
)


def evaluate_five_bar(fb, quadrature: str = "area", gamma: float = 0.5, step=None) -> dict:
    """MIC, Liu 2006 global indices, usable workspace, GCW and its square and joint ranges.

    Parameters
    ----------
    fb : FiveBar
    quadrature : {"area", "polar"}
        Rule for the disk means (GCI, GVI, GPI, GSI); the GCW means are area means.
    gamma : float
        LCI level bounding the good-conditioning workspace, in (0, 1).
    step : float, optional
        Raster step [L] of the usable workspace and GCW (default ``length_scale/400``).

    Returns a dict with :data:`FIVE_BAR_KEYS`; ranges are ``[lo, hi]`` in degrees
    over the GCW. An empty GCW (no usable point with LCI >= gamma, e.g. Liu's
    (0.4, 2.33, 0.27)) is a result: ``gcw_area = 0``, ``gcw_square_side = 0``, NaN
    GCW means and square centre, ``None`` ranges; the MIC indices are still given.
    """
    _v.choice("quadrature", quadrature, QUADRATURES)
    gamma = _v.open_unit_interval("gamma", gamma)
    m = mic(fb)
    out = global_indices(fb, quadrature, mic=m)
    usable = usable_region(fb, step=step, center=(0.0, m.center_y))
    good = gcw(fb, gamma, usable)
    side, cy = largest_square(good)
    (t1lo, t1hi), (t2lo, t2hi) = joint_ranges(fb, good)
    reg = region_indices(fb, good)
    out.update(
        usable_area=usable.area,
        gcw_area=good.area,
        gcw_gci=reg["gci"],
        gcw_gsi_max=reg["gsi_max"],
        gcw_gsi_min=reg["gsi_min"],
        gcw_square_side=side,
        gcw_square_center_y=cy,
        theta1_range_deg=_range_deg(t1lo, t1hi),
        theta2_range_deg=_range_deg(t2lo, t2hi),
        quadrature=quadrature,
        mode=fb.mode,
        gamma=gamma,
    )
    return {k: out[k] for k in FIVE_BAR_KEYS}


def _range_deg(lo, hi):
    """``[lo, hi]`` in degrees, or ``None`` when the region is empty (NaN bounds)."""
    if np.isnan(lo):
        return None
    return [float(np.degrees(lo)), float(np.degrees(hi))]
