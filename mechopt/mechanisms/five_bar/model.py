"""The symmetric five-bar (5R) planar parallel mechanism.

Geometry (Liu 2006 Fig. 1; Le 2013 Fig. 1): base joints
``A1 = (-r3, 0)`` and ``A2 = (r3, 0)`` (``r3`` is HALF the base distance, Le's
``l0``, Liu's ``R3``); cranks ``A_i B_i`` of length ``r1`` (actuated angles
``theta_i`` from the x axis); distal links ``B_i P`` of length ``r2``.

Working modes (Le 2013 eq. 17-18): with ``beta1 = atan2(y, x + r3)``,
``beta2 = atan2(y, r3 - x)`` and ``alpha_i`` the law-of-cosines angle at ``A_i``
(eq. 13-14),

    theta1 = beta1 (+/-) alpha1,     theta2 = pi - beta2 (+/-) alpha2,

the first sign of the mode string applying to leg 1 and the second to leg 2. The
default ``"+-"`` has both elbows outward and is the mode of Liu's numbers.
Geometrically the elbow is ``B_i = A_i + r1 R(s_i alpha_i) (P - A_i)/|P - A_i|``
with ``s_i = +1`` for ``"+"``; the fast kernels use that form (no trigonometry).
"""
from __future__ import annotations

import numpy as np

from mechopt.mechanisms.five_bar import lci as _fast_lci
from mechopt.core import rigid_bodies as _b
from mechopt.core import validation as _v
from mechopt.core.bodies import GROUND, Body, Shapes
from mechopt.core.design_spec import DesignSpec
from mechopt.core.error_spec import ErrorSpec
from mechopt.core.jit import Twin, jitable, select, twin_params
from mechopt.core.kinematic_tree import BASE, CLOSURE_NAMES, ClosureFrame, KinematicTree, TreeJoint
from mechopt.core.indices import lci_of_matrix
from mechopt.core.protocol import ASSEMBLY_MODES, Parameter, PlanarMechanism, as_points
from mechopt.core.zoom import ZoomKernel, point_in_reach, zoom_minimum, zoom_ranges

__all__ = ["FiveBar", "FiveBarDesignSpec", "FiveBarErrorSpec", "MODES", "ASSEMBLY_MODES", "elbow_signs", "legs_elbows",
           "legs_closure", "legs_closure_enclosure", "legs_actuator_enclosure", "legs_reachable", "legs_serial_clearance", "legs_bounding_box",
           "legs_ik", "legs_fk",
           "legs_assembly_of", "legs_tree", "legs_tree_configuration",
           "legs_bodies", "legs_body_frames"]

MODES = ("+-", "-+", "++", "--")
_SIGN = {"+": 1.0, "-": -1.0}
#: reachability tolerance on ``h^2`` of the elbow intersection: rounding on the
#: boundary of a leg's annulus is clipped to the boundary itself
_H2_TOL = _v.ROUNDING


# --- the geometry of a 5R with legs of any lengths -------------------------------
# Written once for FiveBar (equal legs) and AsymmetricFiveBar (each leg its own): every
# function takes the half base ``r3`` and ``legs = ((a1, c1, s1), (a2, c2, s2))``, leg i
# with the crank ``a_i`` on ``A_i`` (``A1 = (-r3, 0)``, ``A2 = (r3, 0)``), the distal link
# ``c_i`` and the elbow sign ``s_i`` of the working mode (Le 2013 eq. 5-19 with ``r1, r2``
# read per leg). With equal legs every operation is that of Le's symmetric closed forms (in
# ``legs_fk`` the foot ``u`` is then exactly 1/2), so the generality costs FiveBar no bit.

def elbow_signs(mode: str):
    """``(s1, s2)`` of a working mode: ``+1`` for ``"+"``, ``-1`` for ``"-"``, leg 1 first.

    Parameters
    ----------
    mode : str
        A working mode (``"+-"``, ...).

    Returns
    -------
    tuple of int
        ``(s1, s2)``.
    """
    return _SIGN[mode[0]], _SIGN[mode[1]]


def legs_elbows(x, y, r3, legs):
    """Elbows ``(b1x, b1y, b2x, b2y, reachable)`` by circle intersection; NaN where unreachable.

    ``B_i = A_i + a_i R(s_i alpha_i) (P - A_i)/|P - A_i|`` with ``alpha_i`` from the law
    of cosines at ``A_i`` (Le eq. 13-14), without trigonometry.

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L].
    y : array_like
        Ordinates [L]; broadcast with ``x``.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    b1x, b1y, b2x, b2y : ndarray
        The elbows [L].
    reachable : ndarray of bool
        Where both legs assemble.
    """
    x, y = as_points(x, y)
    (a1, c1, s1), (a2, c2, s2) = legs
    p = _twin_legs(r3, legs)
    if p is not None:
        xf, yf = x.reshape(-1), y.reshape(-1)
        out, ok = np.empty((4, xf.size)), np.empty(xf.size, dtype=np.bool_)
        _ELBOWS_TWIN(xf, yf, p, out, ok)
        return (*(v.reshape(x.shape) for v in out), ok.reshape(x.shape))
    # P at A_i (0/0) and inf * 0 at a base joint: masked below by ``ok``
    with Twin.numpy_timer(), np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        b1x, b1y, ok1 = _leg_elbow(-r3, a1, c1, s1, x, y)
        b2x, b2y, ok2 = _leg_elbow(r3, a2, c2, s2, x, y)
        ok = ok1 & ok2
        b1x, b1y, b2x, b2y = (np.where(ok, v, np.nan) for v in (b1x, b1y, b2x, b2y))
    return b1x, b1y, b2x, b2y, ok


def _twin_legs(r3, legs):
    """``[r3, a1, c1, s1, a2, c2, s2]`` for the compiled twins when they run
    (:meth:`mechopt.core.jit.Twin.compiled`) and every length is a number; None otherwise
    (lengths as arrays, a caller broadcasting designs: the NumPy path)."""
    (a1, c1, s1), (a2, c2, s2) = legs
    return twin_params((r3, a1, c1, s1, a2, c2, s2))


@jitable
def _legs_of(p):
    """``[r3, a1, c1, s1, a2, c2, s2]`` as a tuple (compiled loops and zooms): a tuple is
    passed by value to the per-point formulas, an array is reference-counted at every
    call (:mod:`mechopt.core.zoom`)."""
    return p[0], p[1], p[2], p[3], p[4], p[5], p[6]


@jitable
def _leg_elbow(ax, a, c, s, x, y):
    """Elbow ``(bx, by, reachable)`` of the leg on ``A = (ax, 0)`` with crank ``a``, link
    ``c`` and elbow sign ``s`` at the point ``(x, y)`` (:func:`legs_elbows`; arrays or, in
    the compiled loop, floats)."""
    dx = x - ax
    dsq = dx * dx + y * y
    # law of cosines at A_i (Le eq. 13-14), scaled by a/d
    k = (a * a + dsq - c * c) / (2.0 * dsq)  # = a cos(alpha) / d
    h2 = (a * a) / dsq - k * k  # = (a sin(alpha) / d)^2
    # reachable <=> |a - c| <= d <= a + c (Le eq. 19); tiny negative h2 from
    # rounding on the boundary is clipped to the boundary itself.
    ok = (h2 >= -_H2_TOL) & (dsq > 0)
    h = np.sqrt(np.maximum(h2, 0.0)) * s
    return ax + k * dx - h * y, k * y + h * dx, ok


