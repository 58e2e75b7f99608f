"""Exact planar area primitives: disk lenses, annulus intersections, chords, boxes.

These are the closed forms behind the exact workspace areas of the Bipod
(:mod:`mechopt.mechanisms.bipod`, an intersection of two annuli) and the Biglide
(:mod:`mechopt.mechanisms.biglide`, strips bounded by circular arcs integrated
along x), and behind the exact GTQI of the Bipod (an area in actuator space).
Everything is vectorised over NumPy broadcasting; scalar inputs give NumPy
scalars. Lengths are in any consistent unit [L], areas in [L^2].

Formulas
--------
Lens (intersection of two disks of radii ``r_a``, ``r_b`` whose centres are ``d``
apart; Weisstein, "Circle-Circle Intersection", MathWorld)::

    d >= r_a + r_b            : 0
    d <= |r_a - r_b|          : pi min(r_a, r_b)^2
    otherwise                 : r_a^2 (alpha - sin(2 alpha)/2) + r_b^2 (beta - sin(2 beta)/2)
    cos alpha = (d^2 + r_a^2 - r_b^2) / (2 d r_a),  cos beta = (d^2 + r_b^2 - r_a^2) / (2 d r_b)

(``alpha``, ``beta`` are the half-angles of the two circular segments.)

Annulus intersection by inclusion-exclusion: with ``1_{Ann_i} = 1_{D(c_i, R_i)} -
1_{D(c_i, r_i)}`` (the inner disk lies inside the outer one)::

    |Ann_1 ^ Ann_2| = L(R1, R2) - L(r1, R2) - L(R1, r2) + L(r1, r2),   L = lens_area(., ., d).

Chord integral (area under a semicircle)::

    int_{u0}^{u1} sqrt(r^2 - u^2) du = F(u1) - F(u0),
    F(u) = (u sqrt(r^2 - u^2) + r^2 arcsin(u / r)) / 2,   u clipped to [-r, r].

Box cut by a 45-degree half-plane (ramp form, ``R(t) = max(t, 0)^2``)::

    |[a1,b1]x[a2,b2] ^ {x - y > c}| = (R(b1-a2-c) - R(b1-b2-c) - R(a1-a2-c) + R(a1-b2-c)) / 2
    |[a1,b1]x[a2,b2] ^ {x + y < c}| = (R(c-a1-a2) - R(c-b1-a2) - R(c-a1-b2) + R(c-b1-b2)) / 2

(inclusion-exclusion of the triangles ``{x < X, y > Y, x - y > c}`` of area
``R(X - Y - c)/2``, and likewise for the sum).
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "lens_area",
    "annuli_intersection_area",
    "HALF_PLANES",
    "chord_integral",
    "interval_overlap",
    "box_area_diff_above",
    "box_area_sum_below",
]

#: allowed values of ``half_plane`` in :func:`annuli_intersection_area`
HALF_PLANES = ("upper", "lower")


def _arrays(**named):
    """Broadcast named inputs to float arrays; raise a one-line ValueError on
    non-numeric, non-finite or non-broadcastable input."""
    out = {}
    for name, v in named.items():
        try:
            a = np.asarray(v, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be numeric, got {v!r}") from None
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} must be finite, got {v!r}")
        out[name] = a
    try:
        arrs = np.broadcast_arrays(*out.values())
    except ValueError:
        shapes = ", ".join(f"{k}{np.shape(a)}" for k, a in out.items())
        raise ValueError(f"inputs must broadcast to a common shape, got {shapes}") from None
    return arrs


def _nonneg(name, a):
    if np.any(a < 0):
        raise ValueError(f"{name} must be a non-negative radius, got {a.min()!r}")


def _scalar_or_array(a):
    return a[()] if a.ndim == 0 else a


def _segment_factor(t):
    """``t - sin(t) cos(t) = (2t - sin 2t)/2`` without cancellation for small ``t``."""
    x = 2.0 * t
    small = x < 1e-2
    xs = np.where(small, x, 0.0)
    series = xs**3 / 6.0 - xs**5 / 120.0 + xs**7 / 5040.0
    return 0.5 * np.where(small, series, x - np.sin(x))


def lens_area(r_a, r_b, d):
    """Area [L^2] of the intersection of two disks of radii ``r_a``, ``r_b`` [L]
    whose centres are ``d`` [L] apart (formula in the module docstring).

    Handles every relative position (disjoint, tangent, one inside the other,
    ``d = 0``, zero radii). Vectorised; raises ValueError for negative or
    non-finite input.

    Parameters
    ----------
    r_a, r_b : array_like
        The radii [L], >= 0.
    d : array_like
        Distance between the centres [L], >= 0.

    Returns
    -------
    ndarray or float
        The area [L^2].
    """
    r_a, r_b, d = _arrays(r_a=r_a, r_b=r_b, d=d)
    _nonneg("r_a", r_a)
    _nonneg("r_b", r_b)
    _nonneg("d", d)
    small = np.minimum(r_a, r_b)
    inside = d <= np.abs(r_a - r_b)
    apart = d >= r_a + r_b
    part = ~inside & ~apart  # implies d > 0, r_a > 0, r_b > 0
    ds = np.where(part, d, 1.0)
    ras = np.where(part, r_a, 1.0)
    rbs = np.where(part, r_b, 1.0)
    ca = np.clip((ds * ds + ras * ras - rbs * rbs) / (2.0 * ds * ras), -1.0, 1.0)
    cb = np.clip((ds * ds + rbs * rbs - ras * ras) / (2.0 * ds * rbs), -1.0, 1.0)
    seg = ras * ras * _segment_factor(np.arccos(ca)) + rbs * rbs * _segment_factor(np.arccos(cb))
    out = np.where(inside, np.pi * small * small, np.where(part, seg, 0.0))
    return _scalar_or_array(out)


def annuli_intersection_area(c1, r1_in, r1_out, c2, r2_in, r2_out, half_plane=None):
    """Area [L^2] of the intersection of two annuli, by inclusion-exclusion of lenses.

    Parameters
    ----------
    c1, c2 : array_like, shape (..., 2)
        Centres ``(x, y)`` [L].
    r1_in, r1_out, r2_in, r2_out : array_like
        Inner and outer radii [L], ``0 <= r_in <= r_out`` (``r_in = 0`` is a disk).
    half_plane : {None, "upper", "lower"}
        Restrict to ``y > 0`` or ``y < 0``. Allowed only when both centres lie on
        the x axis: the intersection is then symmetric about it and the result
        is exactly half of the whole area.

    Returns
    -------
    ndarray or float
        The area [L^2], broadcast over all inputs (formula in the module docstring).

    Raises
    ------
    ValueError
        For centres that are not finite points, negative radii, an inner radius above
        the outer one, an unknown ``half_plane`` or one with a centre off the x axis.
    """
    c1 = np.asarray(c1, dtype=float)
    c2 = np.asarray(c2, dtype=float)
    if c1.shape[-1:] != (2,) or c2.shape[-1:] != (2,):
        raise ValueError(
            f"c1 and c2 must have shape (..., 2), got {c1.shape} and {c2.shape}"
        )
    if not (np.all(np.isfinite(c1)) and np.all(np.isfinite(c2))):
        raise ValueError(f"c1 and c2 must be finite, got {c1.tolist()!r} and {c2.tolist()!r}")
    d = np.hypot(c2[..., 0] - c1[..., 0], c2[..., 1] - c1[..., 1])
    r1i, r1o, r2i, r2o, d = _arrays(r1_in=r1_in, r1_out=r1_out, r2_in=r2_in, r2_out=r2_out, d=d)
    for name, a in (("r1_in", r1i), ("r2_in", r2i)):
        _nonneg(name, a)
    if np.any(r1i > r1o):
        raise ValueError(f"r1_out must be >= r1_in, got r1_in={r1_in!r}, r1_out={r1_out!r}")
    if np.any(r2i > r2o):
        raise ValueError(f"r2_out must be >= r2_in, got r2_in={r2_in!r}, r2_out={r2_out!r}")
    area = (
        np.asarray(lens_area(r1o, r2o, d))
        - lens_area(r1i, r2o, d)
        - lens_area(r1o, r2i, d)
        + lens_area(r1i, r2i, d)
    )
    area = np.maximum(area, 0.0)  # rounding of nearly-cancelling terms
    if half_plane is not None:
        if half_plane not in HALF_PLANES:
            raise ValueError(
                f"half_plane must be one of None, 'upper', 'lower', got {half_plane!r}"
            )
        if np.any(c1[..., 1] != 0.0) or np.any(c2[..., 1] != 0.0):
            raise ValueError(
                "half_plane needs both centres on the x axis (y = 0), got "
                f"c1={c1.tolist()!r}, c2={c2.tolist()!r}"
            )
        area = 0.5 * area
    return _scalar_or_array(np.asarray(area))


def chord_integral(r, u0, u1):
    """``int_{u0}^{u1} sqrt(max(r^2 - u^2, 0)) du`` [L^2], exactly.

    The area between the u axis and a half circle of radius ``r`` [L] centred at
    ``u = 0``, over ``[u0, u1]``; the limits are clipped to ``[-r, r]`` (the
    integrand is 0 outside). Negative if ``u1 < u0``.

    Parameters
    ----------
    r : array_like
        The radius [L], >= 0.
    u0, u1 : array_like
        The limits [L].

    Returns
    -------
    ndarray or float
        The integral [L^2] (negative when ``u1 < u0``).
    """
    r, u0, u1 = _arrays(r=r, u0=u0, u1=u1)
    _nonneg("r", r)

    def F(u):
        u = np.clip(u, -r, r)
        with np.errstate(invalid="ignore", divide="ignore"):
            s = np.where(r > 0, np.clip(u / np.where(r > 0, r, 1.0), -1.0, 1.0), 0.0)
        return 0.5 * (u * np.sqrt(np.maximum(r * r - u * u, 0.0)) + r * r * np.arcsin(s))

    return _scalar_or_array(F(u1) - F(u0))


def interval_overlap(lo1, hi1, lo2, hi2):
    """Length of ``[lo1, hi1] ^ [lo2, hi2]``: ``max(0, min(hi1, hi2) - max(lo1, lo2))``.

    Parameters
    ----------
    lo1, hi1 : array_like
        The first interval.
    lo2, hi2 : array_like
        The second interval.

    Returns
    -------
    ndarray or float
        The length (0 when disjoint).
    """
    lo1, hi1, lo2, hi2 = (np.asarray(v, dtype=float) for v in (lo1, hi1, lo2, hi2))
    out = np.maximum(0.0, np.minimum(hi1, hi2) - np.maximum(lo1, lo2))
    return _scalar_or_array(np.asarray(out))


def _ramp2(t):
    return np.square(np.maximum(t, 0.0))


def box_area_diff_above(a1, b1, a2, b2, c):
    """Area of ``{(x, y) in [a1, b1] x [a2, b2] : x - y > c}`` (ramp form, module docstring).

    Parameters
    ----------
    a1, b1 : array_like
        The x range.
    a2, b2 : array_like
        The y range.
    c : array_like
        The threshold.

    Returns
    -------
    ndarray or float
        The area.
    """
    a1, b1, a2, b2, c = (np.asarray(v, dtype=float) for v in (a1, b1, a2, b2, c))
    out = 0.5 * (_ramp2(b1 - a2 - c) - _ramp2(b1 - b2 - c) - _ramp2(a1 - a2 - c)
                 + _ramp2(a1 - b2 - c))
    return _scalar_or_array(np.asarray(out))


def box_area_sum_below(a1, b1, a2, b2, c):
    """Area of ``{(x, y) in [a1, b1] x [a2, b2] : x + y < c}`` (ramp form, module docstring).

    Parameters
    ----------
    a1, b1 : array_like
        The x range.
    a2, b2 : array_like
        The y range.
    c : array_like
        The threshold.

    Returns
    -------
    ndarray or float
        The area.
    """
    a1, b1, a2, b2, c = (np.asarray(v, dtype=float) for v in (a1, b1, a2, b2, c))
    out = 0.5 * (_ramp2(c - a1 - a2) - _ramp2(c - b1 - a2) - _ramp2(c - a1 - b2)
                 + _ramp2(c - b1 - b2))
    return _scalar_or_array(np.asarray(out))
