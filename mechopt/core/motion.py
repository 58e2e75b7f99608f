"""Motions of the platform: the trapezoidal velocity profile of Wu 2008 sec. 6.2 and the
motion of Wu's Table 3 (read from ``mechopt/data/wu2008.csv``); paths (a straight
segment, a polyline read from a CSV file, the standard pick-and-place cycle) timed by a
profile (trapezoidal velocity, S-curve with limited jerk, cycloidal) within a cycle time.

A path is a list of pieces, each run from rest to rest: a straight segment (the
pick-and-place cycle's three: up, across, down) or a C2 curve (a natural cubic spline
through the points of a CSV file, parameterised by chord length, run as one piece). Each
piece ``k`` of length ``L_k`` takes ``T_k`` of the cycle with ``T_k`` proportional to
``sqrt(L_k)``: with one profile shape the peak acceleration ``~ L_k / T_k^2`` is then the
same on every piece. On a piece the travelled length is ``L_k s(t / T_k)`` with a
normalised profile ``s`` (:func:`profile`: ``s(0) = 0``, ``s(1) = 1``, ``s'(0) = s'(1) = 0``).

Units: those of the points ([L], times in s): speeds [L/s], accelerations [L/s^2]; the
Wu functions are in SI.
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import validation as _v

__all__ = ["trapezoidal_profile", "wu2008_trajectory", "PROFILES", "profile", "segment_path",
           "polyline_path", "read_path_csv", "pick_and_place_path", "timed_motion",
           "PICK_AND_PLACE_MM"]

#: the timing profiles of :func:`profile`
PROFILES = ("cycloidal", "trapezoidal", "s-curve")
#: the standard pick-and-place cycle [mm]: up, across, down (the "Adept cycle" of
#: industrial robot datasheets)
PICK_AND_PLACE_MM = (25.0, 305.0, 25.0)


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

    Raises
    ------
    ValueError
        For non-positive speed or acceleration, or non-finite points or times.
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
    ``n`` equally spaced times over ``[0, Tf]``; ``T0 = 0.150 s``, ``Tf = 0.650 s``.

    Parameters
    ----------
    n : int
        Number of times.

    Returns
    -------
    dict
        ``t`` [s], ``x, y`` [m], ``xd, yd`` [m/s], ``xdd, ydd`` [m/s^2] arrays
        (:func:`trapezoidal_profile`).
    """
    from mechopt.data import published_values

    pub = published_values("wu2008")
    val = {k: pub[("table3", k)][0] for k in ("x0", "y0", "x1", "y1", "v_max", "a_s")}
    n = _v.integer("n", n, 2)
    L = math.hypot(val["x1"] - val["x0"], val["y1"] - val["y0"])
    Tf = val["v_max"] / val["a_s"] + L / val["v_max"]
    return trapezoidal_profile((val["x0"], val["y0"]), (val["x1"], val["y1"]), val["v_max"],
                               val["a_s"], np.linspace(0.0, Tf, n))