@jitable
def _elbows_at(x, y, legs):
    """``(b1x, b1y, b2x, b2y, reachable)`` at one point, NaN where unreachable
    (:func:`legs_elbows`; ``legs = [r3, a1, c1, s1, a2, c2, s2]``, compiled loops only)."""
    r3 = legs[0]
    b1x, b1y, ok1 = _leg_elbow(-r3, legs[1], legs[2], legs[3], x, y)
    b2x, b2y, ok2 = _leg_elbow(r3, legs[4], legs[5], legs[6], x, y)
    if ok1 and ok2:
        return b1x, b1y, b2x, b2y, True
    return np.nan, np.nan, np.nan, np.nan, False


def _elbows_loop(x, y, legs, out, ok):
    """:func:`legs_elbows` point by point (compiled, :class:`mechopt.core.jit.Twin`;
    ``legs = [r3, a1, c1, s1, a2, c2, s2]``): the elbows into the rows of ``out``
    (``b1x, b1y, b2x, b2y``), reachability into ``ok``."""
    lp = _legs_of(legs)
    for i in range(x.size):
        out[0, i], out[1, i], out[2, i], out[3, i], ok[i] = _elbows_at(x[i], y[i], lp)


@jitable
def _closure_at(x, y, legs):
    """:func:`legs_closure` at one point (compiled kernels; ``legs = [r3, a1, c1, s1, a2,
    c2, s2]``): ``(a1x, a1y, a2x, a2y, b1, b2, ok)``, ``A``'s rows and ``B``'s diagonal by
    the NumPy path's operations, NaN where unreachable."""
    r3 = legs[0]
    b1x, b1y, b2x, b2y, ok = _elbows_at(x, y, legs)
    a1x, a1y, a2x, a2y = x - b1x, y - b1y, x - b2x, y - b2y
    return a1x, a1y, a2x, a2y, (b1x + r3) * a1y - b1y * a1x, (b2x - r3) * a2y - b2y * a2x, ok


def _closure_loop(x, y, legs, A, b, ok):
    """:func:`legs_closure` point by point (compiled, :class:`mechopt.core.jit.Twin`;
    :func:`_closure_at`): its ``A`` (shape ``(n, 2, 2)``), ``b`` (``(n, 2)``) and
    reachability."""
    lp = _legs_of(legs)
    for i in range(x.size):
        A[i, 0, 0], A[i, 0, 1], A[i, 1, 0], A[i, 1, 1], b[i, 0], b[i, 1], ok[i] = _closure_at(x[i], y[i], lp)


@jitable
def _ik_cosines_at(legs, x, y):
    """:func:`legs_ik` at one point up to its angles (``legs = [r3, a1, c1, s1, a2, c2,
    s2]``): ``(k1, k2, ok)``, the clipped cosines of ``alpha_i`` (0 where a leg does
    not assemble) and :func:`legs_reachable`. ``arccos`` and ``arctan2`` stay with NumPy
    (:func:`_ik_angles`): its vectorised versions (SIMD, where the CPU has them) differ
    from the C library's, which a compiled loop calls, in the last bit at about one
    point in ten."""
    r3, a1, c1, a2, c2 = legs[0], legs[1], legs[2], legs[4], legs[5]
    d1, d2 = np.hypot(x + r3, y), np.hypot(x - r3, y)
    ok = ((d1 >= abs(a1 - c1)) and (d1 <= a1 + c1) and (d2 >= abs(a2 - c2)) and (d2 <= a2 + c2)
          and d1 > 0 and d2 > 0)
    if not ok:
        return 0.0, 0.0, False
    return (min(max((a1 * a1 + d1 * d1 - c1 * c1) / (2 * a1 * d1), -1.0), 1.0),
            min(max((a2 * a2 + d2 * d2 - c2 * c2) / (2 * a2 * d2), -1.0), 1.0), True)


@jitable
def _ik_angles(s1, s2, alpha1, alpha2, beta1, beta2, ok):
    """``theta1 = beta1 + s1 alpha1``, ``theta2 = pi - beta2 + s2 alpha2`` (Le eq.
    13-18; NaN where not ``ok``): :func:`legs_ik`'s last step, on arrays or (compiled)
    on floats."""
    return (select(ok, beta1 + s1 * alpha1, np.nan), select(ok, np.pi - beta2 + s2 * alpha2, np.nan))


@jitable
def _ik_arguments(legs, x, y):
    """What the five-bar's crank angles need from NumPy at one point (compiled zooms,
    :func:`mechopt.core.zoom.zoom_ranges`): ``(k1, k2, y, x + r3, y, r3 - x, ok)``, the
    ``arccos`` arguments and the ``arctan2`` ones of :func:`legs_ik`."""
    x, y = point_in_reach(x), point_in_reach(y)
    k1, k2, ok = _ik_cosines_at(legs, x, y)
    return k1, k2, y, x + legs[0], y, legs[0] - x, ok


@jitable
def _ik_from(legs, alpha1, alpha2, beta1, beta2, ok):
    """The crank angles from NumPy's ``arccos``/``arctan2`` of :func:`_ik_arguments`
    (:func:`_ik_angles`)."""
    return _ik_angles(legs[3], legs[6], alpha1, alpha2, beta1, beta2, ok)


def _ik_loop(x, y, legs, k1, k2, ok):
    """:func:`legs_ik` up to its angles, point by point (compiled, :class:`mechopt.core.jit.Twin`;
    :func:`_ik_cosines_at`): the clipped cosines into ``k1, k2``, the reachability into ``ok``."""
    lp = _legs_of(legs)
    for i in range(x.size):
        k1[i], k2[i], ok[i] = _ik_cosines_at(lp, x[i], y[i])


@jitable
def _lci_at(legs, x, y):
    """The LCI of the Jacobian at one point, 0 where unreachable: ``FiveBar.lci`` of
    the protocol (``J = A / b`` row by row from :func:`_closure_at`, then
    :func:`mechopt.core.indices.lci_of_matrix`), the zoom's point kernel
    (:meth:`FiveBar.zoom_kernel`; ``legs = [r3, a1, c1, s1, a2, c2, s2]``)."""
    a1x, a1y, a2x, a2y, k1, k2, _ = _closure_at(point_in_reach(x), point_in_reach(y), legs)
    return lci_of_matrix(a1x / k1, a1y / k1, a2x / k2, a2y / k2)


@jitable
def _type2_at(legs, x, y):
    """:meth:`FiveBar.type2_function` at one point (NaN where unreachable), the zoom's
    point kernel (``legs = [r3, a1, c1, s1, a2, c2, s2]``, ``c1 = r2``)."""
    x, y = point_in_reach(x), point_in_reach(y)
    b1x, b1y, b2x, b2y, _ = _elbows_at(x, y, legs)
    return _type2_of(x, y, b1x, b1y, b2x, b2y, legs[2])


@jitable
def _type2_of(x, y, b1x, b1y, b2x, b2y, r2):
    """``(a1 x a2) / r2^2`` with ``a_i = P - B_i`` (:meth:`FiveBar.type2_function`; arrays
    or, compiled, floats)."""
    return ((x - b1x) * (y - b2y) - (y - b1y) * (x - b2x)) / (r2 * r2)


