"""One evaluation entry point for every mechanism: every number of ``mechopt evaluate``.

:func:`evaluate` returns an :class:`Evaluation`: the mechanism, its inputs (echoed)
and its values, which are

* for a mechanism symmetric about the y axis (``mech.disk_indices``, the five-bar):
  the MIC, the Liu 2006 global indices with a named quadrature, the usable
  workspace, the good-conditioning workspace (GCW), its largest centred square and
  the actuator ranges over it (:func:`disk_evaluation`, keys :data:`DISK_KEYS`);
* and the mechanism's own global numbers (``mech.summary()``: exact areas, means
  of the TQI, Wu's k_av and eta_D, ...), each naming its quadrature.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import validation as _v
from .mechanisms.base import Parameter
from .performance import global_indices, region_indices
from .quadrature import QUADRATURES
from .workspace import gcw, joint_ranges, largest_square, mic, usable_region

__all__ = ["DISK_KEYS", "DISK_OPTIONS", "Evaluation", "evaluate", "disk_evaluation"]

DISK_KEYS = (
    "r_mic", "mic_center_y", "gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min",
    "gsi_max", "gsi_min", "usable_area", "gcw_area", "gcw_gci", "gcw_gsi_max", "gcw_gsi_min",
    "gcw_square_side", "gcw_square_center_y", "theta1_range_deg", "theta2_range_deg",
    "quadrature", "mode", "gamma",
)
#: the options of :func:`disk_evaluation` (offered by ``mechopt evaluate`` for every
#: mechanism with ``disk_indices``)
DISK_OPTIONS = (
    Parameter("quadrature", "choice", "-", "rule of the disk means (GCI, GVI, GPI, GSI)", "area",
              QUADRATURES),
    Parameter("gamma", "fraction", "-", "LCI level bounding the good-conditioning workspace", 0.5),
)


@dataclass(frozen=True)
class Evaluation:
    """The result of :func:`evaluate` for any mechanism."""

    #: ``repr`` of the mechanism
    mechanism: str
    #: the values of its declared parameters and the evaluation options
    inputs: dict
    #: ``{name: value}``: floats, strings, ``[lo, hi]`` ranges or None
    values: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        """``{"mechanism": ..., "inputs": {...}, **values}`` (what ``--json`` prints)."""
        return {"mechanism": self.mechanism, "inputs": dict(self.inputs), **self.values}


def evaluate(mech, quadrature: str = "area", gamma: float = 0.5, step=None) -> Evaluation:
    """Every global number of ``mech`` (any :class:`~mechopt.PlanarMechanism`).

    ``quadrature`` and ``gamma`` are those of :func:`disk_evaluation` (used only for
    mechanisms with ``disk_indices``); ``step`` is the raster step [L] of the usable
    workspace and GCW (default ``length_scale/400``).
    """
    inputs = mech.parameter_values()
    values = {}
    if mech.disk_indices:
        values.update(disk_evaluation(mech, quadrature, gamma, step))
        inputs.update(quadrature=quadrature, gamma=float(values["gamma"]))
    values.update(mech.summary())
    return Evaluation(repr(mech), inputs, values)


def disk_evaluation(fb, quadrature: str = "area", gamma: float = 0.5, step=None) -> dict:
    """MIC, Liu 2006 global indices, usable workspace, GCW and its square and joint ranges.

    Parameters
    ----------
    fb : PlanarMechanism
        A mechanism symmetric about the y axis (``disk_indices``), e.g. a FiveBar.
    quadrature : {"area", "polar"}
        Rule for the disk means (GCI, GVI, GPI, GSI); the GCW means are area means.
    gamma : float
        LCI level bounding the good-conditioning workspace, in (0, 1).
    step : float, optional
        Raster step [L] of the usable workspace and GCW (default ``length_scale/400``).

    Returns a dict with :data:`DISK_KEYS`; ranges are ``[lo, hi]`` in degrees
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
    return {k: out[k] for k in DISK_KEYS}


def _range_deg(lo, hi):
    """``[lo, hi]`` in degrees, or ``None`` when the region is empty (NaN bounds)."""
    if np.isnan(lo):
        return None
    return [float(np.degrees(lo)), float(np.degrees(hi))]
