"""Two sliders on parallel vertical guides, one link each to a common point: the
topology of the Biglide (Stan 2008) and of Wu's gantry (Wu 2008), written once.

Geometry. The guides are the vertical lines ``x = g_1`` and ``x = g_2 = -g_1``
(``|g_i| = a``, the order of the legs is the subclass's: the Biglide puts leg 1 on
the right, the gantry on the left); slider ``i`` sits at ``S_i = (g_i, q_i)``, its
link of length ``L`` joins it to the link joint ``A = (x, y - e)``, and the reported
point ``P = (x, y)`` lies ``e`` above it (``e = 0`` for the Biglide, ``e = l2/2`` for
the gantry's platform). With the half chord ``h_i(x) = sqrt(L^2 - (x - g_i)^2)`` the
inverse kinematics (Stan eq. 5, Wu eq. 2) is

    q_i = y - e + s_i h_i(x),        s_i = +1 or -1,

the working ``mode`` being the two signs ``s1 s2`` (first character for leg 1;
``"-"`` puts the slider below the link joint). ``c_i = y - e - q_i = -s_i h_i =
L cos(theta_i)``, ``theta_i`` the angle of link ``i`` from the vertical, depends on
``x`` only.

Closure: differentiating ``(x - g_i)^2 + (y - e - q_i)^2 = L^2`` gives
``a_i . p_dot = c_i q_dot_i`` with ``a_i = (x - g_i, c_i) = A - S_i``, so
``J = B^-1 A`` has rows ``(tan theta_i, 1)`` (Wu eq. 4): every local index depends on
``x`` only. Type I (``c_i = 0``, a link horizontal): the vertical lines
``x = g_i -/+ L``, which bound the workspace in x: ``a - L <= x <= L - a``. Type II
(the links collinear): only in the mixed modes, on the line ``x = 0``.

Forward kinematics: ``A`` is an intersection of the circles of radius ``L`` about the
two sliders; assembly ``"up"`` puts it on the left of the vector from the left slider
to the right one (above the line of the sliders), ``"down"`` on its right.

Strokes ``lo_i <= q_i <= hi_i`` (lengths ``S_i = hi_i - lo_i``) bound the reachable
set; they are tested with a tolerance of ``1e-12`` times the largest of ``L`` and the
limits' magnitudes, so that a pose computed from a limit value (``fk``, or the corner
of a synthesized task rectangle, Wu eq. 16) stays reachable despite rounding.

Workspace area (exact). For each x the leg-i admissible y form the interval
``[c_i'(x), c_i'(x) + S_i]`` with ``c_i' = lo_i + e - s_i h_i``, so the vertical
chord is ``g(d) = max(0, min(S1, S2, d + S1, S2 - d))`` with ``d = c_1' - c_2'``.
``g`` is piecewise linear in ``d`` with kinks at ``d in {-S1, 0, S2 - S1, S2}``; the
x where ``d`` reaches a kink solve ``sigma1 h1 - sigma2 h2 = K`` (``sigma_i = -s_i``),
whose squared form gives

    x^2 = K^2 (4 (L^2 - a^2) - K^2) / (4 (4 a^2 + K^2)).

Between consecutive roots the chord is a constant or ``+/- d(x) + const`` and
``int h_i dx`` is a circular-segment area: :meth:`TwoSliderMechanism.workspace_area`
is exact to rounding. Spurious roots of the squared equation only split an interval.

GTQI: ``int TQI(x) g(d(x)) dx / W`` by adaptive Gauss-Kronrod (scipy ``quad``) on
each of those intervals, relative error below 1e-10, or a fixed Gauss rule
(:meth:`TwoSliderMechanism.tqi_integral`).

Velocity output ratio (Wu eq. 6-7): at ``y_dot = 0``, ``q_i_dot = tan(theta_i) x_dot``,
so ``k_v(i) = |x_dot / q_i_dot| = |cot theta_i| = h_i / |x - g_i|``, and ``k_av(i)`` is
a mean of it over ``x in [x_min, x_max]`` (:meth:`TwoSliderMechanism.k_av`, three
readings of eq. 7; the literal one in closed form, infinite when the range contains
the guide).

References
----------
Stan, Maties, Balan (2008), in Wu (ed.), Parallel Manipulators, Towards New
Applications, I-Tech, ISBN 978-3-902613-40-0: eq. (5), (8), (9), Figs. 5-6.
Wu, Wang, Wang, Shao (2008), Proc. IMechE C 222:1367-1374 (doi:10.1243/09544062JMES830):
eq. (1)-(9).
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import rigid_bodies as _b
from mechopt.core import geometry as _g
from mechopt.core import interval as _iv
from mechopt.core import validation as _v
from mechopt.core.indices import box_rows_of_matrix, lci_of_matrix
from mechopt.core.jit import Twin, jitable, twin_params
from mechopt.core.zoom import ZoomKernel, point_in_reach, zoom_minimum
from mechopt.core.kinematic_tree import BASE, CLOSURE_NAMES, ClosureFrame, KinematicTree, TreeJoint
from mechopt.core.error_spec import ErrorSpec
from mechopt.core.protocol import ASSEMBLY_MODES, PlanarMechanism, as_points
from mechopt.core.quadrature import gauss_legendre

__all__ = ["TwoSliderMechanism", "GuideDesignSpec", "SliderErrorSpec", "ASSEMBLY_MODES", "GTQI_METHODS", "K_AV_READINGS"]

#: how :meth:`TwoSliderMechanism.gtqi` integrates: 1-D adaptive quadrature of exact
#: chords, a fixed Gauss rule of them, or a raster
GTQI_METHODS = ("gauss", "quad", "raster")
#: readings of Wu eq. (6)-(7) offered by :meth:`TwoSliderMechanism.k_av`
K_AV_READINGS = ("literal", "displacement", "max_speed")
#: stroke limits are tested with this tolerance relative to the largest of the link
#: length and the limits' magnitudes (module docstring)
LIMIT_RTOL = _v.ROUNDING
_QUAD_EPSREL = 1e-10
_SIGN = {"+": 1.0, "-": -1.0}


#: Gauss-Legendre orders of the fixed rules: the TQI column integrals per interval
#: between breakpoints (``tqi_mean(method="gauss")``) and the ``max_speed`` k_av integral
GAUSS_ORDER_TQI = 128
GAUSS_ORDER_KAV = 64


@jitable
def _closure_at(p, via_positions, px, py):
    """:meth:`TwoSliderMechanism.closure` at one point (compiled kernels): ``(u1, c1, u2,
    c2, ok)`` with ``A = [[u1, c1], [u2, c2]]`` and ``b = (c1, c2)``, each by the NumPy
    path's operations (:meth:`~TwoSliderMechanism.legs`, :func:`_w`), NaN where a leg does
    not assemble; ``p = [g1, g2, L, s1, s2, e, lo1, hi1, lo2, hi2]`` (the strokes widened
    by their tolerance)."""
    g1, g2, L, s1, s2, e = p[0], p[1], p[2], p[3], p[4], p[5]
    u1, u2 = px - g1, px - g2
    c1 = -s1 * np.sqrt(L * L - u1 * u1)
    c2 = -s2 * np.sqrt(L * L - u2 * u2)
    y_a = py - e
    q1, q2 = y_a - c1, y_a - c2
    ok = (q1 >= p[6]) and (q1 <= p[7]) and (q2 >= p[8]) and (q2 <= p[9])
    if via_positions:
        c1, c2 = y_a - q1, y_a - q2
    if not ok:
        return np.nan, np.nan, np.nan, np.nan, False
    return u1, c1, u2, c2, True


@jitable
def _params_of(p):
    """The closure's parameters ``p`` (10) as a tuple (compiled loops): passed by value to
    :func:`_closure_at`, where an array would be reference-counted at every call."""
    return p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9]


@jitable
def _kernel_params_of(kp):
    """A zoom kernel's parameters ``kp`` (12: the closure's, the flag, the row) as a
    tuple (:func:`_params_of`)."""
    return kp[0], kp[1], kp[2], kp[3], kp[4], kp[5], kp[6], kp[7], kp[8], kp[9], kp[10], kp[11]


def _closure_loop(x, y, p, via_positions, A, b, ok):
    """:meth:`TwoSliderMechanism.closure` point by point (compiled,
    :class:`mechopt.core.jit.Twin`; :func:`_closure_at`)."""
    pt = _params_of(p)
    for i in range(x.size):
        u1, c1, u2, c2, ok[i] = _closure_at(pt, via_positions, x[i], y[i])
        A[i, 0, 0], A[i, 0, 1], A[i, 1, 0], A[i, 1, 1] = u1, c1, u2, c2
        b[i, 0], b[i, 1] = c1, c2


@jitable
def _closure_of(kp, x, y):
    """:func:`_closure_at` of a zoom kernel's parameters ``kp`` (:meth:`TwoSliderMechanism.zoom_kernel`:
    the closure's, then the closure-via-positions flag and a row) at a point kept as
    ``as_points`` keeps it."""
    return _closure_at(kp, kp[10] != 0.0, point_in_reach(x), point_in_reach(y))


@jitable
def _lci_at(kp, x, y):
    """The protocol's LCI of ``J = A / b`` (row by row) at one point (a zoom kernel)."""
    u1, c1, u2, c2, _ = _closure_of(kp, x, y)
    return lci_of_matrix(u1 / c1, c1 / c1, u2 / c2, c2 / c2)


