"""One evaluation entry point for every mechanism: every number of ``mechopt evaluate``.

:func:`evaluate` returns an :class:`Evaluation`: the mechanism, its inputs (echoed)
and its values, which are

* for a mechanism symmetric about the y axis (``mech.disk_indices``, the five-bar):
  the MIC, the Liu 2006 global indices with a named quadrature, the usable
  workspace, the good-conditioning workspace (GCW), its largest centred square and
  the actuator ranges over it (:func:`disk_evaluation`, keys :data:`DISK_KEYS`);
* and the mechanism's own global numbers (``mech.summary()``: exact areas, means
  of the TQI, Wu's k_av and eta_D, ...), each naming its quadrature.

Units. Every index is scale invariant and lengths, areas, ... scale as ``D``,
``D^2``, ... when every length of a design is multiplied by ``D`` (Liu 2006 eq. 20),
so a design is evaluated in units of its size: divided by the power of two nearest
its ``length_scale`` (:func:`unit_of`), evaluated, and its values multiplied back
by that unit to their powers (:func:`disk_powers`, the mechanism's declared
``summary_powers``). A power
of two is exact in floating point and these computations are homogeneous, so the
values are those of the direct evaluation bit for bit (``tests/test_limits.py``)
while designs of every admissible size (lengths in [1e-12, 1e12], e.g. all 1e-12 or
(1e12, 1e12, 0)) are computed on numbers of order 1. What still cannot be evaluated
(a workspace thinner than double precision or the raster resolves, legs that never
meet) raises a one-line ValueError naming the design as given and the condition on
its inputs that fails.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from mechopt.core import validation as _v
from mechopt.analysis import workspace as _ws
from mechopt.core.indices import GLOBAL_INDEX_NAMES
from mechopt.core.protocol import Parameter
from mechopt.analysis.performance import global_indices, region_indices
from mechopt.core.quadrature import MAX_NODES, QUADRATURES
from mechopt.analysis.workspace import gcw, joint_ranges, largest_square

__all__ = ["DISK_KEYS", "DISK_OPTIONS", "disk_powers", "Evaluation", "evaluate",
           "disk_evaluation", "unit_of"]

DISK_KEYS = (
    "r_mic", "mic_center_y", *GLOBAL_INDEX_NAMES, "usable_area", "gcw_area", "gcw_gci", "gcw_gsi_max", "gcw_gsi_min",
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


def disk_powers(mech) -> dict:
    """``{key: p}``: the value ``key`` of :func:`disk_evaluation` of the design scaled by
    ``D`` is ``D**p`` times that of the design (the other keys are not numbers). With
    angular joints J scales as ``1/D`` (velocities as ``D``, efforts as ``1/D``,
    compliances as ``D^2``); with prismatic ones J is invariant.

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with ``disk_indices``.

    Returns
    -------
    dict
        ``{key: p}`` (integers).
    """
    a = 1 if mech.angular_joints else 0
    return {"r_mic": 1, "mic_center_y": 1, "gci": 0, "mci": 0, "gvi_max": a, "gvi_min": a,
            "gpi_max": -a, "gpi_min": -a, "gsi_max": 2 * a, "gsi_min": 2 * a, "usable_area": 2,
            "gcw_area": 2, "gcw_gci": 0, "gcw_gsi_max": 2 * a, "gcw_gsi_min": 2 * a,
            "gcw_square_side": 1, "gcw_square_center_y": 1}


#: the unit of :func:`unit_of` is ``2**k`` with ``|k| <= 39``: its inverse is itself an
#: admissible scale factor (``validation.LENGTH_MIN <= 2**-39``, ``2**39 <= LENGTH_MAX``)
_UNIT_EXPONENT_MAX = 39


def unit_of(mech) -> float:
    """The power of two nearest ``mech.length_scale`` (within ``2**+-39``): the unit a
    design is evaluated in (1.0 for designs of size about 1).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.

    Returns
    -------
    float
        ``2**k`` [L]; 1.0 when the length scale is not a positive finite number.
    """
    L = float(mech.length_scale)
    if not (L > 0.0 and math.isfinite(L)):
        return 1.0
    k = max(-_UNIT_EXPONENT_MAX, min(_UNIT_EXPONENT_MAX, round(math.log2(L))))
    return math.ldexp(1.0, k)


def _in_unit(mech, unit):
    """``mech`` with its lengths divided by ``unit`` (a power of two: exact), or None if
    the result is not an admissible design (a length below 1e-12 of a mixed design)."""
    if unit == 1.0:
        return mech
    try:
        return mech.scaled(1.0 / unit)
    except ValueError:
        return None


def _scale_back(values: dict, powers: dict, unit: float) -> dict | None:
    """Values in the unit ``unit`` -> values in the design's own units (None if a
    float value has no declared power)."""
    out = {}
    for key, v in values.items():
        if isinstance(v, float):
            p = powers.get(key)
            if p is None:
                return None
            v = v * unit ** p if p else v
        out[key] = v
    return out


@dataclass(frozen=True)
class Evaluation:
    """The result of :func:`evaluate` for any mechanism.

    Parameters
    ----------
    mechanism : str
        ``repr`` of the mechanism.
    inputs : dict
        The values of its declared parameters and the evaluation options.
    values : dict
        ``{name: value}``: floats (in the design's units, :doc:`outputs` gives each),
        strings, ``[lo, hi]`` ranges or None.
    """

    #: ``repr`` of the mechanism
    mechanism: str
    #: the values of its declared parameters and the evaluation options
    inputs: dict
    #: ``{name: value}``: floats, strings, ``[lo, hi]`` ranges or None
    values: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        """The evaluation as one dict (what ``--json`` prints).

        Returns
        -------
        dict
            ``{"mechanism": ..., "inputs": {...}, **values}``.
        """
        return {"mechanism": self.mechanism, "inputs": dict(self.inputs), **self.values}


def evaluate(mech, quadrature: str = "area", gamma: float = 0.5, step=None) -> Evaluation:
    """Every global number of ``mech`` (any :class:`~mechopt.PlanarMechanism`).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism, however it was built (constructor, ``from_parameters``,
        ``scaled``, ``with_mode``).
    quadrature : {"area", "polar"}
        Rule of the disk means (mechanisms with ``disk_indices`` only; Liu 2006 used
        "polar").
    gamma : float
        LCI level bounding the good-conditioning workspace, in (0, 1) (mechanisms
        with ``disk_indices`` only).
    step : float, optional
        Raster step [L] of the usable workspace and GCW (default
        ``length_scale/400``).

    Returns
    -------
    Evaluation
        The mechanism's ``repr``, its inputs and every number: for ``disk_indices``
        mechanisms those of :func:`disk_evaluation`, then its own ``summary()``
        (computed in a power-of-two unit near its size, :func:`unit_of`, and scaled
        back).

    Raises
    ------
    ValueError
        One line, for invalid options or a design whose numbers do not exist (no MIC,
        a workspace too thin for the raster).
    """
    inputs = mech.parameter_values()
    values = {}
    if mech.disk_indices:
        values.update(disk_evaluation(mech, quadrature, gamma, step))
        inputs.update(quadrature=quadrature, gamma=float(values["gamma"]))
    values.update(_summary(mech))
    return Evaluation(repr(mech), inputs, values)


def _summary(mech) -> dict:
    """``mech.summary()``, computed in the unit of :func:`unit_of` where its numbers'
    powers are declared (``mech.summary_powers``), else as given (and on any error
    as given, so that the message names the design's own values)."""
    powers = mech.summary_powers
    unit = unit_of(mech)
    if powers is not None and unit != 1.0:
        scaled = _in_unit(mech, unit)
        if scaled is not None:
            try:
                out = _scale_back(scaled.summary(), powers, unit)
            except ValueError:
                out = None
            if out is not None:
                return out
    return mech.summary()


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
        Raster step [L] of the usable workspace and GCW (default ``length_scale/400``),
        any positive size giving at most ``quadrature.MAX_NODES`` cells (the error
        names the smallest step that does).

    Returns
    -------
    dict
        The keys :data:`DISK_KEYS` (lengths [L], areas [L^2], indices
        dimensionless); ranges are ``[lo, hi]`` in degrees over the GCW. An empty GCW
        (no usable point with LCI >= gamma, e.g. Liu's (0.4, 2.33, 0.27)) is a
        result: ``gcw_area = 0``, ``gcw_square_side = 0``, NaN GCW means and square
        centre, ``None`` ranges; the MIC indices are still given.

    Raises
    ------
    ValueError
        One line naming the design's inputs, when it has no MIC or a usable
        workspace too thin for the raster (see
        :func:`mechopt.analysis.workspace.no_mic_message` and
        :func:`mechopt.analysis.workspace.unusable_message`).
    """
    _v.choice("quadrature", quadrature, QUADRATURES)
    gamma = _v.open_unit_interval("gamma", gamma)
    if step is not None:
        step = _v.positive_size("step", step)
        if step > _v.LENGTH_MAX:
            raise ValueError(f"step must lie in (0, {_v.LENGTH_MAX:g}], got {_v.show(step)}")
    unit = unit_of(fb)
    design = _in_unit(fb, unit)
    if design is None:
        design, unit = fb, 1.0
    if step is not None:
        _check_raster(fb, step)
    m = _ws._mic(design)  # the mechanism's explicit MIC if it has one, else the rays method
    if m is None:
        raise ValueError(_ws.no_mic_message(fb))
    out = global_indices(design, quadrature, mic=m)
    nstep = _ws._default_step(design) if step is None else step / unit
    usable = _ws._usable_region(design, nstep, (0.0, m.center_y))
    if usable is None:
        raise ValueError(_ws.unusable_message(fb, nstep * unit, (0.0, m.center_y * unit),
                                              given_step=step is not None, r_mic=m.radius * unit))
    good = gcw(design, gamma, usable)
    side, cy = largest_square(good)
    (t1lo, t1hi), (t2lo, t2hi) = joint_ranges(design, good)
    reg = region_indices(design, good)
    out.update(
        usable_area=usable.area,
        gcw_area=good.area,
        gcw_gci=reg["gci"],
        gcw_gsi_max=reg["gsi_max"],
        gcw_gsi_min=reg["gsi_min"],
        gcw_square_side=side,
        gcw_square_center_y=cy,
    )
    out = {k: float(v) for k, v in out.items()}
    out = _scale_back(out, disk_powers(fb), unit)
    out.update(
        theta1_range_deg=_range_deg(t1lo, t1hi),
        theta2_range_deg=_range_deg(t2lo, t2hi),
        quadrature=quadrature,
        mode=fb.mode,
        gamma=gamma,
    )
    return {k: out[k] for k in DISK_KEYS}


def _check_raster(fb, step):
    """A ``step`` giving more than ``MAX_NODES`` cells over the workspace's box is
    refused here, in the design's own units, with the smallest step that works."""
    xmin, xmax, _, ymax = fb.bounding_box()
    w, h = max(xmax - xmin, 0.0), max(ymax, 0.0)
    fx, fy = w / step, h / step
    if not (math.isfinite(fx) and math.isfinite(fy)) or \
            max(math.ceil(fx), 1) * max(math.ceil(fy), 1) > MAX_NODES:
        # (w/s + 1)(h/s + 1) <= N for s >= ((w + h) + sqrt((w + h)^2 + 4 (N - 1) w h)) / (2 (N - 1))
        n = MAX_NODES - 1
        smallest = ((w + h) + math.sqrt((w + h) ** 2 + 4.0 * n * w * h)) / (2.0 * n)
        raise ValueError(f"step {step!r} gives a raster of more than {MAX_NODES:.0e} cells over the "
                         f"workspace of {fb!r}: use a step of at least {_round_up(smallest)}")


def _round_up(x, digits=3):
    """``x`` rounded up to ``digits`` significant digits, as text."""
    q = 10.0 ** (math.floor(math.log10(x)) - digits + 1)
    return f"{math.ceil(x / q) * q:.{digits}g}"


def _range_deg(lo, hi):
    """``[lo, hi]`` in degrees, or ``None`` when the region is empty (NaN bounds)."""
    if np.isnan(lo):
        return None
    return [float(np.degrees(lo)), float(np.degrees(hi))]