# one entry per kernel, each naming its kernel: numba's cache keeps a function that calls
# a global kernel, not one that receives the kernel as an argument (compiled again in
# every process)
def _lci_zoom_loop(p, search):
    """:func:`mechopt.core.zoom.zoom_minimum` of :func:`_lci_at` (compiled, :class:`Twin`)."""
    return zoom_minimum(_lci_at, _legs_of(p), *search)


def _type2_zoom_loop(p, search):
    """:func:`mechopt.core.zoom.zoom_minimum` of :func:`_type2_at` (compiled, :class:`Twin`)."""
    return zoom_minimum(_type2_at, _legs_of(p), *search)


def _ik_ranges_loop(p, search):
    """:func:`mechopt.core.zoom.zoom_ranges` of the crank angles (:func:`_ik_arguments`,
    :func:`_ik_from`; compiled, :class:`Twin`)."""
    return zoom_ranges(_ik_arguments, _ik_from, _legs_of(p), *search)


_ELBOWS_TWIN = Twin(_elbows_loop)
_IK_TWIN = Twin(_ik_loop)
_CLOSURE_TWIN = Twin(_closure_loop)
_ZOOMS = {"lci": Twin(_lci_zoom_loop), "type2": Twin(_type2_zoom_loop), "ik": Twin(_ik_ranges_loop)}


def legs_closure(x, y, r3, legs):
    """``(A, b, reachable)`` of ``A p_dot = B theta_dot``: ``a_i = P - B_i``,
    ``B_ii = (B_i - A_i) x a_i``.

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L].
    y : array_like
        Ordinates [L]; broadcast with ``x``.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    A : ndarray
        Shape ``(..., 2, 2)`` [L].
    b : ndarray
        The diagonal of ``B``, shape ``(..., 2)`` [L^2].
    reachable : ndarray of bool
        Where both legs assemble.
    """
    x, y = as_points(x, y)
    p = _twin_legs(r3, legs)
    if p is not None:
        A, b, ok = np.empty(x.shape + (2, 2)), np.empty(x.shape + (2,)), np.empty(x.shape, dtype=np.bool_)
        _CLOSURE_TWIN(x.reshape(-1), y.reshape(-1), p, A.reshape(-1, 2, 2), b.reshape(-1, 2), ok.reshape(-1))
        return A, b, ok
    b1x, b1y, b2x, b2y, ok = legs_elbows(x, y, r3, legs)
    a1x, a1y = x - b1x, y - b1y
    a2x, a2y = x - b2x, y - b2y
    A = np.stack([np.stack([a1x, a1y], -1), np.stack([a2x, a2y], -1)], -2)
    # (B_i - A_i) x a_i = a_i (u_i x a_i): the closure |P - B_i|^2 = c_i^2
    # differentiated gives a_i . p_dot = a_i (u_i x a_i) theta_dot_i.
    k1 = (b1x + r3) * a1y - b1y * a1x
    k2 = (b2x - r3) * a2y - b2y * a2x
    return A, np.stack([k1, k2], -1), ok


def legs_closure_enclosure(x, y, r3, legs):
    """Interval enclosure of :func:`legs_closure` over boxes ``x, y`` (intervals):
    ``(A, b, certain)`` (:meth:`mechopt.core.protocol.PlanarMechanism.closure_enclosure`).

    The same elbow as :func:`legs_elbows`, written from positions only: with
    ``v = P - A_i``, ``d^2 = |v|^2``, ``k = 1/2 + (a_i^2 - c_i^2) / (2 d^2)``,
    ``h^2 = a_i^2 / d^2 - k^2`` and ``h = s_i sqrt(h^2)`` (the working mode's sign),
    ``B_i - A_i = k v + h perp(v)`` (``perp(v) = (-v_y, v_x)``), so ``a_i = P - B_i =
    (1 - k) v - h perp(v)`` and ``B_ii = (B_i - A_i) x a_i = -h d^2`` (the cross
    products of ``v`` and ``perp(v)`` are ``+-d^2``): ``+ - * / sqrt`` only, each with
    outward rounding (:mod:`mechopt.core.interval`), so the intervals contain the exact
    values at every point of the box. ``certain`` is False where ``d^2`` may vanish or
    ``h^2`` may be negative (the leg may not assemble) or may vanish (the point
    evaluator clips ``h^2`` in ``[-1e-12, 0)`` to 0: a type-I pose, where every bounded
    quantity takes its floor anyway). Lengths (``r3``, ``a_i``, ``c_i``) may be
    intervals too (a tolerance box).

    Parameters
    ----------
    x, y : mechopt.core.interval.Interval
        The boxes [L].
    r3 : float or Interval
        Half the base distance [L].
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L] (floats or intervals),
        elbow sign (+1 or -1).

    Returns
    -------
    A : tuple
        ``((a1x, a1y), (a2x, a2y))`` intervals [L].
    b : tuple
        ``(B_11, B_22)`` intervals [L^2].
    certain : ndarray of bool
        Where every point of the box assembles both legs.
    """
    from mechopt.core.interval import as_interval

    r3 = as_interval(r3)
    rows, bs, certain = [], [], None
    for ax, (a, c, s) in zip((-r3, r3), legs):
        a2, c2 = as_interval(a).sqr(), as_interval(c).sqr()
        vx, vy = x - ax, as_interval(y)
        d2 = (vx.sqr() + vy.sqr()).nonneg()
        u = 1.0 / d2
        k = 0.5 + 0.5 * ((a2 - c2) * u)
        h, neg = (a2 * u - k.sqr()).sqrt()
        ok = ~neg & (d2.lo > 0.0) & (h.lo > 0.0)
        if s < 0:
            h = -h
        m = 1.0 - k
        rows.append((m * vx + h * vy, m * vy - h * vx))
        bs.append(-(h * d2))
        certain = ok if certain is None else certain & ok
    return tuple(rows), tuple(bs), certain


def legs_actuator_enclosure(x, y, r3, legs):
    """Interval enclosure of :func:`legs_ik`'s crank angles over boxes ``x, y``
    (intervals): ``(theta, certain)``
    (:meth:`mechopt.core.protocol.PlanarMechanism.actuator_enclosure`).

    The same formulas as :func:`legs_ik` (Le 2013 eq. 13-18), ``theta1 = beta1 + s1
    alpha1``, ``theta2 = pi - beta2 + s2 alpha2``: ``beta_i`` the angle of ``P - A_i``
    (leg 2 mirrored: of ``(r3 - x, y)``) by :func:`mechopt.core.interval.atan2` (its
    exact range over the box from the corners), ``alpha_i = acos(k_i)`` with ``k_i =
    (a_i^2 + d_i^2 - c_i^2) / (2 a_i d_i)`` by :func:`mechopt.core.interval.acos`,
    ``d_i = |P - A_i|``, ``pi`` enclosed by :data:`mechopt.core.interval.PI`; outward
    rounding throughout. ``certain`` is False where a leg may not assemble (``k_i`` not
    certainly within ``[-1, 1]``, or ``d_i`` may vanish) or the box may meet ``beta_i``'s
    branch cut (``y = 0`` beyond the base joint, where the point evaluator's angle jumps by
    ``2 pi``). Lengths (``r3``, ``a_i``, ``c_i``) may be intervals too (a tolerance box).

    Parameters
    ----------
    x, y : mechopt.core.interval.Interval
        The boxes [L].
    r3 : float or Interval
        Half the base distance [L].
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L] (floats or intervals),
        elbow sign (+1 or -1).

    Returns
    -------
    theta : tuple
        ``(theta1, theta2)`` intervals [rad].
    certain : ndarray of bool
        Where every point of the box assembles both legs and both angles are continuous.
    """
    from mechopt.core import interval as _iv

    r3, y = _iv.as_interval(r3), _iv.as_interval(y)
    out, certain = [], None
    for i, (a, c, s) in enumerate(legs):
        a = _iv.as_interval(a)
        vx = x + r3 if i == 0 else r3 - x  # leg 2 mirrored: beta2 = atan2(y, r3 - x)
        d2 = (vx.sqr() + y.sqr()).nonneg()
        d = d2.sqrt()[0]
        k = (a.sqr() + d2 - _iv.as_interval(c).sqr()) / (2.0 * (a * d))
        beta, cont = _iv.atan2(y, vx)
        alpha = _iv.acos(k)
        ok = cont & (d.lo > 0.0) & (k.lo >= -1.0) & (k.hi <= 1.0)
        th = beta + alpha if s > 0 else beta - alpha
        out.append(th if i == 0 else (_iv.PI - beta) + (alpha if s > 0 else -alpha))
        certain = ok if certain is None else certain & ok
    return tuple(out), certain