def profile(kind, tau, accel_fraction: float = 1.0 / 3.0, jerk_fraction: float = 0.25):
    """Normalised rest-to-rest profile ``(s, s', s'')`` at ``tau`` in [0, 1] (clipped).

    ``"cycloidal"``: ``s = tau - sin(2 pi tau) / (2 pi)`` (zero acceleration at both
    ends; peak speed 2, peak acceleration 2 pi). ``"trapezoidal"``: constant acceleration
    over ``accel_fraction`` ``f`` of the time at each end (peak speed ``1/(1 - f)``,
    acceleration ``1/(f (1 - f))``). ``"s-curve"``: the same with the acceleration ramped
    at constant jerk over ``jerk_fraction`` ``r`` of each acceleration phase (peak
    acceleration ``1/((1 - f) f (1 - r))``, jerk that over ``r f``; ``r = 0`` is the
    trapezoid). Both have the cruise speed of the area condition
    ``v (1 - f) = 1`` (the speed curve of each acceleration phase is symmetric about its
    midpoint). Piecewise polynomial, evaluated exactly phase by phase.

    Parameters
    ----------
    kind : str
        ``"cycloidal"``, ``"trapezoidal"`` or ``"s-curve"``.
    tau : array_like
        Normalised time, in [0, 1].
    accel_fraction : float
        ``f``, in (0, 0.5].
    jerk_fraction : float
        ``r``, in [0, 0.5].

    Returns
    -------
    s, sd, sdd : ndarray
        Normalised position, speed and acceleration.

    Raises
    ------
    ValueError
        For an unknown kind or fractions out of range.
    """
    _v.choice("profile", kind, PROFILES)
    tau = np.clip(np.asarray(tau, dtype=float), 0.0, 1.0)
    if kind == "cycloidal":
        w = 2.0 * math.pi
        return tau - np.sin(w * tau) / w, 1.0 - np.cos(w * tau), w * np.sin(w * tau)
    f = _v.finite_number("accel_fraction", accel_fraction)
    if not 0.0 < f <= 0.5:
        raise ValueError(f"accel_fraction must lie in (0, 0.5], got {accel_fraction!r}")
    r = 0.0 if kind == "trapezoidal" else _v.finite_number("jerk_fraction", jerk_fraction)
    if not 0.0 <= r <= 0.5:
        raise ValueError(f"jerk_fraction must lie in [0, 0.5], got {jerk_fraction!r}")
    tj = r * f
    v = 1.0 / (1.0 - f)
    A = v / (f - tj)
    J = A / tj if tj > 0 else 0.0
    # (duration, acceleration at the start, jerk) of the seven phases
    phases = [(tj, 0.0, J), (f - 2 * tj, A, 0.0), (tj, A, -J), (1.0 - 2 * f, 0.0, 0.0),
              (tj, 0.0, -J), (f - 2 * tj, -A, 0.0), (tj, -A, J)]
    starts, state = [], []
    t0, s0, v0 = 0.0, 0.0, 0.0
    for d, a0, j in phases:
        starts.append(t0), state.append((s0, v0, a0, j))
        s0, v0 = s0 + v0 * d + a0 * d * d / 2 + j * d ** 3 / 6, v0 + a0 * d + j * d * d / 2
        t0 += d
    k = np.clip(np.searchsorted(np.array(starts), tau, side="right") - 1, 0, len(phases) - 1)
    st = np.array(state)[k]
    dt = tau - np.array(starts)[k]
    s0, v0, a0, j = st[..., 0], st[..., 1], st[..., 2], st[..., 3]
    return (s0 + v0 * dt + a0 * dt * dt / 2 + j * dt ** 3 / 6, v0 + a0 * dt + j * dt * dt / 2,
            a0 + j * dt)


class _Segment:
    """A straight piece from ``p0`` to ``p1`` [L]."""

    def __init__(self, p0, p1):
        self.p0 = np.array(_v.finite_numbers("p0", p0, 2, "a point (x, y)"), dtype=float)
        self.p1 = np.array(_v.finite_numbers("p1", p1, 2, "a point (x, y)"), dtype=float)
        self.length = float(np.hypot(*(self.p1 - self.p0)))
        if not self.length > 0:
            raise ValueError(f"a segment's end must differ from its start {tuple(self.p0)!r}")

    def __call__(self, u):
        """Point, first and second derivative in the length ``u`` [L] along the piece."""
        e = (self.p1 - self.p0) / self.length
        u = np.asarray(u, float)[..., None]
        return self.p0 + u * e, np.broadcast_to(e, u.shape[:-1] + (2,)), np.zeros(u.shape[:-1] + (2,))


class _Spline:
    """A natural cubic spline through points, parameterised by chord length [L]."""

    def __init__(self, points):
        from scipy.interpolate import CubicSpline

        P = np.asarray(points, dtype=float)
        if P.ndim != 2 or P.shape[1] != 2 or len(P) < 2 or not np.all(np.isfinite(P)):
            raise ValueError("a path needs at least two finite points (x, y)")
        d = np.hypot(*np.diff(P, axis=0).T)
        if not np.all(d > 0):
            raise ValueError("consecutive points of a path must differ")
        u = np.concatenate([[0.0], np.cumsum(d)])
        self.length = float(u[-1])
        self._s = CubicSpline(u, P, bc_type="natural" if len(P) > 2 else "not-a-knot")

    def __call__(self, u):
        return self._s(u), self._s(u, 1), self._s(u, 2)


def segment_path(p0, p1):
    """A path of one straight piece from ``p0`` to ``p1`` [L].

    Parameters
    ----------
    p0, p1 : tuple of float
        The ends [L].

    Returns
    -------
    list
        One piece (its ``length`` [L] and position/derivatives in arc length).
    """
    return [_Segment(p0, p1)]


def polyline_path(points):
    """A path of one C2 piece: the natural cubic spline through ``points`` ((n, 2) [L],
    n >= 2; two points give the segment), parameterised by chord length.

    Parameters
    ----------
    points : array_like
        Shape (n, 2) [L], n >= 2.

    Returns
    -------
    list
        One piece.
    """
    return [_Spline(points)]


def read_path_csv(path):
    """The points of a CSV file with columns ``x`` and ``y`` (a header row; other
    columns ignored) as an ``(n, 2)`` array [L].

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    ndarray
        Shape (n, 2) [L].

    Raises
    ------
    ValueError
        One line, for an unreadable file, missing columns or non-numeric values.
    """
    import csv

    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise ValueError(f"path file {str(path)!r} is not a readable CSV file: {e}") from None
    try:
        pts = np.array([(float(r["x"]), float(r["y"])) for r in rows])
    except (KeyError, TypeError, ValueError):
        raise ValueError(f"path file {str(path)!r} needs numeric columns x and y") from None
    if len(pts) < 2:
        raise ValueError(f"path file {str(path)!r} needs at least two points")
    return pts