@jitable
def _type2_at(kp, x, y):
    """The protocol's type-II function ``det A / (|a1| |a2|)`` at one point (a zoom kernel)."""
    u1, c1, u2, c2, _ = _closure_of(kp, x, y)
    return (u1 * c2 - c1 * u2) / (np.hypot(u1, c1) * np.hypot(u2, c2))


@jitable
def _box_at(kp, x, y):
    """Row ``kp[11]`` of :func:`mechopt.core.indices.box_rows_of_matrix` of ``J = A / b``
    at one point (a zoom kernel)."""
    u1, c1, u2, c2, _ = _closure_of(kp, x, y)
    v0, v1, v2, v3 = box_rows_of_matrix(u1 / c1, c1 / c1, u2 / c2, c2 / c2)
    r = kp[11]
    return v0 if r == 0.0 else (v1 if r == 1.0 else (v2 if r == 2.0 else v3))


# one entry per kernel, each naming its kernel (numba caches a function that calls a
# global kernel, not one that receives it as an argument)
def _lci_zoom_loop(p, search):
    """:func:`mechopt.core.zoom.zoom_minimum` of :func:`_lci_at` (compiled, :class:`Twin`)."""
    return zoom_minimum(_lci_at, _kernel_params_of(p), *search)


def _type2_zoom_loop(p, search):
    """:func:`mechopt.core.zoom.zoom_minimum` of :func:`_type2_at` (compiled, :class:`Twin`)."""
    return zoom_minimum(_type2_at, _kernel_params_of(p), *search)


def _box_zoom_loop(p, search):
    """:func:`mechopt.core.zoom.zoom_minimum` of :func:`_box_at` (compiled, :class:`Twin`)."""
    return zoom_minimum(_box_at, _kernel_params_of(p), *search)


_CLOSURE_TWIN = Twin(_closure_loop)
_ZOOMS = {"lci": Twin(_lci_zoom_loop), "type2": Twin(_type2_zoom_loop), "box": Twin(_box_zoom_loop)}


def _w(u, l):
    """``sqrt(l^2 - u^2)``; NaN where ``|u| > l``."""
    with np.errstate(invalid="ignore"):
        return np.sqrt(l * l - u * u)


class SliderErrorSpec(ErrorSpec):
    """The perturbable geometry of two sliders on vertical guides (the Biglide, the
    gantry; :mod:`mechopt.core.error_spec`): leg ``i`` holds the link joint on the
    circle of centre the slider joint ``S_i = (g_i, q_i)`` and radius the link length
    ``L``. Deviations: the slider positions ``q1``, ``q2`` (actuator) and the link
    lengths ``L1``, ``L2`` [L]; each guide's placement ``G1x, G1y, G2x, G2y`` [L] (its
    x, and the y of its zero). Passive joints with clearance: the slider joints ``S1``,
    ``S2`` (leg ``i``'s centre moves) and the platform joint ``P`` (leg 1's centre
    moves). Every centre and radius is affine in the deviations.

    The gantry's parallelogram keeps its platform level only with exact links: with
    a platform of height ``l2 > 0`` a link error turns it and moves the reference
    point, which this model does not cover (:meth:`check` refuses it; the designs of
    ``mechopt design`` have ``l2 = 0``, where the platform joints and the reference
    point coincide)."""

    scalars = (("q1", "actuator"), ("q2", "actuator"), ("L1", "link"), ("L2", "link"),
               ("G1x", "base"), ("G1y", "base"), ("G2x", "base"), ("G2y", "base"))
    joints = (("S1", (0,)), ("S2", (1,)), ("P", (0,)))

    def check(self, mech):
        if mech._e != 0.0:
            raise ValueError(f"the error model covers a platform of no height (l2 = 0: a link error turns a "
                             f"taller platform), got l2 = {2.0 * mech._e!r}")

    def circles(self, mech, q1, q2, d):
        g = lambda k: d.get(k, 0.0)  # noqa: E731
        (g1, g2), L = mech.guides, mech.length_scale
        return (g1 + g("G1x") + 0.0 * q1, q1 + g("q1") + g("G1y"), L + g("L1") + 0.0 * q1,
                g2 + g("G2x") + 0.0 * q2, q2 + g("q2") + g("G2y"), L + g("L2") + 0.0 * q2)

    def circle_jacobian(self, mech, q1, q2):
        q1, _ = np.broadcast_arrays(np.asarray(q1, float), np.asarray(q2, float))
        D = np.zeros(q1.shape + (6, 8))
        D[..., 1, 0] = D[..., 4, 1] = D[..., 2, 2] = D[..., 5, 3] = 1.0  # q_i, L_i
        D[..., 0, 4] = D[..., 1, 5] = D[..., 3, 6] = D[..., 4, 7] = 1.0  # guides
        return D