def _reach(x, y, r3, legs):
    """Per leg ``(d_i, |a_i - c_i|, a_i + c_i)``: the distance ``|P - A_i|`` and the radii
    of the leg's annulus (Le eq. 19)."""
    x, y = as_points(x, y)
    (a1, c1, _), (a2, c2, _) = legs
    return ((np.hypot(x + r3, y), abs(a1 - c1), a1 + c1),
            (np.hypot(x - r3, y), abs(a2 - c2), a2 + c2))


def legs_reachable(x, y, r3, legs):
    """Both legs assemble: ``|a_i - c_i| <= |P - A_i| <= a_i + c_i``, ``P`` not on a base joint.

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L].
    y : array_like
        Ordinates [L]; broadcast with ``x``.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    ndarray of bool
        Where both legs assemble.
    """
    return _assembles(_reach(x, y, r3, legs))


def _assembles(reach):
    """:func:`legs_reachable` from the annuli of :func:`_reach`."""
    (d1, lo1, hi1), (d2, lo2, hi2) = reach
    return (d1 >= lo1) & (d1 <= hi1) & (d2 >= lo2) & (d2 <= hi2) & (d1 > 0) & (d2 > 0)


def legs_serial_clearance(x, y, r3, legs):
    """Distance to the nearest of the four circles bounding the legs' annuli, signed.

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L].
    y : array_like
        Ordinates [L]; broadcast with ``x``.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    ndarray
        Signed distance [L], positive inside the reachable set (Le 2013 eq. 19).
    """
    (d1, lo1, hi1), (d2, lo2, hi2) = _reach(x, y, r3, legs)
    return np.minimum.reduce([hi1 - d1, d1 - lo1, hi2 - d2, d2 - lo2])


def legs_bounding_box(r3, legs):
    """The box of the intersection of the two outer disks ``|P - A_i| <= a_i + c_i``.

    Parameters
    ----------
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    tuple of float
        ``(xmin, xmax, ymin, ymax)`` [L].
    """
    (a1, c1, _), (a2, c2, _) = legs
    reach1, reach2 = a1 + c1, a2 + c2
    reach = min(reach1, reach2)
    return (max(-r3 - reach1, r3 - reach2), min(-r3 + reach1, r3 + reach2), -reach, reach)


def legs_ik(x, y, r3, legs):
    """Crank angles ``theta1 = beta1 + s1 alpha1``, ``theta2 = pi - beta2 + s2 alpha2``
    (Le eq. 13-18), unwrapped (see :meth:`FiveBar.ik`); NaN where unreachable.

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L].
    y : array_like
        Ordinates [L]; broadcast with ``x``.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    theta1, theta2 : ndarray
        Crank angles [rad].
    reachable : ndarray of bool
        Where both legs assemble.
    """
    x, y = as_points(x, y)
    (a1, c1, s1), (a2, c2, s2) = legs
    p = _twin_legs(r3, legs)
    if p is not None:  # the cosines compiled, the angles by NumPy's functions (_ik_loop)
        k1, k2, ok = np.empty(x.shape), np.empty(x.shape), np.empty(x.shape, dtype=np.bool_)
        _IK_TWIN(x.reshape(-1), y.reshape(-1), p, k1.reshape(-1), k2.reshape(-1), ok.reshape(-1))
    else:
        reach = _reach(x, y, r3, legs)
        ok = _assembles(reach)
        d1, d2 = reach[0][0], reach[1][0]  # |P - A_i|
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # clipped below
            k1 = np.clip((a1 * a1 + d1 * d1 - c1 * c1) / (2 * a1 * d1), -1.0, 1.0)
            k2 = np.clip((a2 * a2 + d2 * d2 - c2 * c2) / (2 * a2 * d2), -1.0, 1.0)
    th1, th2 = _ik_angles(s1, s2, np.arccos(k1), np.arccos(k2), np.arctan2(y, x + r3), np.arctan2(y, r3 - x), ok)
    return th1, th2, ok


def legs_fk(theta1, theta2, r3, legs, assembly: str = "up"):
    """``(x, y, valid)``: the intersection of the distal circles about ``B_1`` and ``B_2``
    (Le eq. 5-12); ``"up"``: ``P`` on the left of ``B1 -> B2``. NaN where they do not meet.

    Parameters
    ----------
    theta1 : array_like
        Crank angle of leg 1 [rad].
    theta2 : array_like
        Crank angle of leg 2 [rad].
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).
    assembly : str
        ``"up"`` or ``"down"``.

    Returns
    -------
    x, y : ndarray
        The platform point [L].
    valid : ndarray of bool
        Where the circles meet.

    Raises
    ------
    ValueError
        For an unknown assembly mode or angles that do not broadcast.
    """
    _v.choice("assembly", assembly, ASSEMBLY_MODES)
    t1, t2 = as_points(theta1, theta2)
    (a1, c1, _), (a2, c2, _) = legs
    b1x, b1y = -r3 + a1 * np.cos(t1), a1 * np.sin(t1)
    b2x, b2y = r3 + a2 * np.cos(t2), a2 * np.sin(t2)
    mx, my = b2x - b1x, b2y - b1y
    m2 = mx * mx + my * my
    with np.errstate(divide="ignore", invalid="ignore"):
        # the foot of P on B1 -> B2, in units of |m|: exactly 1/2 for equal distal links
        u = (c1 * c1 - c2 * c2 + m2) / (2.0 * m2)
        h2 = c1 * c1 / m2 - u * u
    valid = (h2 >= 0) & (m2 > 0)
    h = np.sqrt(np.clip(h2, 0, None)) * (1.0 if assembly == "up" else -1.0)
    with np.errstate(invalid="ignore"):  # inf * 0 where B1 = B2: not valid, masked below
        x = b1x + u * mx - h * my
        y = b1y + u * my + h * mx
    return np.where(valid, x, np.nan), np.where(valid, y, np.nan), valid


def legs_assembly_of(x, y, r3, legs):
    """The FK assembly (``"up"``/``"down"``) of each pose of the working mode.

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L].
    y : array_like
        Ordinates [L]; broadcast with ``x``.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    ndarray of str
        ``"up"`` or ``"down"`` per pose.
    """
    b1x, b1y, b2x, b2y, _ = legs_elbows(x, y, r3, legs)
    x, y = as_points(x, y)
    cross = (b2x - b1x) * (y - b1y) - (b2y - b1y) * (x - b1x)
    return np.where(cross >= 0, "up", "down")