def pick_and_place_path(box, contains=None):
    """The standard pick-and-place cycle (:data:`PICK_AND_PLACE_MM`: 25 up, 305 across,
    25 down) scaled to the task box ``(xmin, xmax, ymin, ymax)`` [L]: the across move
    spans the box's width (scale ``s = width / 305 mm``), the lift is ``25 s`` along +y,
    centred on the box's middle height; three straight pieces, each from rest to rest.
    With ``contains(x, y) -> bool array`` (a task region's test), the cycle is shrunk
    about the box's centre by ``0.95^k`` (the smallest ``k <= 40``) until its four corners
    lie in the region (a circle's or a polygon's bounding box is larger than it).

    Parameters
    ----------
    box : tuple of float
        ``(xmin, xmax, ymin, ymax)`` [L].
    contains : callable, optional
        ``contains(x, y) -> bool array``, a task region's test.

    Returns
    -------
    list
        Three straight pieces (up, across, down).

    Raises
    ------
    ValueError
        For an invalid box, or a region that no shrunk cycle fits in.
    """
    xmin, xmax, ymin, ymax = _v.finite_numbers("box", box, 4, "(xmin, xmax, ymin, ymax)")
    if not (xmax > xmin and ymax >= ymin):
        raise ValueError(f"box must have xmin < xmax and ymin <= ymax, got {box!r}")
    up, across, _ = PICK_AND_PLACE_MM
    cx, cy = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
    for k in range(41):
        half = 0.5 * (xmax - xmin) * 0.95 ** k
        lift = up * 2.0 * half / across
        x0, x1, y0 = cx - half, cx + half, cy - 0.5 * lift
        corners = np.array([(x0, y0), (x0, y0 + lift), (x1, y0 + lift), (x1, y0)])
        if contains is None or np.all(contains(corners[:, 0], corners[:, 1])):
            break
    return [_Segment(corners[i], corners[i + 1]) for i in range(3)]


def timed_motion(path, cycle_time, kind: str = "cycloidal", n: int = 401, **shape):
    """The path run within ``cycle_time`` [s] (module docstring), sampled at ``n`` equal
    time steps: dict of arrays ``t`` [s], ``x, y`` [L], ``xd, yd`` [L/s], ``xdd, ydd``
    [L/s^2], and ``piece`` (index of the piece). ``shape``: ``accel_fraction``,
    ``jerk_fraction`` of :func:`profile`.

    Parameters
    ----------
    path : list
        Pieces (:func:`segment_path`, :func:`polyline_path`, :func:`pick_and_place_path`).
    cycle_time : float
        Duration [s], > 0.
    kind : str
        Profile of each piece (:func:`profile`).
    n : int
        Number of time steps.
    **shape : 
        ``accel_fraction``, ``jerk_fraction`` of :func:`profile`.

    Returns
    -------
    dict
        The arrays named above.

    Raises
    ------
    ValueError
        For a non-positive cycle time or invalid settings.
    """
    T = _v.finite_number("cycle_time", cycle_time)
    if not T > 0:
        raise ValueError(f"cycle_time must be > 0 [s], got {cycle_time!r}")
    n = _v.integer("n", n, 2)
    _v.choice("profile", kind, PROFILES)
    L = np.array([p.length for p in path])
    dur = T * np.sqrt(L) / np.sum(np.sqrt(L))
    ends = np.cumsum(dur)
    t = np.linspace(0.0, T, n)
    k = np.minimum(np.searchsorted(ends, t, side="left"), len(path) - 1)
    out = {key: np.zeros(n) for key in ("x", "y", "xd", "yd", "xdd", "ydd")}
    for i, piece in enumerate(path):
        sel = k == i
        t0 = ends[i] - dur[i]
        s, sd, sdd = profile(kind, (t[sel] - t0) / dur[i], **shape)
        u, ud, udd = piece.length * s, piece.length * sd / dur[i], piece.length * sdd / dur[i] ** 2
        p, dp, ddp = piece(u)
        v = dp * ud[:, None]
        a = ddp * (ud * ud)[:, None] + dp * udd[:, None]
        out["x"][sel], out["y"][sel] = p[:, 0], p[:, 1]
        out["xd"][sel], out["yd"][sel] = v[:, 0], v[:, 1]
        out["xdd"][sel], out["ydd"][sel] = a[:, 0], a[:, 1]
    out["t"], out["piece"] = t, k
    return out