class TwoSliderMechanism(PlanarMechanism):
    """Base of the two-slider mechanisms (module docstring); not offered by itself.

    A subclass calls :meth:`_set_sliders` in its constructor and implements what
    differs: its parameters, ``serial_clearance``, the default range of :meth:`k_av`
    (:meth:`_k_av_default_range`) and its summary.
    """

    assembly_modes = ASSEMBLY_MODES
    joint_names = ("q1", "q2")
    angular_joints = False
    error_spec = SliderErrorSpec

    def _set_sliders(self, half_span, link, leg1_right, mode, strokes, stroke_lengths, offset):
        """Store the topology: guides at ``+-half_span`` (leg 1 at ``+half_span`` if
        ``leg1_right``), links of length ``link``, the signs of ``mode``, the actuator
        limits ``strokes = ((lo1, hi1), (lo2, hi2))`` and their lengths
        ``stroke_lengths = (S1, S2)`` (as the subclass defines them), and the height
        ``offset`` of the reported point above the link joint."""
        self._a, self._L = half_span, link
        self._g = (half_span, -half_span) if leg1_right else (-half_span, half_span)
        self._s = (_SIGN[mode[0]], _SIGN[mode[1]])
        self._lims = tuple(strokes)
        self._S = tuple(stroke_lengths)
        self._e = offset
        (lo1, hi1), (lo2, hi2) = self._lims
        self._stroke_tol = LIMIT_RTOL * max(abs(lo1), abs(hi1), abs(lo2), abs(hi2), link)

    # --- geometry ---------------------------------------------------------------
    @property
    def length_scale(self) -> float:
        """The link length [L]."""
        return self._L

    @property
    def guides(self):
        """x coordinates of the guides of sliders 1 and 2 [L]."""
        return self._g

    @property
    def joint_limits(self):
        """``((q1_min, q1_max), (q2_min, q2_max))`` [L]."""
        return self._lims

    @property
    def x_range(self):
        """``(a - L, L - a)``: where both links reach their guides (bounded by type-I lines)."""
        return (self._a - self._L, self._L - self._a)

    def _half_chords(self, x):
        """``(h1, h2, ok1, ok2)``: ``h_i = sqrt(L^2 - (x - g_i)^2)`` (0 where ``|x - g_i| > L``)."""
        out = []
        for g in self._g:
            u = x - g
            r2 = self._L * self._L - u * u
            out.append((np.sqrt(np.maximum(r2, 0.0)), r2 >= 0))
        (h1, ok1), (h2, ok2) = out
        return h1, h2, ok1, ok2

    def _offsets(self, x):
        """``c_i = y - e - q_i = L cos(theta_i) = -s_i h_i`` as functions of x, per leg
        (NaN where the link cannot reach its guide)."""
        c1 = -self._s[0] * _w(x - self._g[0], self._L)
        c2 = -self._s[1] * _w(x - self._g[1], self._L)
        return c1, c2

    def legs(self, x, y):
        """``(q1, q2, c1, c2, reachable)`` without masking: slider positions and
        ``c_i = L cos(theta_i)`` [L] of both legs.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        q1, q2 : ndarray
            Slider positions [L].
        c1, c2 : ndarray
            ``L cos(theta_i)`` [L].
        reachable : ndarray of bool
            Where both links reach their guides within the strokes.
        """
        c1, c2 = self._offsets(x)
        y_a = y - self._e
        q1 = y_a - c1
        q2 = y_a - c2
        return q1, q2, c1, c2, self._in_strokes(q1, q2)

    def _in_strokes(self, q1, q2):
        """Both slider positions within their strokes, to the tolerance of the module
        docstring (False where NaN)."""
        (lo1, hi1), (lo2, hi2) = self._lims
        t = self._stroke_tol
        with np.errstate(invalid="ignore"):
            return (q1 >= lo1 - t) & (q1 <= hi1 + t) & (q2 >= lo2 - t) & (q2 <= hi2 + t)

    def slider_positions(self, x, y):
        """``(q1, q2)`` of the inverse kinematics in this mode, ignoring strokes; NaN
        where a link cannot reach its guide.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        q1, q2 : ndarray
            Slider positions [L].
        """
        x, y = as_points(x, y)
        q1, q2, _, _, _ = self.legs(x, y)
        return q1, q2

    def link_tangents(self, x, y):
        """``(tan theta_1, tan theta_2, c1, c2, reachable)``: the rows of ``J`` are
        ``(tan theta_i, 1)``, ``c_i = L cos(theta_i)`` [L]; NaN where unreachable
        (what the gantry's dynamics, :class:`mechopt.mechanisms.gantry_dynamics.GantryDynamics`, needs).

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        tan1, tan2 : ndarray
            ``tan theta_i`` (dimensionless).
        c1, c2 : ndarray
            ``L cos(theta_i)`` [L].
        reachable : ndarray of bool
            Where the pose is reachable.
        """
        x, y = as_points(x, y)
        _, _, c1, c2, ok = self.legs(x, y)
        with np.errstate(invalid="ignore", divide="ignore"):
            t1 = (x - self._g[0]) / c1
            t2 = (x - self._g[1]) / c2
        nan = np.nan
        return (np.where(ok, t1, nan), np.where(ok, t2, nan), np.where(ok, c1, nan),
                np.where(ok, c2, nan), ok)

    # --- bodies (the mass model and the dynamics) ----------------------------------
    def bodies(self):
        """The declared bodies (:class:`mechopt.core.rigid_bodies.BodySpec`): per leg the slider
        carriage on ``S_i`` and the link ``S_i P`` (a tube of the mass law); the payload
        at ``P``. The motors stay on the frame (they drive the carriages).

        Returns
        -------
        list of mechopt.core.rigid_bodies.BodySpec
            The bodies.
        """
        out = []
        for i in (1, 2):
            out += [_b.BodySpec(f"carriage{i}", "carriage", 0.0, (f"S{i}",), leg=i),
                    _b.BodySpec(f"link{i}", "link", self._L, (f"S{i}", "P"), leg=i)]
        return tuple(out + [_b.BodySpec("payload", "payload", 0.0, ("P",))])

    def slider_motion(self, x, y, xd, yd, xdd, ydd):
        """``(q, qd, qdd, S, A)``: slider positions with their exact derivatives, the
        sliders ``S_i = (g_i, q_i)`` and the link joint ``A = P - (0, e)`` as
        ``(position, velocity, acceleration)`` arrays of shape ``(..., 2)``.

        The closure ``|A - S_i|^2 = L^2`` with ``d = A - S_i = (x - g_i, c_i)``
        differentiated once and twice gives ``q_dot_i = y_dot + (x - g_i) x_dot / c_i``
        (Wu eq. 4) and ``q_ddot_i = y_ddot + ((x - g_i) x_ddot + x_dot^2 +
        (y_dot - q_dot_i)^2) / c_i``; NaN where unreachable.

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
            Slider positions [L], rates [L/s], accelerations [L/s^2].
        S : tuple of ndarray
            The sliders' ``(position, velocity, acceleration)``.
        A : tuple of ndarray
            The link joint's ``(position, velocity, acceleration)``.
        """
        x, y = as_points(x, y)
        q1, q2, ok = self.ik(x, y)
        xd, yd, xdd, ydd = np.broadcast_arrays(*(np.asarray(v, float) for v in (xd, yd, xdd, ydd)))
        q, qd, qdd, S = [], [], [], []
        for g, qi in zip(self._g, (q1, q2)):
            c = y - self._e - qi
            with np.errstate(divide="ignore", invalid="ignore"):
                w = yd + (x - g) * xd / c
                al = ydd + ((x - g) * xdd + xd * xd + (yd - w) ** 2) / c
            z = np.zeros(x.shape)
            S.append((_b.stack2(np.full(x.shape, g), qi), _b.stack2(z, w), _b.stack2(z, al)))
            q.append(qi), qd.append(w), qdd.append(al)
        A = (_b.stack2(x, y - self._e), _b.stack2(xd, yd), _b.stack2(xdd, ydd))
        return np.stack(q, -1), np.stack(qd, -1), np.stack(qdd, -1), S, A

    def body_frames(self, x, y, xd, yd, xdd, ydd):
        """``(q, qd, qdd, frames)`` of :meth:`bodies` along a motion of ``P``
        (:meth:`slider_motion`; :mod:`mechopt.core.rigid_bodies` for the frames).

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
            Slider positions [L], rates [L/s] and accelerations [L/s^2].
        frames : dict
            Per body its frame along the motion (:mod:`mechopt.core.rigid_bodies`).
        """
        q, qd, qdd, S, A = self.slider_motion(x, y, xd, yd, xdd, ydd)
        frames = {}
        for i, Si in enumerate(S, 1):
            frames[f"carriage{i}"] = _b.translating_frame(*Si)
            frames[f"link{i}"] = _b.segment_frame(Si, A)
        P = (A[0] + np.array([0.0, self._e]), A[1], A[2])
        frames["payload"] = _b.translating_frame(*P)
        return q, qd, qdd, frames

    def link_angles(self, x, y):
        """``(theta_1, theta_2)`` [rad] of the links from the vertical (Wu eq. 1), in
        (-pi, pi]; NaN where unreachable.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        theta_1, theta_2 : ndarray
            The angles [rad].
        """
        x, y = as_points(x, y)
        ok = self.reachable(x, y)
        c1, c2 = self._offsets(x)
        t1 = np.arctan2(x - self._g[0], c1)
        t2 = np.arctan2(x - self._g[1], c2)
        return np.where(ok, t1, np.nan), np.where(ok, t2, np.nan)

    def y_interval(self, x):
        """``(y_lo, y_hi)`` of the reachable set at abscissa ``x`` (NaN where empty):
        leg i admits ``y in [lo_i + e + c_i(x), hi_i + e + c_i(x)]``.

        Parameters
        ----------
        x : array_like
            Abscissae [L].

        Returns
        -------
        y_lo, y_hi : ndarray
            The bounds [L].
        """
        lo, hi = self._y_bounds(np.asarray(x, dtype=float))
        empty = ~(lo <= hi)
        return np.where(empty, np.nan, lo), np.where(empty, np.nan, hi)

    def _y_bounds(self, x):
        """The lower and upper bound of the reachable y at ``x`` (``lo > hi``: empty)."""
        c1, c2 = self._offsets(x)
        (lo1, hi1), (lo2, hi2) = self._lims
        e = self._e
        return (np.maximum(lo1 + e + c1, lo2 + e + c2), np.minimum(hi1 + e + c1, hi2 + e + c2))

    # --- protocol -----------------------------------------------------------------
    def reachable(self, x, y):
        """Both links reach their guides and both sliders lie within their strokes
        (to the tolerance of the module docstring).

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray of bool
            True where every leg assembles (and, with stroke limits, within them).
        """
        x, y = as_points(x, y)
        return self.legs(x, y)[4]

    def ik(self, x, y):
        """Slider positions ``(q1, q2, reachable)`` [L]; NaN where unreachable.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        q1, q2 : ndarray
            Actuator coordinates [rad or L]; NaN where unreachable.
        reachable : ndarray of bool
            Where the point is reached in the working mode.
        """
        x, y = as_points(x, y)
        q1, q2, _, _, ok = self.legs(x, y)
        return np.where(ok, q1, np.nan), np.where(ok, q2, np.nan), ok

    #: compute ``c_i`` of the closure as ``(y - e) - q_i`` from the slider positions (True:
    #: the Biglide's, Stan eq. 5 differentiated) rather than as ``-s_i h_i`` (False: the
    #: gantry's, Wu eq. 1); the same number up to the rounding of ``y``, kept per
    #: mechanism so that the Jacobians (and every index and design built on them) keep
    #: their last digits
    _closure_via_positions = False

    def closure(self, x, y):
        """``A p_dot = B q_dot`` with ``a_i = (x - g_i, c_i)`` and ``B_ii = c_i = L cos(theta_i)``;
        rows of ``J = B^-1 A`` are ``(tan theta_i, 1)``. NaN where unreachable.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        A : ndarray
            Shape ``(..., 2, 2)``.
        b : ndarray
            Shape ``(..., 2)``: the diagonal of ``B``.
        reachable : ndarray of bool
            Where every leg assembles.
        """
        x, y = as_points(x, y)
        p = self._twin_params()
        if p is not None:
            A, b, ok = np.empty(x.shape + (2, 2)), np.empty(x.shape + (2,)), np.empty(x.shape, dtype=np.bool_)
            _CLOSURE_TWIN(x.reshape(-1), y.reshape(-1), p, self._closure_via_positions,
                          A.reshape(-1, 2, 2), b.reshape(-1, 2), ok.reshape(-1))
            return A, b, ok
        q1, q2, c1, c2, ok = self.legs(x, y)
        if self._closure_via_positions:
            y_a = y - self._e
            c1, c2 = y_a - q1, y_a - q2
        u1 = x - self._g[0]
        u2 = x - self._g[1]
        A = np.stack([np.stack([u1, c1], -1), np.stack([u2, c2], -1)], -2)
        b = np.stack([c1, c2], -1)
        A = np.where(ok[..., None, None], A, np.nan)
        b = np.where(ok[..., None], b, np.nan)
        return A, b, ok

    def zoom_kernel(self, quantity):
        """The compiled zooms of the LCI, the type-II function and the four per-actuator
        (box) speed and force factors (``"box"``, a row per :meth:`ZoomKernel.with_row
        <mechopt.core.zoom.ZoomKernel.with_row>`) of the protocol's Jacobian (the
        protocol's :meth:`~mechopt.core.protocol.PlanarMechanism.zoom_kernel`).

        Parameters
        ----------
        quantity : str
            ``"lci"``, ``"type2"`` or ``"box"``.

        Returns
        -------
        mechopt.core.zoom.ZoomKernel or None
            The compiled search, or None.
        """
        p = self._twin_params()
        if p is None or quantity not in _ZOOMS:
            return None
        return ZoomKernel(_ZOOMS[quantity], np.r_[p, float(self._closure_via_positions), 0.0])

    def _twin_params(self):
        """``[g1, g2, L, s1, s2, e, lo1, hi1, lo2, hi2]`` (the strokes widened by their
        tolerance) for the compiled closure when the twins run
        (:meth:`mechopt.core.jit.Twin.compiled`) and every length is a number; None
        otherwise (the NumPy path)."""
        (lo1, hi1), (lo2, hi2) = self._lims
        t = self._stroke_tol
        return twin_params((self._g[0], self._g[1], self._L, self._s[0], self._s[1], self._e,
                            lo1 - t, hi1 + t, lo2 - t, hi2 + t))

    def closure_enclosure(self, x, y, lengths=None):
        """Interval enclosure of :meth:`closure` over boxes: with ``u_i = x - g_i`` and
        ``c_i = -s_i sqrt(L^2 - u_i^2)`` (the working mode's sign), ``A = [[u_1, c_1],
        [u_2, c_2]]``, ``b = (c_1, c_2)``, each operation outward rounded
        (:mod:`mechopt.core.interval`). The Biglide computes ``c_i`` as ``(y - e) - q_i``
        from the slider position ``q_i = y - e + s_i h_i``: the same real number.
        ``certain`` is False where ``L^2 - u_i^2`` may be <= 0 (the link may not reach its
        guide, or lie horizontal: type I) or the enclosure of ``q_i = y - e - c_i`` is not
        inside the stroke widened by the point evaluator's tolerance (module docstring).

        With ``lengths`` (a tolerance box: the design spec's half guide distance and link
        length, :attr:`GuideDesignSpec.guide` and :attr:`GuideDesignSpec.link`, as
        intervals) the guides are ``x = +-a`` (the legs in this mechanism's order) and the
        link ``L`` for every ``a``, ``L`` of their intervals, so ``A`` and ``b`` enclose the
        closure of every such mechanism (the guides stay symmetric about ``x = 0``, the
        frame the design spec places the task in). ``certain`` then means only that both
        links reach their guides and are not horizontal at every point of the box, for
        every mechanism of it: the strokes are not tested. They are not lengths of the
        box: each mechanism of a tolerance box is built with its own strokes, derived as
        the ranges of ``q_i`` over the task (:attr:`GuideDesignSpec.derived_strokes`), which
        contain every ``q_i`` of the task by construction wherever the link reaches its
        guide; the nominal mechanism's strokes do not bound a neighbour's ``q_i`` (whether
        the derived strokes meet ``max_stroke`` is the stroke requirement's question).

        Parameters
        ----------
        x, y : mechopt.core.interval.Interval
            The boxes [L].
        lengths : dict, optional
            ``{guide | link: interval}`` [L], the names of the design spec's lengths
            (the Biglide's ``l1``, ``l2``; the gantry's ``d1``, ``l``); the others keep
            this mechanism's values.

        Returns
        -------
        tuple
            ``(A, b, certain)`` (:meth:`mechopt.core.protocol.PlanarMechanism.closure_enclosure`).

        Raises
        ------
        ValueError
            For a name in ``lengths`` that is not one of the design spec's lengths.
        """
        if lengths:
            spec = self.design_spec
            L = self._length_intervals((spec.guide, spec.link), lengths)
            a, link = _iv.as_interval(L[spec.guide]), _iv.as_interval(L[spec.link])
            guides = (a, -a) if self._g[0] > 0 else (-a, a)
        else:
            link, guides = self._L, self._g
        L2 = _iv.as_interval(link).sqr()
        rows, bs, certain = [], [], None
        for g, s, (lo, hi) in zip(guides, self._s, self._lims):
            u = x - g
            h, neg = (L2 - u.sqr()).sqrt()
            c = -h if s > 0 else h
            ok = ~neg & (h.lo > 0.0)
            if not lengths:
                q = (y - self._e) - c
                t = self._stroke_tol
                ok = ok & (q.lo >= lo - t) & (q.hi <= hi + t)
            rows.append((u, c))
            bs.append(c)
            certain = ok if certain is None else certain & ok
        return tuple(rows), tuple(bs), certain

    def actuator_enclosure(self, x, y, lengths=None):
        """Interval enclosure of the slider positions of :meth:`ik` over boxes: ``q_i =
        (y - e) - c_i`` with ``c_i`` of :meth:`closure_enclosure` (``-s_i sqrt(L^2 - (x -
        g_i)^2)``; ``y`` and ``x`` each once, so the natural extension is the exact range
        up to the outward rounding), ``certain`` its (the link reaches its guide, not
        horizontal, and without ``lengths`` the position inside the widened stroke).

        Parameters
        ----------
        x, y : mechopt.core.interval.Interval
            The boxes [L].
        lengths : dict, optional
            As :meth:`closure_enclosure` takes them.

        Returns
        -------
        tuple
            ``((q1, q2), certain)`` (:meth:`mechopt.core.protocol.PlanarMechanism.actuator_enclosure`).
        """
        _, c, certain = self.closure_enclosure(x, y, lengths)
        return tuple((y - self._e) - ci for ci in c), certain

    # --- the kinematic tree (mechopt.core.kinematic_tree; mechopt export) -----------------
    def kinematic_tree(self):
        """Per leg ``i`` the actuated prismatic joint ``q<i>`` on the base at ``(g_i, 0)``
        along y (body ``slider<i>``, limited to the stroke), the passive ``pivot<i>`` at
        the slider (body ``link<i>``, x along the link) and the closure frame at
        ``(L, 0)`` of ``link<i>``: the link joint. Only with the reported point at the
        link joint (no platform offset ``e``): a gantry platform of height ``l2 > 0`` is
        held level by a third, parallelogram link, which this tree does not describe
        (ValueError); ``mechopt design`` builds gantries with ``l2 = 0``.

        Returns
        -------
        mechopt.core.kinematic_tree.KinematicTree
            The tree.

        Raises
        ------
        ValueError
            For a platform offset ``e`` other than 0 (a gantry with ``l2 > 0``).
        """
        if self._e != 0:
            raise ValueError(f"{self.cli_name} with a platform offset ({self._e!r}: l2 > 0, a parallelogram "
                             f"leg) has no kinematic tree for export; only l2 = 0 is exported")
        joints, closure = [], []
        for i, (g, lim) in enumerate(zip(self._g, self._lims), 1):
            joints += [TreeJoint(f"q{i}", "prismatic", BASE, f"slider{i}", (g, 0.0), (0.0, 1.0), True,
                                 tuple(lim)),
                       TreeJoint(f"pivot{i}", "revolute", f"slider{i}", f"link{i}")]
            closure.append(ClosureFrame(CLOSURE_NAMES[i - 1], f"link{i}", (self._L, 0.0)))
        return KinematicTree(self.cli_name, tuple(joints), tuple(closure))

    def tree_configuration(self, x, y) -> dict:
        """Every joint of :meth:`kinematic_tree` at ``(x, y)``: ``q<i>`` from :meth:`ik`,
        ``pivot<i>`` the angle of link ``i`` from the x axis, ``atan2(y - q_i, x - g_i)``
        [rad]; NaN out of reach.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        dict
            ``{joint: ndarray}``: slider positions [L], pivot angles [rad].
        """
        x, y = as_points(x, y)
        q1, q2, _ = self.ik(x, y)
        out = {}
        for i, (g, q) in enumerate(zip(self._g, (q1, q2)), 1):
            out[f"q{i}"] = q
            out[f"pivot{i}"] = np.arctan2(y - self._e - q, x - g)
        return out

    def _left_right(self, q1, q2):
        """``(q_left, q_right)``: the slider positions ordered by the guides' x."""
        return (q1, q2) if self._g[0] < self._g[1] else (q2, q1)

    def fk(self, q1, q2, assembly: str = "up", limits: bool = True):
        """Forward kinematics ``(x, y, valid)`` by intersecting the link circles.

        With ``m = S_right - S_left = (2a, q_right - q_left)`` the link joint is
        ``A = M +/- sqrt(L^2 / |m|^2 - 1/4) (-m_y, m_x)``, ``M`` the sliders' midpoint;
        ``"up"`` takes ``+``. ``valid`` is False (NaN) where ``|m| > 2 L`` or, with
        ``limits=True``, a slider is outside its stroke.

        Parameters
        ----------
        q1 : array_like
            First actuator coordinate [rad or L].
        q2 : array_like
            Second actuator coordinate [rad or L]; broadcast with ``q1``.
        assembly : str
            One of :attr:`assembly_modes`.
        limits : bool
            Whether slider positions outside their strokes are invalid.

        Returns
        -------
        x, y : ndarray
            The platform point [L]; NaN where invalid.
        valid : ndarray of bool
            Where the legs assemble in that mode.
        """
        _v.choice("assembly", assembly, ASSEMBLY_MODES)
        q1, q2 = as_points(q1, q2)
        ql, qr = self._left_right(q1, q2)
        mx = 2.0 * self._a
        my = qr - ql
        m2 = mx * mx + my * my
        with np.errstate(invalid="ignore", divide="ignore"):
            h2 = self._L * self._L / m2 - 0.25  # (distance M -> A)^2 / |m|^2
            valid = h2 >= 0
            if limits:
                valid &= self._in_strokes(q1, q2)
        h = np.sqrt(np.clip(h2, 0.0, None)) * (1.0 if assembly == "up" else -1.0)
        ax = 0.0 - h * my  # the sliders' midpoint has x = 0
        ay = 0.5 * (q1 + q2) + h * mx
        y = ay + self._e
        return np.where(valid, ax, np.nan), np.where(valid, y, np.nan), valid

    def assembly_of(self, x, y):
        """``"up"`` where the link joint is on the left of the vector from the left
        slider to the right one (or on it), else ``"down"``.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray of str
            The assembly mode of each pose.
        """
        x, y = as_points(x, y)
        q1, q2 = self.slider_positions(x, y)
        ql, qr = self._left_right(q1, q2)
        cross = 2.0 * self._a * ((y - self._e) - ql) - (qr - ql) * (x + self._a)
        return np.where(cross >= 0, "up", "down")

    def bounding_box(self):
        """``(xmin, xmax, ymin, ymax)``, tight: the extremes of :meth:`y_interval`.

        Between consecutive candidate abscissae (the breakpoints of
        :meth:`workspace_area`, which include the ends of :attr:`x_range` and ``0``,
        and the guides) both offsets ``c_i(x)`` are monotone and neither bound switches
        legs, so the bounds of the set reach their extremes at candidates. An empty
        workspace gives a box of zero height at the top of the strokes.

        Returns
        -------
        tuple of float
            ``(xmin, xmax, ymin, ymax)`` [L].
        """
        xmin, xmax = self.x_range
        pts = set(self._breakpoints().tolist()) | {g for g in self._g if xmin <= g <= xmax}
        lo, hi = self._y_bounds(np.array(sorted(pts)))
        keep = lo <= hi + _v.RESOLUTION * self._L  # non-empty (to rounding at pinch points)
        if not np.any(keep):
            (_, hi1), (_, hi2) = self._lims
            y = float(min(hi1, hi2) + self._e)
            return (float(xmin), float(xmax), y, y)
        return (float(xmin), float(xmax), float(np.min(lo[keep])), float(np.max(hi[keep])))

    # --- exact workspace area and GTQI --------------------------------------------
    def _breakpoints(self):
        """Sorted x in the x range where the chord changes formula (module docstring)."""
        xa, xb = self.x_range
        (a1, _), (a2, _) = self._lims
        S1, S2 = self._S
        a, L = self._a, self._L
        pts = [xa, xb, 0.0]
        for k in (-S1, 0.0, S2 - S1, S2):
            K = k - (a1 - a2)
            num = K * K * (4.0 * (L * L - a * a) - K * K)
            den = 4.0 * (4.0 * a * a + K * K)
            if num >= 0:
                r = np.sqrt(num / den)
                pts += [r, -r]
        return np.unique(np.clip(pts, xa, xb))

    def _d(self, x):
        """``d(x) = c_1'(x) - c_2'(x)``, ``c_i' = lo_i - s_i h_i(x)`` (``e`` cancels)."""
        h1, h2, _, _ = self._half_chords(np.asarray(x, dtype=float))
        (a1, _), (a2, _) = self._lims
        return (a1 - a2) - self._s[0] * h1 + self._s[1] * h2

    def chord(self, x):
        """Exact length [L] of the vertical section of the workspace at ``x``.

        Parameters
        ----------
        x : array_like
            Abscissae [L].

        Returns
        -------
        ndarray
            The length [L] (0 where the section is empty).
        """
        x = np.asarray(x, dtype=float)
        S1, S2 = self._S
        d = self._d(x)
        g = np.maximum(0.0, np.minimum.reduce([np.full_like(d, S1), np.full_like(d, S2),
                                               d + S1, S2 - d]))
        xa, xb = self.x_range
        return np.where((x >= xa) & (x <= xb), g, 0.0)

    def _segment_integral(self, u0, u1) -> float:
        """``int_{u0}^{u1} sqrt(L^2 - u^2) du``, a circular-segment area (the area's
        column integrals): :func:`mechopt.core.geometry.chord_integral`."""
        return float(_g.chord_integral(self._L, u0, u1))

    def workspace_area(self) -> float:
        """Exact area W [L^2] of the workspace of this mode (Stan eq. 8; module docstring).

        Returns
        -------
        float
            The area [L^2].
        """
        (a1, _), (a2, _) = self._lims
        S1, S2 = self._S
        total = 0.0
        pts = self._breakpoints()
        for x0, x1 in zip(pts[:-1], pts[1:]):
            dx = x1 - x0
            if dx <= 0:
                continue
            dm = float(self._d(0.5 * (x0 + x1)))
            pieces = (S1, S2, dm + S1, S2 - dm)
            k = int(np.argmin(pieces))
            if pieces[k] <= 0:
                continue
            if k < 2:
                total += pieces[k] * dx
                continue
            ih1 = self._segment_integral(x0 - self._g[0], x1 - self._g[0])
            ih2 = self._segment_integral(x0 - self._g[1], x1 - self._g[1])
            int_d = (a1 - a2) * dx - self._s[0] * ih1 + self._s[1] * ih2
            total += (int_d + S1 * dx) if k == 2 else (S2 * dx - int_d)
        # the terms are circular segments of size up to L^2, so the sum is exact to some
        # eps L^2: a negative total is that round-off about an empty or almost empty
        # workspace (strokes [0, 1e-12] with L = 1.1 give -2.2e-16 for a true 2e-25):
        # its area is 0 to the accuracy of the formula
        return float(total) if total > 0 else 0.0

    def tqi_of_x(self, x):
        """TQI (Stan eq. 9) as a function of ``x`` alone: ``2 |t1 - t2| / (t1^2 + t2^2 + 2)``
        with ``t_i = (x - g_i)/c_i`` the slopes of ``J``'s rows; 0 on type-I lines.

        Parameters
        ----------
        x : array_like
            Abscissae [L].

        Returns
        -------
        ndarray
            The TQI (dimensionless).
        """
        x = np.asarray(x, dtype=float)
        h1, h2, _, _ = self._half_chords(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = (x - self._g[0]) / (-self._s[0] * h1)
            t2 = (x - self._g[1]) / (-self._s[1] * h2)
            out = 2.0 * np.abs(t1 - t2) / (t1 * t1 + t2 * t2 + 2.0)
        return np.where(np.isfinite(out), out, 0.0)

    def tqi_integral(self, return_error: bool = False, method: str = "quad"):
        """``int_W TQI dA`` [L^2] along x of ``TQI(x) * chord(x)`` on the intervals of
        :meth:`_breakpoints`.

        ``method="quad"``: adaptive quadrature (relative tolerance 1e-10); with
        ``return_error=True`` returns ``(value, absolute error estimate)``.
        ``method="gauss"``: a fixed 128-node Gauss-Legendre rule per interval,
        vectorised (about 100x faster; the square-root behaviour of the chord at
        the interval ends limits it to about 3e-8 relative, see
        ``tests/test_biglide.py``), for optimisation loops.

        Parameters
        ----------
        return_error : bool
            With ``method="quad"``, also return the error estimate.
        method : str
            ``"quad"`` or ``"gauss"``.

        Returns
        -------
        float or tuple
            The integral [L^2], or ``(value, absolute error estimate)``.
        """
        pts = self._breakpoints()
        if method == "gauss":
            t, w = gauss_legendre(GAUSS_ORDER_TQI)
            total = 0.0
            for x0, x1 in zip(pts[:-1], pts[1:]):
                if x1 > x0:
                    xs = 0.5 * (x1 - x0) * t + 0.5 * (x0 + x1)
                    total += 0.5 * (x1 - x0) * float(np.sum(w * self.tqi_of_x(xs) * self.chord(xs)))
            return (total, float("nan")) if return_error else total
        total, err = 0.0, 0.0
        f = lambda t: float(self.tqi_of_x(t) * self.chord(t))  # noqa: E731
        epsabs = self._quad_epsabs()
        for x0, x1 in zip(pts[:-1], pts[1:]):
            if x1 <= x0:
                continue
            from scipy import integrate  # only the adaptive rule needs scipy

            # full_output: scipy's IntegrationWarning is not passed on (see _quad_epsabs)
            v, e = integrate.quad(f, x0, x1, epsabs=epsabs, epsrel=_QUAD_EPSREL, limit=200,
                                  full_output=1)[:2]
            total += v
            err += e
        return (total, err) if return_error else total

    def _quad_epsabs(self) -> float:
        """The absolute floor of the adaptive rule of :meth:`tqi_integral`.

        Far below the result for ordinary designs (which the relative tolerance
        decides): ``1e-14 L^2``. The integrand is only known to some eps times the
        chord (the TQI is a difference of nearly equal slopes when the guides are close
        or the strokes long: ``l1 = 1e-12``, ``l2 = 1e-3``, strokes of 1 give a TQI of
        1e-9 with 7 correct digits), so the floor is at least ``1e-14`` times the
        largest possible value of the integral, the x range times the longest stroke:
        a tolerance below the integrand's own rounding is what made scipy warn
        (IntegrationWarning) for such mixed sizes. Where the integrand is known to still
        fewer digits (links longer than the guide distance by 1e-9 of it or less: the
        half chords ``sqrt(L^2 - u^2)`` cancel), the rule returns its best estimate
        without the warning; ``tqi_integral(return_error=True)`` gives its error estimate.
        """
        xa, xb = self.x_range
        return max(1e-14 * self._L ** 2, 1e-14 * (xb - xa) * max(self._S))

    def gtqi(self, method: str = "quad", step=None) -> float:
        """Area mean of the TQI (Stan eq. 9) over the workspace of this mode.

        ``method="quad"``: :meth:`tqi_integral` / :meth:`workspace_area` (TQI depends
        on x only, so the 2-D mean is a 1-D integral of exact chord lengths; relative
        error ~1e-10); ``method="gauss"``: the same with the fixed Gauss rule of
        :meth:`tqi_integral` (~3e-8, 100x faster). ``method="raster"``: mid-point mean
        over the reachable cells of :func:`mechopt.core.quadrature.grid_over` with side
        ``step`` [L] (default: the smaller side of the bounding box /
        :data:`~mechopt.core.quadrature.RASTER_CELLS`); first-order error in ``step``.
        NaN for an empty workspace.

        Parameters
        ----------
        method : str
            ``"quad"``, ``"gauss"`` or ``"raster"``.
        step : float, optional
            Raster cell side [L].

        Returns
        -------
        float
            The GTQI (dimensionless).
        """
        _v.choice("method", method, GTQI_METHODS)
        if method in ("quad", "gauss"):
            w = self.workspace_area()
            return float(self.tqi_integral(method=method) / w) if w > 0 else float("nan")
        return self.raster_mean(self.tqi, step)

    # --- velocity output ratio (Wu 2008 sec. 3.3) ------------------------------------
    def velocity_output_ratio(self, x, leg: int = 1):
        """``k_v(i) = |x_dot / q_dot_i|`` at ``y_dot = 0`` (Wu eq. 6): ``|cot theta_i|``
        ``= h_i / |x - g_i|``.

        Depends on ``x`` only (and not on the mode); ``inf`` where the link is
        vertical, NaN where the link cannot reach its guide.

        Parameters
        ----------
        x : array_like
            Abscissae [L].
        leg : int
            1 or 2.

        Returns
        -------
        ndarray
            ``k_v(leg)`` (dimensionless).
        """
        leg = _v.choice("leg", leg, (1, 2))
        x = np.asarray(x, dtype=float)
        u = x - self._g[leg - 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            return _w(u, self._L) / np.abs(u)

    def k_v(self, x, y):
        """Velocity output ratios ``(k_v(1), k_v(2))`` of Wu eq. (6) at the poses
        ``(x, y)``: :meth:`velocity_output_ratio` of both legs, NaN where unreachable.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        k_v1, k_v2 : ndarray
            The ratios (dimensionless).
        """
        x, y = as_points(x, y)
        ok = self.reachable(x, y)
        return (np.where(ok, self.velocity_output_ratio(x, 1), np.nan),
                np.where(ok, self.velocity_output_ratio(x, 2), np.nan))

    def _k_av_default_range(self):
        """``(x_min, x_max)`` of :meth:`k_av` when not given: the whole :attr:`x_range`."""
        return self.x_range

    def k_av(self, x_min=None, x_max=None, leg: int = 1, reading: str = "literal") -> float:
        """Global velocity output ratio ``k_av`` of Wu eq. (7) of ``leg`` over ``[x_min, x_max]``.

        The range defaults to the mechanism's own (the Biglide's whole x range, the
        gantry's task rectangle ``[-b/2, b/2]``, eq. 17-18); it must lie in
        :attr:`x_range`. ``reading`` selects how eq. (6)-(7) are read; ``"literal"``
        is the one used throughout mechopt:

        ``"literal"`` (default)
            the x-mean of ``k_v(i) = |cot theta_i|`` (eq. 6 with ``y_dot = 0``, then eq. 7),
            integrated in closed form with the primitive
            ``sqrt(L^2-u^2) - L ln((L + sqrt(L^2-u^2))/|u|)`` of ``sqrt(L^2-u^2)/|u|``;
            ``inf`` if the range contains the guide of that leg (a vertical link).
            Wu's Table 1 design gives 1.787, not the printed 1.05.
        ``"displacement"``
            the x travel over the slider travel at ``y_dot = 0``,
            ``(x_max - x_min) / int |tan theta_i| dx`` (the harmonic x-mean of ``k_v``).
            Every design of Wu eq. (13) gives exactly 1 (``y_d1 = b``).
        ``"max_speed"``
            the x-mean of the largest ``|x_dot|`` with both sliders at unit speed and
            ``y_dot`` free, ``2 / |tan theta_1 - tan theta_2|`` (leg-independent),
            by 64-point Gauss-Legendre (smooth integrand; error below 1e-10 for
            the designs of Wu eq. 14-16). Wu's Table 1 design gives 1.109.

        None of these (nor the others listed in ``tests/test_gantry.py``) reproduces
        Wu's Table 1 ``k_av = 1.05``; the literal reading is kept.

        Parameters
        ----------
        x_min, x_max : float, optional
            The range of x [L] (default: the mechanism's own).
        leg : int
            1 or 2.
        reading : str
            ``"literal"``, ``"displacement"`` or ``"max_speed"``.

        Returns
        -------
        float
            ``k_av`` (dimensionless).

        Raises
        ------
        ValueError
            For a range outside :attr:`x_range`, an unknown leg or reading.
        """
        reading = _v.choice("reading", reading, K_AV_READINGS)
        leg = _v.choice("leg", leg, (1, 2))
        if x_min is None or x_max is None:
            dmin, dmax = self._k_av_default_range()
            x_min = dmin if x_min is None else x_min
            x_max = dmax if x_max is None else x_max
        x_min = _v.finite_number("x_min", x_min)
        x_max = _v.finite_number("x_max", x_max)
        if not x_min < x_max:
            raise ValueError(f"x_max must be greater than x_min = {x_min!r}, got {x_max!r}")
        lo, hi = self.x_range
        tol = _v.ROUNDING * self._L
        if x_min < lo - tol or x_max > hi + tol:
            raise ValueError(
                f"[x_min, x_max] must lie in the reachable x range [{lo!r}, {hi!r}], "
                f"got [{x_min!r}, {x_max!r}]"
            )
        l = self._L

        def wf(u):
            return math.sqrt(max(l * l - u * u, 0.0))

        if reading == "max_speed":
            g, gw = gauss_legendre(GAUSS_ORDER_KAV)
            xs = 0.5 * (x_max - x_min) * g + 0.5 * (x_max + x_min)
            u1, u2 = xs - self._g[0], xs - self._g[1]
            t1 = u1 / (-self._s[0] * _w(u1, l))  # tan theta_i = (x - g_i) / c_i
            t2 = u2 / (-self._s[1] * _w(u2, l))
            f = 2.0 / np.abs(t1 - t2)
            return float(0.5 * np.dot(gw, f))
        xb = self._g[leg - 1]
        a, b = x_min - xb, x_max - xb  # u = x - x_guide
        if reading == "literal":
            if a <= 0.0 <= b:
                return math.inf  # |cot| ~ 1/|u| is not integrable at a vertical link

            def F(u):  # primitive of sqrt(l^2-u^2)/u on u > 0
                w = wf(u)
                return w - l * math.log((l + w) / u)

            ua, ub = sorted((abs(a), abs(b)))
            return (F(ub) - F(ua)) / (x_max - x_min)
        # displacement: int |u| / sqrt(l^2-u^2) du = |w(u1) - w(u2)| on each side of 0
        if a < 0.0 < b:
            travel = (l - wf(a)) + (l - wf(b))
        else:
            travel = abs(wf(a) - wf(b))
        return (x_max - x_min) / travel if travel > 0 else math.inf


# ------------------------------------------------------------ design specification
from mechopt.core.bodies import GROUND, Body, Shapes  # noqa: E402  (appended section: the design spec)
from mechopt.core.design_spec import DesignSpec  # noqa: E402


class GuideDesignSpec(DesignSpec):
    """``mechopt design`` of two sliders on the vertical guides ``x = g_i``
    (``mech.guides``), each with one link of the length named :attr:`link` (the
    Biglide, the gantry): the strokes are derived from the task, the links must be
    longer than the half guide distance named :attr:`guide`; the reachable set has no
    holes (its complement is unbounded) and lies within ``|x| <= lmax``. The link
    angles from the guides depend on x alone (module docstring), so their extremes
    over the task lie on its boundary."""

    #: names (in :attr:`lengths`) of the half guide distance and of the link length
    guide = link = ""
    derived_strokes = True

    def validity(self, v, lmax):
        return (v[self.guide] - v[self.link]) / lmax + _v.RESOLUTION

    def joints(self, mech, x, y):
        q1, q2 = mech.slider_positions(x, y)  # the built gantries have l2 = 0: q_i = y - c_i
        g = mech.guides
        return [(np.full_like(x, g[0]), q1), (np.full_like(x, g[1]), q2), (x, y)]

    def link_angles(self, mech, x, y):
        """Each link's angle from its guide, ``arcsin(|x - g_i| / L)`` in [0, pi/2].

        Parameters
        ----------
        mech : TwoSliderMechanism
            The mechanism.
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        angle1, angle2 : ndarray
            The angles [rad], in [0, pi/2].
        """
        g, L = mech.guides, getattr(mech, self.link)
        with np.errstate(invalid="ignore"):
            return (np.arcsin(np.clip(np.abs(x - g[0]) / L, 0, 1)),
                    np.arcsin(np.clip(np.abs(x - g[1]) / L, 0, 1)))

    def links(self, mech, x, y, shapes=None):
        """The guides (``"guide1"``, ``"guide2"``: fixed, along ``x = g_i`` over the
        slider's stroke and half a carriage beyond each end), the carriages
        (``"carriage1"``, ``"carriage2"``: centred on the slider joint ``S_i = (g_i, q_i)``,
        ``carriage_length`` along the guide) and the links ``S_i A`` (``"link1"``,
        ``"link2"``) to the link joint ``A = (x, y - e)``, named ``"P"`` (the tool) when
        the reported point is the link joint itself (``e = 0``: the Biglide, the designed
        gantries), else ``"A"``.

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
        mx, my = as_points(*self.to_mech(mech, *as_points(x, y)))
        q1, q2, _, _, _ = mech.legs(mx, my)
        ok = mech.reachable(mx, my)
        tip = "P" if mech._e == 0 else "A"
        ty = np.where(ok, my - mech._e, np.nan)
        tx = np.where(ok, mx, np.nan)
        half = 0.5 * shapes.carriage_length
        out = []
        for i, (g, q, (lo, hi)) in enumerate(zip(mech.guides, (q1, q2), mech.joint_limits), start=1):
            s = f"S{i}"
            q = np.where(ok, q, np.nan)
            out += [Body.make(f"guide{i}", "guide", (s,), (GROUND, GROUND), (g, lo - half), (g, hi + half),
                              shapes, mx.shape),
                    Body.make(f"carriage{i}", "carriage", (s,), (s, s), (g, q - half), (g, q + half), shapes),
                    Body.make(f"link{i}", "distal", (s, tip), (s, tip), (g, q), (tx, ty), shapes)]
        return out

    def joint_speeds(self, mech, x, y, radius=0.0):
        """The slider ``S_i``: ``|J_i| = |(tan theta_i, 1)| = 1 / cos theta_i =
        L / sqrt(L^2 - (x - g_i)^2)`` (the closure of the module docstring), largest over
        the disc of ``radius`` where ``|x - g_i|`` is, at ``|x - g_i| + radius`` (infinite
        from ``L``: a type-I singularity within reach); the link joint ``A`` or ``P``
        translates with the platform: 1.

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
        mx, my = as_points(*self.to_mech(mech, *as_points(x, y)))
        L = mech._L
        out = {"P": np.ones_like(mx), "A": np.ones_like(mx)}
        for i, g in enumerate(mech.guides, start=1):
            u = np.abs(mx - g) + radius
            with np.errstate(divide="ignore", invalid="ignore"):
                out[f"S{i}"] = np.where(u < L, L / np.sqrt(np.maximum(L * L - u * u, 0.0)), np.inf)
        return out

    def holes(self, mech):
        return []

    def x_reach(self, lmax):
        return lmax

    def placement_scale(self, v, lmax):
        return v[self.link]

    def sketch(self, mech, px, py, mx, my):
        q1, q2, _ = mech.ik(mx, my)
        g = mech.guides
        chains = [[(g[0], float(q1)), (px, py)], [(g[1], float(q2)), (px, py)]]
        return chains, [(g[0], float(q1)), (g[1], float(q2))]

    def actuator_paths(self, mech, strokes):
        """Each guide over its slider's stroke.

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        strokes : tuple
            As in :meth:`build`.

        Returns
        -------
        list
            Segments ``((x0, y0), (x1, y1))`` [L].
        """
        return [((g, lo), (g, hi)) for g, (lo, hi) in zip(mech.guides, strokes)]