def legs_bodies(r3, legs):
    """The bodies of a 5R (:class:`mechopt.core.rigid_bodies.BodySpec`): per leg ``i`` a motor
    on the base joint ``A_i`` (fixed), the crank ``A_i B_i`` and the distal link
    ``B_i P`` (tubes of the mass law); the payload at ``P``.

    Parameters
    ----------
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    list of mechopt.core.rigid_bodies.BodySpec
        Motors, cranks, distal links and the payload.
    """
    out = []
    for i, (a, c, _) in enumerate(legs, 1):
        out += [_b.BodySpec(f"motor{i}", "motor", 0.0, (f"A{i}",), leg=i),
                _b.BodySpec(f"crank{i}", "link", a, (f"A{i}", f"B{i}"), leg=i),
                _b.BodySpec(f"distal{i}", "link", c, (f"B{i}", "P"), leg=i)]
    return tuple(out + [_b.BodySpec("payload", "payload", 0.0, ("P",))])


def legs_body_frames(x, y, xd, yd, xdd, ydd, r3, legs):
    """``(q, qd, qdd, frames)`` of :func:`legs_bodies` along a motion of ``P`` (module
    :mod:`mechopt.core.rigid_bodies` for the frames).

    The crank tip ``B = A + a n``, ``n = (cos theta, sin theta)``, ``t = (-sin, cos)``
    moves with ``B_dot = a theta_dot t`` and ``B_ddot = a theta_ddot t - a theta_dot^2 n``;
    the closure ``|P - B|^2 = c^2`` differentiated once and twice, with ``d = P - B``::

        theta_dot  = d . P_dot / (a d . t),
        theta_ddot = (d . P_ddot + a theta_dot^2 d . n + |P_dot - B_dot|^2) / (a d . t)

    (``a d . t = B_ii`` of :func:`legs_closure`). Exact; NaN where unreachable.

    Parameters
    ----------
    x, y : array_like
        Platform positions [L] along the motion.
    xd, yd : array_like
        Velocities [L/s].
    xdd, ydd : array_like
        Accelerations [L/s^2].
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    q, qd, qdd : ndarray
        Crank angles [rad], rates [rad/s] and accelerations [rad/s^2].
    frames : dict
        Per body its frame along the motion (:mod:`mechopt.core.rigid_bodies`).
    """
    x, y = as_points(x, y)
    P = _b.stack2(x, y)
    Pd, Pdd = _b.stack2(xd, yd), _b.stack2(xdd, ydd)
    th1, th2, _ = legs_ik(x, y, r3, legs)
    q, qd, qdd, frames = [], [], [], {}
    shape = x.shape
    for i, ((a, _, _), th, ax) in enumerate(zip(legs, (th1, th2), (-r3, r3)), 1):
        n = _b.stack2(np.cos(th), np.sin(th))
        t = _b.stack2(-np.sin(th), np.cos(th))
        A = np.array([ax, 0.0])
        B = A + a * n
        d = P - B
        dt = a * np.sum(d * t, -1)
        with np.errstate(divide="ignore", invalid="ignore"):
            w = np.sum(d * Pd, -1) / dt
            Bd = (a * w)[..., None] * t
            rel = Pd - Bd
            al = (np.sum(d * Pdd, -1) + a * w * w * np.sum(d * n, -1) + np.sum(rel * rel, -1)) / dt
        Bdd = (a * al)[..., None] * t - (a * w * w)[..., None] * n
        zero = np.zeros(shape + (2,))
        frames[f"motor{i}"] = _b.fixed_frame(A, shape)
        frames[f"crank{i}"] = _b.segment_frame((np.broadcast_to(A, B.shape), zero, zero), (B, Bd, Bdd))
        frames[f"distal{i}"] = _b.segment_frame((B, Bd, Bdd), (P, Pd, Pdd))
        q.append(th), qd.append(w), qdd.append(al)
    frames["payload"] = _b.translating_frame(P, Pd, Pdd)
    return np.stack(q, -1), np.stack(qd, -1), np.stack(qdd, -1), frames


def legs_tree(name, r3, legs) -> KinematicTree:
    """The kinematic tree of a 5R (:mod:`mechopt.core.kinematic_tree`): per leg ``i`` the
    actuated crank joint ``theta<i>`` on the base at ``A_i`` (body ``crank<i>``, its x
    axis along the crank), the passive ``elbow<i>`` at ``(a_i, 0)`` of the crank (body
    ``distal<i>``, x along the distal link) and the closure frame at ``(c_i, 0)`` of
    ``distal<i>``: the platform point. Crank angles unlimited here (the design's
    ranges are set by the exporter).

    Parameters
    ----------
    name : str
        The tree's name.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    mechopt.core.kinematic_tree.KinematicTree
        The tree.
    """
    joints, closure = [], []
    for i, (ax, (a, c, _)) in enumerate(zip((-r3, r3), legs), 1):
        joints += [TreeJoint(f"theta{i}", "revolute", BASE, f"crank{i}", (ax, 0.0), actuated=True),
                   TreeJoint(f"elbow{i}", "revolute", f"crank{i}", f"distal{i}", (a, 0.0))]
        closure.append(ClosureFrame(CLOSURE_NAMES[i - 1], f"distal{i}", (c, 0.0)))
    return KinematicTree(name, tuple(joints), tuple(closure))


def legs_tree_configuration(x, y, r3, legs) -> dict:
    """Joint values of :func:`legs_tree` with the platform at ``(x, y)``: ``theta<i>``
    from :func:`legs_ik` (unwrapped), ``elbow<i>`` the angle from the crank to the distal
    link ``B_i -> P`` [rad] in ``(-pi, pi]``, from :func:`legs_elbows`; NaN out of reach.

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L].
    y : array_like
        Ordinates [L]; broadcast with ``x``.
    r3 : float
        Half the base distance [L] (base joints at ``(-r3, 0)`` and ``(r3, 0)``).
    legs : tuple
        Per leg ``(a_i, c_i, s_i)``: crank [L], distal link [L], elbow sign (+1 or -1).

    Returns
    -------
    dict
        ``{joint: ndarray}`` [rad].
    """
    x, y = as_points(x, y)
    t1, t2, _ = legs_ik(x, y, r3, legs)
    b1x, b1y, b2x, b2y, _ = legs_elbows(x, y, r3, legs)
    out = {}
    for i, (t, bx, by) in enumerate(((t1, b1x, b1y), (t2, b2x, b2y)), 1):
        e = np.arctan2(y - by, x - bx) - t
        out[f"theta{i}"] = t
        out[f"elbow{i}"] = np.arctan2(np.sin(e), np.cos(e))
    return out


