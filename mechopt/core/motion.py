"""Point-to-point motion profiles of the platform: the trapezoidal velocity profile of
Wu 2008 sec. 6.2 and the motion of Wu's Table 3 (read from ``mechopt/data/wu2008.csv``).

Units: SI (positions in m, speeds in m/s, accelerations in m/s^2, times in s).
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import validation as _v

__all__ = ["trapezoidal_profile", "wu2008_trajectory"]


def trapezoidal_profile(p0, p1, v_max, a_max, t):
    """Straight-line point-to-point motion: accelerate, cruise, decelerate (Wu sec. 6.2).

    Acceleration and deceleration last ``T0 = v_max / a_max`` each, the total time is
    ``Tf = T0 + |p1 - p0| / v_max`` (Wu eq. 45). If the path is too short to reach
    ``v_max`` the profile is triangular (peak speed ``sqrt(a_max |p1 - p0|)``).

    Parameters
    ----------
    p0, p1 : (float, float)
        Start and end points [m].
    v_max : float
        Cruise speed [m/s], > 0.
    a_max : float
        Acceleration magnitude [m/s^2], > 0.
    t : array_like
        Times [s]; clipped to ``[0, Tf]``.

    Returns
    -------
    dict with ``t``, ``x``, ``y``, ``xd``, ``yd``, ``xdd``, ``ydd`` (arrays) and ``T0``,
    ``Tf`` (floats).
    """
    v = _v.positive_length("v_max", v_max)
    a = _v.positive_length("a_max", a_max)
    x0, y0 = (_v.coordinate("p0", c) for c in _v.finite_numbers("p0", p0, 2, "a point (x, y)"))
    x1, y1 = (_v.coordinate("p1", c) for c in _v.finite_numbers("p1", p1, 2, "a point (x, y)"))
    L = math.hypot(x1 - x0, y1 - y0)
    if L == 0.0:
        raise ValueError(f"p1 must differ from p0 = {(x0, y0)!r}, got {(x1, y1)!r}")
    ex, ey = (x1 - x0) / L, (y1 - y0) / L
    if L < v * v / a:  # triangular
        v = math.sqrt(a * L)
    T0 = v / a
    Tf = T0 + L / v
    try:
        t = np.asarray(t)
    except (TypeError, ValueError):  # e.g. ragged lists
        t = np.asarray(None)
    if t.dtype.kind not in "biuf":
        raise ValueError(f"t must be a number or an array of numbers [s], got {_v.show(t)}")
    t = np.clip(t.astype(float), 0.0, Tf)
    s = np.where(t < T0, 0.5 * a * t * t,
                 np.where(t <= Tf - T0, 0.5 * a * T0 * T0 + v * (t - T0),
                          L - 0.5 * a * (Tf - t) ** 2))
    sd = np.where(t < T0, a * t, np.where(t <= Tf - T0, v, a * (Tf - t)))
    sdd = np.where(t < T0, a, np.where(t <= Tf - T0, 0.0, -a))
    return dict(t=t, x=x0 + ex * s, y=y0 + ey * s, xd=ex * sd, yd=ey * sd, xdd=ex * sdd,
                ydd=ey * sdd, T0=T0, Tf=Tf)


def wu2008_trajectory(n: int = 651):
    """The motion of Wu Table 3 (``(-0.25, 0.5) -> (0.25, 0.5)`` m, 1 m/s, 6.67 m/s^2) at
    ``n`` equally spaced times over ``[0, Tf]``; ``T0 = 0.150 s``, ``Tf = 0.650 s``."""
    from mechopt.data import published_values

    pub = published_values("wu2008")
    val = {k: pub[("table3", k)][0] for k in ("x0", "y0", "x1", "y1", "v_max", "a_s")}
    n = _v.integer("n", n, 2)
    L = math.hypot(val["x1"] - val["x0"], val["y1"] - val["y0"])
    Tf = val["v_max"] / val["a_s"] + L / val["v_max"]
    return trapezoidal_profile((val["x0"], val["y0"]), (val["x1"], val["y1"]), val["v_max"],
                               val["a_s"], np.linspace(0.0, Tf, n))