class FiveBarDesignSpec(DesignSpec):
    """``mechopt design five-bar``: the lengths ``r1, r2, r3`` [L] (``r3``, the half base,
    from 0), the modes :data:`MODES` (default ``"+-"``), cranks; the reachable set is the
    intersection of two annuli, symmetric about the base line, its holes the disks
    ``|P - A_i| < |r1 - r2|`` about the base joints (Le 2013 eq. 19)."""

    name = "five-bar"
    lengths = ("r1", "r2", "r3")
    modes, default_mode = MODES, "+-"
    angular = True

    def lower_bounds(self, lmin):
        return [lmin, lmin, 0.0]

    def build(self, v, mode, strokes=None, pad=0.0):
        return FiveBar(v["r1"], v["r2"], v["r3"], mode)

    def size(self, mech, derived):
        """``2 (r1 + r2 + r3)``: two cranks, two distal links, the base distance.

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        derived : dict
            The evaluation's derived values (strokes, ...).

        Returns
        -------
        float
            The size [L].
        """
        return 2.0 * (mech.r1 + mech.r2 + mech.r3)

    def joints(self, mech, x, y):
        b1x, b1y, b2x, b2y, _ = mech.elbows(x, y)
        return [(b1x, b1y), (b2x, b2y), (x, y), (np.full_like(x, mech.r3), np.zeros_like(x))]

    def holes(self, mech):
        return [(-mech.r3, 0.0), (mech.r3, 0.0)]

    def links(self, mech, x, y, shapes=None):
        """The motor housings (discs about ``A1 = (-r3, 0)``, ``A2 = (r3, 0)``), the cranks
        ``A_i B_i`` (``"crank1"``, ``"crank2"``) and the distal links ``B_i P``
        (``"distal1"``, ``"distal2"``) at task points ``(x, y)``: joints ``A1, A2, B1, B2,
        P`` (the asymmetric five-bar's too, each leg with its own lengths).

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        x : array_like
            Task points' abscissae [L, task frame].
        y : array_like
            Ordinates [L, task frame]; shape of ``x``.
        shapes : mechopt.core.bodies.Shapes, optional
            Widths and sizes of the bodies [L].

        Returns
        -------
        list of mechopt.core.bodies.Body
            The bodies as capsules.
        """
        shapes = shapes or Shapes.default()
        x, y = as_points(x, y)
        b1x, b1y, b2x, b2y, _ = legs_elbows(x, y, mech.r3, mech._legs())
        r3 = mech.r3
        out = []
        for i, (ax, bx, by) in enumerate(((-r3, b1x, b1y), (r3, b2x, b2y)), start=1):
            a, b = f"A{i}", f"B{i}"
            out += [Body.make(f"housing{i}", "housing", (a,), (GROUND, GROUND), (ax, 0.0), (ax, 0.0),
                              shapes, x.shape),
                    Body.make(f"crank{i}", "proximal", (a, b), (a, b), (ax, 0.0), (bx, by), shapes),
                    Body.make(f"distal{i}", "distal", (b, "P"), (b, "P"), (bx, by), (x, y), shapes)]
        return out

    def joint_speeds(self, mech, x, y, radius=0.0):
        """``A_i``: 0; ``P``: 1; the elbow ``B_i``: ``a_i |J_i| = 1 / |sin gamma_i|`` with
        ``gamma_i`` the angle between the crank and the distal link (``J_i = a_i^T /
        (a c sin gamma_i)``, the closure of :func:`legs_closure`). ``cos gamma_i = (d^2 -
        a^2 - c^2) / (2 a c)`` depends on ``d = |P - A_i|`` alone, monotonically, and ``d``
        is 1-Lipschitz in ``P``: over the disc of ``radius`` about a task point ``d`` lies in
        ``[d0 - radius, d0 + radius]``, where ``|cos gamma_i|`` is largest at an end; the
        bound is infinite when that interval leaves the leg's annulus
        ``[|a - c|, a + c]`` (a type-I singularity within reach).

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        x : array_like
            Task points' abscissae [L, task frame].
        y : array_like
            Ordinates [L, task frame]; shape of ``x``.
        radius : float
            Radius [L] of the platform positions about each task point.

        Returns
        -------
        dict
            ``{name: ndarray}``, speed bounds [L/L].
        """
        x, y = as_points(x, y)
        out = {"A1": np.zeros_like(x), "A2": np.zeros_like(x), "P": np.ones_like(x)}
        for i, (ax, (a, c, _)) in enumerate(zip((-mech.r3, mech.r3), mech._legs()), start=1):
            d = np.hypot(x - ax, y)
            worst = np.zeros_like(d)
            for dd in (np.maximum(d - radius, 0.0), d + radius):
                worst = np.maximum(worst, np.abs((dd * dd - a * a - c * c) / (2.0 * a * c)))
            with np.errstate(divide="ignore", invalid="ignore"):
                out[f"B{i}"] = np.where(worst < 1.0, 1.0 / np.sqrt(1.0 - np.minimum(worst, 1.0) ** 2), np.inf)
        return out

    def reach_radius(self, lmax):
        return 2.0 * lmax

    def placement_scale(self, v, lmax):
        return v["r1"] + v["r2"]

    def placement_above_base(self, mode):
        return True

    def placement_both_sides(self, mode):
        # the reachable set is symmetric about the base line, and the mirror image of a
        # design in mode (s1, s2) is the design in mode (-s1, -s2): with every mode
        # searched (mode None) the upper half holds them all; with one mode fixed the
        # lower half holds other designs
        return mode is not None

    def sketch(self, mech, px, py, mx, my):
        b1x, b1y, b2x, b2y, _ = mech.elbows(px, py)
        chains = [[(-mech.r3, 0), (float(b1x), float(b1y)), (px, py)],
                  [(mech.r3, 0), (float(b2x), float(b2y)), (px, py)]]
        return chains, [(-mech.r3, 0), (mech.r3, 0)]

    def joint_arc_radius(self, mech, leg):
        return 0.35 * mech.r1


class FiveBarErrorSpec(ErrorSpec):
    """The perturbable geometry of a 5R with legs of any lengths (``FiveBar`` and
    ``AsymmetricFiveBar``; :mod:`mechopt.core.error_spec`). Leg ``i`` holds ``P`` on
    the circle of centre the elbow ``B_i = A_i + a_i (cos theta_i, sin theta_i)`` and
    radius ``c_i``. Deviations: the crank angles ``theta1``, ``theta2`` [rad]; the four
    link lengths ``a1, a2`` (cranks) and ``c1, c2`` (distal links) [L]; the base joints'
    coordinates ``A1x, A1y, A2x, A2y`` [L]. Passive joints with clearance: the elbows
    ``B1``, ``B2`` (the distal link's bore about the crank's pin: leg ``i``'s centre
    moves) and the platform joint ``P`` (the pin on distal link 2 is the tool point,
    the bore of distal link 1 about it moves leg 1's centre).

    The centre rotates with the crank, so it is not affine in ``theta_i``: with
    ``u = (cos theta, sin theta)`` and ``u'`` its derivative,
    ``(a + da) u(theta + dt) - a u(theta) - da u - a dt u' = da (u(theta + dt) - u(theta))
    + a (u(theta + dt) - u - dt u')``, of norm at most ``|da| |dt| + a dt^2 / 2``
    (``|e^(i dt) - 1| <= |dt|``, and the Taylor remainder of ``e^(i t)``, whose second
    derivative has modulus 1, is at most ``dt^2 / 2``).
    """

    scalars = (("theta1", "actuator"), ("theta2", "actuator"), ("a1", "link"), ("a2", "link"),
               ("c1", "link"), ("c2", "link"), ("A1x", "base"), ("A1y", "base"), ("A2x", "base"),
               ("A2y", "base"))
    joints = (("B1", (0,)), ("B2", (1,)), ("P", (0,)))

    def circles(self, mech, q1, q2, d):
        (a1, c1, _), (a2, c2, _) = mech._legs()
        g = lambda k: d.get(k, 0.0)  # noqa: E731
        t1, t2 = q1 + g("theta1"), q2 + g("theta2")
        k1, k2 = a1 + g("a1"), a2 + g("a2")
        return (-mech.r3 + g("A1x") + k1 * np.cos(t1), g("A1y") + k1 * np.sin(t1), c1 + g("c1"),
                mech.r3 + g("A2x") + k2 * np.cos(t2), g("A2y") + k2 * np.sin(t2), c2 + g("c2"))

    def circle_jacobian(self, mech, q1, q2):
        (a1, _, _), (a2, _, _) = mech._legs()
        q1, q2 = np.broadcast_arrays(np.asarray(q1, float), np.asarray(q2, float))
        D = np.zeros(q1.shape + (6, 10))
        for leg, (q, a) in enumerate(((q1, a1), (q2, a2))):
            c, s = np.cos(q), np.sin(q)
            r = 3 * leg
            D[..., r, leg], D[..., r + 1, leg] = -a * s, a * c  # theta_i
            D[..., r, 2 + leg], D[..., r + 1, 2 + leg] = c, s  # a_i
            D[..., r + 2, 4 + leg] = 1.0  # c_i
            D[..., r, 6 + 2 * leg] = D[..., r + 1, 7 + 2 * leg] = 1.0  # A_i
        return D

    def centre_curvature(self, mech, q1, q2, half):
        (a1, _, _), (a2, _, _) = mech._legs()
        return tuple(half.get(f"a{i}", 0.0) * half.get(f"theta{i}", 0.0) + 0.5 * a * half.get(f"theta{i}", 0.0) ** 2
                     for i, a in ((1, a1), (2, a2)))


class FiveBar(PlanarMechanism):
    """Symmetric 5R mechanism ``FiveBar(r1, r2, r3, mode="+-")``.

    Lengths may be in any consistent unit [L]; angles are in rad.

    Parameters
    ----------
    r1 : float
        Crank (proximal link) length [L], > 0.
    r2 : float
        Distal link length [L], > 0.
    r3 : float
        Half of the base distance [L], >= 0.
    mode : {"+-", "-+", "++", "--"}
        Working mode of Le 2013 eq. (17)-(18).

    References
    ----------
    Le, Kang, Doan (2013), ICCAIS, doi:10.1109/ICCAIS.2013.6720521, eq. (9)-(19).
    Liu, Wang, Pritschow (2006), Mech. Mach. Theory 41:119-144,
    doi:10.1016/j.mechmachtheory.2005.05.003, eq. (1).
    """

    cli_name = "five-bar"
    cli_help = "symmetric 5R mechanism (Liu 2006 indices)"
    parameters = (
        Parameter("r1", "length", "L", "crank (proximal link) length [L]"),
        Parameter("r2", "length", "L", "distal link length [L]"),
        Parameter("r3", "length0", "L", "half the base distance [L]"),
        Parameter("mode", "choice", "-", "working mode of Le 2013 eq. (17)-(18)", "+-", MODES),
    )
    disk_indices = True
    explicit_mic = True
    #: no summary numbers of its own (the disk evaluation gives them)
    summary_powers: dict = {}
    modes = MODES
    assembly_modes = ASSEMBLY_MODES
    joint_names = ("theta1", "theta2")
    angular_joints = True
    design_spec = FiveBarDesignSpec
    error_spec = FiveBarErrorSpec

    def __init__(self, r1, r2, r3, mode: str = "+-"):
        self.r1 = _v.positive_length("r1", r1)
        self.r2 = _v.positive_length("r2", r2)
        self.r3 = _v.nonnegative_length("r3", r3)
        self.mode = _v.choice("mode", mode, MODES)
        self._s1 = _SIGN[mode[0]]
        self._s2 = _SIGN[mode[1]]

    def __repr__(self):
        return f"FiveBar(r1={self.r1!r}, r2={self.r2!r}, r3={self.r3!r}, mode={self.mode!r})"

    def with_mode(self, mode: str) -> "FiveBar":
        """The same link lengths in another working mode.

        Parameters
        ----------
        mode : str
            One of :data:`MODES`.

        Returns
        -------
        FiveBar
            A new instance.
        """
        return FiveBar(self.r1, self.r2, self.r3, mode)

    def scaled(self, factor: float) -> "FiveBar":
        """All lengths multiplied by ``factor`` (Liu 2006 eq. 20: ``R_i = D r_i``).

        Parameters
        ----------
        factor : float
            Scale factor D, > 0.

        Returns
        -------
        FiveBar
            A new instance.

        Raises
        ------
        ValueError
            For a non-positive or non-finite factor.
        """
        factor = _v.positive_length("factor", factor)
        return FiveBar(self.r1 * factor, self.r2 * factor, self.r3 * factor, self.mode)

    @property
    def length_scale(self) -> float:
        return (self.r1 + self.r2 + self.r3) / 3.0

    @property
    def base_joints(self):
        """``((-r3, 0), (r3, 0))``."""
        return (-self.r3, 0.0), (self.r3, 0.0)

    # --- elbows -------------------------------------------------------------
    def _legs(self):
        """Both legs ``(crank, distal link, elbow sign)``: ``r1``, ``r2`` each."""
        return (self.r1, self.r2, self._s1), (self.r1, self.r2, self._s2)

    def elbows(self, x, y):
        """Elbow points of the working mode by circle intersection (:func:`legs_elbows`).

        Returns ``(b1x, b1y, b2x, b2y, reachable)``; NaN where unreachable.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        b1x, b1y, b2x, b2y : ndarray
            The elbows [L].
        reachable : ndarray of bool
            Where both legs assemble.
        """
        return legs_elbows(x, y, self.r3, self._legs())

    # --- bodies (the mass model and the dynamics) ---------------------------
    def bodies(self):
        """The declared bodies (:func:`legs_bodies`): motors, cranks, distal links, payload.

        Returns
        -------
        list of mechopt.core.rigid_bodies.BodySpec
            The bodies.
        """
        return legs_bodies(self.r3, self._legs())

    def body_frames(self, x, y, xd, yd, xdd, ydd):
        """``(q, qd, qdd, frames)`` along a motion of ``P`` (:func:`legs_body_frames`).

        Parameters
        ----------
        x, y : array_like
            Platform positions [L] along the motion.
        xd, yd : array_like
            Velocities [L/s].
        xdd, ydd : array_like
            Accelerations [L/s^2].

        Returns
        -------
        q, qd, qdd : ndarray
            Crank angles [rad], rates [rad/s], accelerations [rad/s^2].
        frames : dict
            Per body its frame along the motion.
        """
        return legs_body_frames(x, y, xd, yd, xdd, ydd, self.r3, self._legs())

    # --- protocol ------------------------------------------------------------
    def closure(self, x, y):
        """``A p_dot = B theta_dot`` with ``a_i = P - B_i``, ``B_ii = (B_i - A_i) x a_i``.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        A : ndarray
            Shape ``(..., 2, 2)`` [L].
        b : ndarray
            The diagonal of ``B`` [L^2].
        reachable : ndarray of bool
            Where both legs assemble.
        """
        return legs_closure(x, y, self.r3, self._legs())

    def closure_enclosure(self, x, y, lengths=None):
        """Interval enclosure of :meth:`closure` over boxes (:func:`legs_closure_enclosure`),
        for every mechanism with ``r1, r2, r3`` in ``lengths`` (intervals) where given.

        Parameters
        ----------
        x, y : mechopt.core.interval.Interval
            The boxes [L].
        lengths : dict, optional
            ``{"r1" | "r2" | "r3": interval}`` [L].

        Returns
        -------
        tuple
            ``(A, b, certain)``.
        """
        return legs_closure_enclosure(x, y, *self._interval_legs(lengths))

    def _interval_legs(self, lengths):
        """``(r3, legs)`` of :meth:`_legs` with the lengths in ``lengths`` (intervals)
        replacing the instance's, for the enclosures."""
        L = self._length_intervals(("r1", "r2", "r3"), lengths)
        return L["r3"], ((L["r1"], L["r2"], self._s1), (L["r1"], L["r2"], self._s2))

    def actuator_enclosure(self, x, y, lengths=None):
        """Interval enclosure of the crank angles of :meth:`ik` over boxes
        (:func:`legs_actuator_enclosure`), for every mechanism with ``r1, r2, r3`` in
        ``lengths`` (intervals) where given.

        Parameters
        ----------
        x, y : mechopt.core.interval.Interval
            The boxes [L].
        lengths : dict, optional
            ``{"r1" | "r2" | "r3": interval}`` [L].

        Returns
        -------
        tuple
            ``(theta, certain)``.
        """
        return legs_actuator_enclosure(x, y, *self._interval_legs(lengths))

    def reachable(self, x, y):
        return legs_reachable(x, y, self.r3, self._legs())

    def serial_clearance(self, x, y):
        """Distance to the nearest of the four circles of Le eq. (19), signed.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            Signed distance [L], positive inside.
        """
        return legs_serial_clearance(x, y, self.r3, self._legs())

    def bounding_box(self):
        """``(r3 - (r1 + r2), r1 + r2 - r3, -(r1 + r2), r1 + r2)``.

        Returns
        -------
        tuple of float
            ``(xmin, xmax, ymin, ymax)`` [L].
        """
        return legs_bounding_box(self.r3, self._legs())

    def ik(self, x, y):
        """Actuated angles of the working mode (Le eq. 13-18), in rad.

        The angles are returned as the formulas give them, without wrapping, so
        that joint ranges over a region are continuous (Liu 2006 3.2.3 prints
        theta1 in [36.40, 274.97] deg): ``beta1 + s1 alpha1`` lies in (-2 pi, 2 pi)
        and ``pi - beta2 + s2 alpha2`` in (-pi, 3 pi); for mode "+-" theta1 is in
        (-pi, 2 pi) and theta2 in (-pi, 2 pi).

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        theta1, theta2 : ndarray
            Crank angles [rad], NaN where unreachable.
        reachable : ndarray of bool
            Where both legs assemble.
        """
        return legs_ik(x, y, self.r3, self._legs())

    def fk(self, theta1, theta2, assembly: str = "up"):
        """Forward kinematics (Le eq. 5-12) by intersecting the two distal circles.

        ``assembly="up"`` is Le's solution 1: ``P`` on the left of the vector
        ``B1 -> B2`` (above the line B1B2 when B1 is left of B2); ``"down"`` is
        solution 2. Returns ``(x, y, valid)``; NaN where the circles do not meet.

        Parameters
        ----------
        theta1 : array_like
            Crank angle of leg 1 [rad].
        theta2 : array_like
            Crank angle of leg 2 [rad].
        assembly : str
            ``"up"`` (default) or ``"down"``.

        Returns
        -------
        x, y : ndarray
            The platform point [L].
        valid : ndarray of bool
            Where the circles meet.
        """
        return legs_fk(theta1, theta2, self.r3, self._legs(), assembly)

    def assembly_of(self, x, y):
        """Which FK assembly mode (``"up"``/``"down"``) a pose of this working mode is in.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray of str
            ``"up"`` or ``"down"`` per pose.
        """
        return legs_assembly_of(x, y, self.r3, self._legs())

    def kinematic_tree(self):
        """Bodies and joints, the loop cut at the platform (:func:`legs_tree`).

        Returns
        -------
        mechopt.core.kinematic_tree.KinematicTree
            The tree.
        """
        return legs_tree(self.cli_name, self.r3, self._legs())

    def tree_configuration(self, x, y) -> dict:
        """Every joint of :meth:`kinematic_tree` at ``(x, y)`` (:func:`legs_tree_configuration`).

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        dict
            ``{joint: ndarray}`` [rad].
        """
        return legs_tree_configuration(x, y, self.r3, self._legs())

    def zoom_kernel(self, quantity):
        """The compiled zooms of the LCI, the type-II function and the crank angles
        (:func:`_lci_at`, :func:`_type2_at`, :func:`_ik_arguments`; the protocol's
        :meth:`~mechopt.core.protocol.PlanarMechanism.zoom_kernel`).

        Parameters
        ----------
        quantity : str
            ``"lci"``, ``"type2"`` or ``"ik"``.

        Returns
        -------
        mechopt.core.zoom.ZoomKernel or None
            The compiled search, or None.
        """
        legs = _twin_legs(self.r3, self._legs())
        if legs is None or quantity not in _ZOOMS:
            return None
        return ZoomKernel(_ZOOMS[quantity], legs)

    def type2_function(self, x, y):
        """``(a1 x a2) / (|a1| |a2|)`` with ``a_i = P - B_i``: the sine of the angle
        between the distal links; zero when B1, P, B2 are collinear (type II).

        Same value as the protocol's generic version (``|a_i| = r2``), without
        building the matrices: the MIC root finding calls it most.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            The sine, in [-1, 1]; NaN where unreachable.
        """
        x, y = as_points(x, y)
        b1x, b1y, b2x, b2y, _ = self.elbows(x, y)
        return _type2_of(x, y, b1x, b1y, b2x, b2y, self.r2)

    def explicit_workspace(self):
        """The explicit MIC (closed-form serial clearance, explicit type-II locus; Le 2013
        eq. 19, Liu 2006 sec. 3), the legs' reach and the conditions on ``r1, r2, r3``
        for :mod:`mechopt.analysis.workspace`: a
        :class:`~mechopt.mechanisms.five_bar.mic.FiveBarWorkspace`.

        Returns
        -------
        mechopt.mechanisms.five_bar.mic.FiveBarWorkspace
            The workspace geometry.
        """
        from mechopt.mechanisms.five_bar.mic import FiveBarWorkspace

        return FiveBarWorkspace(self)

    def lci(self, x, y):
        """Local conditioning index ``1/kappa_J`` in [0, 1]; 0 where unreachable or singular.

        Fused fast path (:func:`mechopt.mechanisms.five_bar.lci.five_bar_lci`: elbows by circle
        intersection and the closed-form 2x2 LCI in one pass, numba-compiled when
        numba is importable). Same values as the generic
        ``indices.lci(self.jacobian(x, y))`` to rounding (tested to 1e-12).

        A NaN coordinate is not a point: its LCI is NaN (not 0, which would read as
        "unreachable"). A finite or infinite coordinate beyond reach gives 0.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            The LCI (dimensionless).
        """
        px, py = as_points(x, y)
        out = _fast_lci.five_bar_lci(px, py, self.r1, self.r2, self.r3, self._s1, self._s2)
        nan = np.isnan(np.asarray(x, dtype=float)) | np.isnan(np.asarray(y, dtype=float))
        if np.any(nan):
            out = np.where(np.broadcast_to(nan, np.shape(out)), np.nan, out)
        return out
