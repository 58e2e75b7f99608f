"""The Biglide: planar PRRRP parallel mechanism with two sliders on parallel guides.

Geometry (Stan, Maties, Balan 2008, Fig. 5-6 and eq. 5): two vertical guides at
``x = +L1`` (slider 1) and ``x = -L1`` (slider 2), so ``2 L1`` is the distance between
them; slider ``i`` sits at ``S_i = (g_i, q_i)`` with ``g_1 = +L1``, ``g_2 = -L1``
(the numbering of Stan eq. 5, which puts leg 1 on the right); links of constant
length ``L2`` join the sliders to the tool centre point ``P = (x, y)``. The
actuated coordinates are the slider positions, limited to strokes
``q_i_min <= q_i <= q_i_max``. Inverse kinematics (Stan eq. 5):

    q_i = y + s_i sqrt(L2^2 - (x - g_i)^2),     s_i = +1 or -1,

the working ``mode`` being the two signs ``s1 s2`` as a string (``"--"``, ``"++"``,
``"+-"``, ``"-+"``; first character for leg 1). ``"-"`` puts the slider below ``P``;
``"--"`` is the configuration of Wu et al. 2008 (their eq. 2 with "-" only) and
the default. The same mechanism with a platform offset is Wu's gantry.

Forward kinematics: ``P`` is an intersection of the circles of radius ``L2``
around ``S1`` and ``S2``; assembly ``"up"`` puts ``P`` above the line
``S2 -> S1`` (on its left), ``"down"`` below it. Mode ``"--"`` is always
``"up"``, ``"++"`` always ``"down"``; the mixed modes change assembly across
their type-II line ``x = 0``.

Closure: differentiating ``(x - g_i)^2 + (y - q_i)^2 = L2^2``,

    (x - g_i) x_dot + (y - q_i) y_dot = (y - q_i) q_i_dot,
    A = [P - S1; P - S2],   B = diag(y - q1, y - q2) = diag(-s1 h1, -s2 h2),

with ``h_i = sqrt(L2^2 - (x - g_i)^2)``; ``J = B^-1 A`` has rows ``(tan theta_i, 1)``
(Wu eq. 4), ``theta_i`` the angle of link ``i`` from the vertical.

* Type I (``h_i = 0``, link horizontal): the vertical lines ``x = g_i -/+ L2``,
  which bound the workspace in x: ``L1 - L2 <= x <= L2 - L1``.
* Type II (``det A = 0``, links collinear): only in the mixed modes, on the whole
  line ``x = 0`` (``P`` the midpoint of ``S1 S2``); never in ``"--"``/``"++"``.
* The other boundaries of the workspace are stroke limits (arcs of radius ``L2``
  around ``(g_i, q_i_min)`` and ``(g_i, q_i_max)``); ``J`` is regular there.

``J`` depends on ``x`` only, so every local index is constant along y (Stan Fig. 30).

Workspace area (exact). For each x the leg-i admissible y form the interval
``[c_i(x), c_i(x) + S_i]`` with ``c_i = q_i_min - s_i h_i(x)`` and ``S_i`` the stroke,
so the vertical chord of the workspace is ``g(d) = max(0, min(S1, S2, d + S1, S2 - d))``
with ``d = c1 - c2``. ``g`` is piecewise linear in ``d`` with kinks at
``d in {-S1, 0, S2 - S1, S2}``; the x where ``d`` reaches a kink solve
``sigma1 h1 - sigma2 h2 = K`` (``sigma_i = -s_i``), whose squared form gives

    x^2 = K^2 (4 (L2^2 - L1^2) - K^2) / (4 (4 L1^2 + K^2)).

Between consecutive roots the chord is a constant or ``+/- d(x) + const``, and
``int h_i dx`` is a closed-form circular-segment area
(:func:`mechopt.geometry.chord_integral`): :meth:`Biglide.workspace_area` is exact
to rounding. Spurious roots of the squared equation only split an interval.

GTQI: ``int TQI(x) g(d(x)) dx / W``, adaptive Gauss-Kronrod (scipy ``quad``) on each
of those intervals, relative error below 1e-10 (:meth:`Biglide.gtqi`).

Velocity output ratio (Wu eq. 6-7): at ``y_dot = 0``, ``q_i_dot = tan(theta_i) x_dot``,
so ``k_v(i) = |x_dot / q_i_dot| = |cot theta_i| = h_i / |x - g_i|`` and ``k_av(i)`` is its
mean over ``x in [x_min, x_max]``, in closed form:
``int sqrt(L^2 - u^2)/u du = sqrt(L^2 - u^2) - L ln((L + sqrt(L^2 - u^2))/u)`` for ``u > 0``
(infinite when the range contains the guide, ``x = g_i``).

Units: lengths in any consistent unit [L], areas in [L^2]; ``k_v``, TQI dimensionless.
Stan's Table 3 varies ``L2`` in (1, 1.2) without printing ``L1`` or the strokes.

References
----------
Stan, Maties, Balan (2008), in Wu (ed.), Parallel Manipulators, Towards New
Applications, I-Tech, ISBN 978-3-902613-40-0: eq. (5), (8), (9), Figs. 5-6, 25-28,
30, Table 3.
Wu, Wang, Wang, Shao (2008), Proc. IMechE C 222:1367-1374 (doi:10.1243/09544062JMES830):
eq. (1)-(7).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from .. import geometry as _g
from .. import validation as _v
from .base import Parameter, PlanarMechanism, as_points

__all__ = ["Biglide", "MODES", "ASSEMBLY_MODES", "GTQI_METHODS", "summary", "SUMMARY_KEYS"]

MODES = ("--", "++", "+-", "-+")
ASSEMBLY_MODES = ("up", "down")
#: how :meth:`Biglide.gtqi` integrates: 1-D adaptive quadrature of exact chords, or raster
GTQI_METHODS = ("gauss", "quad", "raster")
SUMMARY_KEYS = ("workspace_area", "gtqi", "tqi_integral", "k_av_1", "k_av_2", "quadrature")
_SIGN = {"+": 1.0, "-": -1.0}
#: default raster resolution: cells across the smaller side of the bounding box
RASTER_CELLS = 400
#: stroke limits are tested with this tolerance relative to ``length_scale``, so
#: that a pose computed from ``q = q_min`` or ``q_max`` (fk) is reachable
LIMIT_RTOL = 1e-12
_QUAD_EPSREL = 1e-10


@lru_cache(maxsize=1)
def _gauss_nodes(n: int = 128):
    return np.polynomial.legendre.leggauss(n)


def _stroke(name_min, q_min, name_max, q_max):
    return _v.stroke(name_min, q_min, name_max, q_max, positive=False)


class Biglide(PlanarMechanism):
    """Biglide (PRRRP) ``Biglide(l1, l2, q1_min, q1_max, q2_min=None, q2_max=None, mode="--")``.

    Parameters
    ----------
    l1 : float
        Stan's ``L1`` [L], > 0: the guides are the lines ``x = +l1`` (slider 1) and
        ``x = -l1`` (slider 2).
    l2 : float
        Stan's ``L2`` [L], the link length, > ``l1`` (otherwise the links never meet).
    q1_min, q1_max : float
        Stroke of slider 1 along its guide [L] (y coordinates), ``q1_min < q1_max``.
    q2_min, q2_max : float, optional
        Stroke of slider 2 [L]; default to slider 1's.
    mode : {"--", "++", "+-", "-+"}
        Signs ``s1 s2`` of Stan eq. (5); ``"-"`` puts the slider below ``P``.

    See the module docstring for the kinematics, singularities and references.
    """

    cli_name = "biglide"
    cli_help = "Biglide PRRRP (Stan 2008): exact workspace area, global TQI, k_av"
    parameters = (
        Parameter("l1", "length", "L", "half the distance of the guides [L]"),
        Parameter("l2", "length", "L", "link length [L]"),
        Parameter("q1_min", "position", "L", "lower stroke limit of slider 1 [L]"),
        Parameter("q1_max", "position", "L", "upper stroke limit of slider 1 [L]"),
        Parameter("q2_min", "position", "L", "lower stroke limit of slider 2 [L] (default: q1-min)", None),
        Parameter("q2_max", "position", "L", "upper stroke limit of slider 2 [L] (default: q1-max)", None),
        Parameter("mode", "choice", "-", "signs of the inverse kinematics, leg 1 first", "--", MODES),
    )
    modes = MODES
    assembly_modes = ASSEMBLY_MODES
    joint_names = ("q1", "q2")
    angular_joints = False

    def __init__(self, l1, l2, q1_min, q1_max, q2_min=None, q2_max=None, mode: str = "--"):
        self.l1 = _v.positive_length("l1", l1)
        self.l2 = _v.positive_length("l2", l2)
        if not self.l2 > self.l1:
            raise ValueError(
                f"l2 must be greater than l1 = {self.l1!r} (otherwise the links cannot "
                f"meet), got {l2!r}"
            )
        self.q1_min, self.q1_max = _stroke("q1_min", q1_min, "q1_max", q1_max)
        q2_min = self.q1_min if q2_min is None else q2_min
        q2_max = self.q1_max if q2_max is None else q2_max
        self.q2_min, self.q2_max = _stroke("q2_min", q2_min, "q2_max", q2_max)
        self.mode = _v.choice("mode", mode, MODES)
        self._s = (_SIGN[mode[0]], _SIGN[mode[1]])
        self._g = (self.l1, -self.l1)

    def __repr__(self):
        return (
            f"Biglide(l1={self.l1!r}, l2={self.l2!r}, q1_min={self.q1_min!r}, "
            f"q1_max={self.q1_max!r}, q2_min={self.q2_min!r}, q2_max={self.q2_max!r}, "
            f"mode={self.mode!r})"
        )

    def with_mode(self, mode: str) -> "Biglide":
        """The same dimensions in another working mode."""
        return Biglide(self.l1, self.l2, self.q1_min, self.q1_max, self.q2_min, self.q2_max, mode)

    def summary(self) -> dict:
        """:data:`SUMMARY_KEYS` (see :func:`summary`)."""
        return summary(self)

    def scaled(self, factor: float) -> "Biglide":
        """Every length (``l1``, ``l2``, the stroke limits) multiplied by ``factor``
        (the Jacobian of these prismatic actuators is unchanged)."""
        f = _v.positive_length("factor", factor)
        return Biglide(self.l1 * f, self.l2 * f, self.q1_min * f, self.q1_max * f,
                       self.q2_min * f, self.q2_max * f, self.mode)

    @property
    def length_scale(self) -> float:
        """The link length ``l2`` [L]."""
        return self.l2

    @property
    def guides(self):
        """x coordinates of the guides of sliders 1 and 2: ``(l1, -l1)``."""
        return self._g

    @property
    def joint_limits(self):
        """``((q1_min, q1_max), (q2_min, q2_max))`` [L]."""
        return (self.q1_min, self.q1_max), (self.q2_min, self.q2_max)

    @property
    def x_range(self):
        """``(l1 - l2, l2 - l1)``: where both links reach (bounded by type-I lines)."""
        return (self.l1 - self.l2, self.l2 - self.l1)

    def _strokes(self):
        return ((self.q1_min, self.q1_max), (self.q2_min, self.q2_max))

    # --- kinematics ------------------------------------------------------------
    def _half_chords(self, x):
        """``(h1, h2, ok1, ok2)``: ``h_i = sqrt(l2^2 - (x - g_i)^2)`` (0 where ``|x - g_i| > l2``)."""
        out = []
        for g in self._g:
            u = x - g
            r2 = self.l2 * self.l2 - u * u
            out.append((np.sqrt(np.maximum(r2, 0.0)), r2 >= 0))
        (h1, ok1), (h2, ok2) = out
        return h1, h2, ok1, ok2

    def slider_positions(self, x, y):
        """``(q1, q2)`` of Stan eq. (5) in this mode, ignoring strokes; NaN where a link
        cannot reach its guide."""
        x, y = as_points(x, y)
        h1, h2, ok1, ok2 = self._half_chords(x)
        q1 = np.where(ok1, y + self._s[0] * h1, np.nan)
        q2 = np.where(ok2, y + self._s[1] * h2, np.nan)
        return q1, q2

    def reachable(self, x, y):
        """Both links reach their guides and both sliders lie within their strokes
        (to ``LIMIT_RTOL * length_scale``)."""
        q1, q2 = self.slider_positions(x, y)
        return self._within_strokes(q1, q2, LIMIT_RTOL)

    def ik(self, x, y):
        """Slider positions (Stan eq. 5) ``(q1, q2, reachable)`` [L]; NaN where unreachable."""
        q1, q2 = self.slider_positions(x, y)
        ok = self._within_strokes(q1, q2, LIMIT_RTOL)
        return np.where(ok, q1, np.nan), np.where(ok, q2, np.nan), ok

    def fk(self, q1, q2, assembly: str = "up", limits: bool = True):
        """Forward kinematics ``(x, y, valid)`` by intersecting the link circles.

        With ``m = S1 - S2 = (2 l1, q1 - q2)`` and the midpoint ``M = (0, (q1 + q2)/2)``,
        ``P = M +/- sqrt(l2^2 - |m|^2/4) n`` with ``n = (-(q1 - q2), 2 l1)/|m|`` the unit
        normal on the left of ``S2 -> S1``; ``"up"`` takes ``+``. ``valid`` is False
        (NaN) where ``|m| > 2 l2`` or, with ``limits=True``, a slider is outside its
        stroke.
        """
        _v.choice("assembly", assembly, ASSEMBLY_MODES)
        q1, q2 = as_points(q1, q2)
        l1, l2 = self.l1, self.l2
        dq = q1 - q2
        m2 = 4.0 * l1 * l1 + dq * dq
        with np.errstate(invalid="ignore"):
            h2 = l2 * l2 / m2 - 0.25  # (distance M -> P)^2 / |m|^2
            valid = h2 >= 0
            if limits:
                valid &= self._within_strokes(q1, q2, LIMIT_RTOL)
        h = np.sqrt(np.where(valid, h2, 0.0)) * (1.0 if assembly == "up" else -1.0)
        x = -h * dq
        y = 0.5 * (q1 + q2) + h * 2.0 * l1
        return np.where(valid, x, np.nan), np.where(valid, y, np.nan), valid

    def assembly_of(self, x, y):
        """``"up"`` where ``P`` is on the left of ``S2 -> S1`` (or on it), else ``"down"``."""
        x, y = as_points(x, y)
        q1, q2 = self.slider_positions(x, y)
        cross = 2.0 * self.l1 * (y - q2) - (q1 - q2) * (x + self.l1)
        return np.where(cross >= 0, "up", "down")

    def closure(self, x, y):
        """``A = [P - S1; P - S2]``, ``b = (y - q1, y - q2)``; NaN where unreachable."""
        x, y = as_points(x, y)
        q1, q2, ok = self.ik(x, y)
        nan = np.where(ok, 0.0, np.nan)
        A = np.stack(
            [
                np.stack([x - self._g[0] + nan, y - q1], -1),
                np.stack([x - self._g[1] + nan, y - q2], -1),
            ],
            -2,
        )
        return A, np.stack([y - q1, y - q2], -1), ok

    def serial_clearance(self, x, y):
        """Signed distance to the boundary of the reachable set, positive inside.

        Per leg the boundary is two arcs of radius ``l2`` (stroke limits, around
        ``(g_i, q_i_min)`` and ``(g_i, q_i_max)``) and two vertical segments on the
        type-I lines ``x = g_i +/- l2``; inside, the distance to each piece is
        closed form (the near arc: ``|P - C| - l2``; the far arc: ``l2 - |P - C|``
        when ``P`` faces it, otherwise its endpoints are covered by the segments),
        and the result is their minimum. Outside it is minus the largest constraint
        violation (``|x - g_i| - l2``, ``q_i_min - q_i`` or ``q_i - q_i_max``): negative,
        but not the distance.
        """
        x, y = as_points(x, y)
        L = self.l2
        q1, q2 = self.slider_positions(x, y)
        inside_terms, viol_terms = [], []
        for g, s, q, (qmin, qmax) in zip(self._g, self._s, (q1, q2), self._strokes()):
            u = x - g
            q_near, q_far = (qmin, qmax) if s < 0 else (qmax, qmin)
            d_near = np.hypot(u, y - q_near) - L
            faces = (y - q_far) * (-s) >= 0
            d_far = np.where(faces, L - np.hypot(u, y - q_far), np.inf)
            dy = np.maximum.reduce([np.zeros_like(y), y - qmax, qmin - y])
            d_side = np.hypot(L - np.abs(u), dy)
            inside_terms += [d_near, d_far, d_side]
            with np.errstate(invalid="ignore"):
                v = np.where(np.isnan(q), np.abs(u) - L, np.maximum(qmin - q, q - qmax))
            viol_terms.append(v)
        ok = self.reachable(x, y)
        inside = np.minimum.reduce(inside_terms)
        outside = -np.maximum.reduce(viol_terms)
        return np.where(ok, inside, outside)

    def _leg_y_ranges(self):
        xa, xb = self.x_range
        out = []
        for g, s, (qmin, qmax) in zip(self._g, self._s, self._strokes()):
            umin = 0.0 if xa <= g <= xb else min(abs(xa - g), abs(xb - g))
            hmax = np.sqrt(max(self.l2**2 - umin**2, 0.0))
            out.append((qmin, qmax + hmax) if s < 0 else (qmin - hmax, qmax))
        return out

    def bounding_box(self):
        """``(l1 - l2, l2 - l1, ymin, ymax)``: y from each leg's stroke and the
        largest ``h_i`` over the x range, intersected over the legs."""
        xa, xb = self.x_range
        (a1, b1), (a2, b2) = self._leg_y_ranges()
        ymin, ymax = max(a1, a2), min(b1, b2)
        if ymax < ymin:  # empty workspace
            ymax = ymin
        return (xa, xb, ymin, ymax)

    # --- velocity output ratio (Wu 2008) ----------------------------------------
    def k_v(self, x, y):
        """Velocity output ratios ``(k_v(1), k_v(2))`` of Wu eq. (6): ``h_i / |x - g_i|``.

        Independent of ``y`` and of the mode; ``inf`` where a link is vertical,
        NaN where unreachable.
        """
        x, y = as_points(x, y)
        ok = self.reachable(x, y)
        h1, h2, _, _ = self._half_chords(x)
        with np.errstate(divide="ignore"):
            k1 = h1 / np.abs(x - self._g[0])
            k2 = h2 / np.abs(x - self._g[1])
        return np.where(ok, k1, np.nan), np.where(ok, k2, np.nan)

    def k_av(self, leg: int, x_min=None, x_max=None) -> float:
        """Global velocity output ratio of Wu eq. (7) for ``leg`` 1 or 2, closed form.

        The mean of ``k_v(leg)`` over ``x in [x_min, x_max]`` (default: the whole
        x range of the workspace, :attr:`x_range`); ``inf`` if the interval contains
        the guide of that leg.
        """
        if leg not in (1, 2):
            raise ValueError(f"leg must be 1 or 2, got {leg!r}")
        xa, xb = self.x_range
        x_min = xa if x_min is None else _v.finite_number("x_min", x_min)
        x_max = xb if x_max is None else _v.finite_number("x_max", x_max)
        if not x_max > x_min:
            raise ValueError(f"x_max must be greater than x_min = {x_min!r}, got {x_max!r}")
        tol = 1e-12 * self.l2
        if x_min < xa - tol or x_max > xb + tol:
            raise ValueError(
                f"[x_min, x_max] must lie in the workspace x range [{xa!r}, {xb!r}], "
                f"got [{x_min!r}, {x_max!r}]"
            )
        g = self._g[leg - 1]
        u0, u1 = x_min - g, x_max - g
        if u0 <= 0.0 <= u1:
            return float("inf")
        a, c = sorted((abs(u0), abs(u1)))
        L = self.l2

        def G(u):
            w = np.sqrt(max(L * L - u * u, 0.0))
            return w - L * np.log((L + w) / u)

        return float((G(c) - G(a)) / (x_max - x_min))

    # --- exact workspace area and GTQI -------------------------------------------
    def _breakpoints(self):
        """Sorted x in the x range where the chord changes formula (module docstring)."""
        xa, xb = self.x_range
        (a1, b1), (a2, b2) = self._strokes()
        S1, S2 = b1 - a1, b2 - a2
        l1, L = self.l1, self.l2
        pts = [xa, xb, 0.0]
        for k in (-S1, 0.0, S2 - S1, S2):
            K = k - (a1 - a2)
            num = K * K * (4.0 * (L * L - l1 * l1) - K * K)
            den = 4.0 * (4.0 * l1 * l1 + K * K)
            if num >= 0:
                r = np.sqrt(num / den)
                pts += [r, -r]
        pts = np.unique(np.clip(pts, xa, xb))
        return pts

    def _d(self, x):
        """``d(x) = c1(x) - c2(x)``, ``c_i = q_i_min - s_i h_i(x)``."""
        h1, h2, _, _ = self._half_chords(np.asarray(x, dtype=float))
        return (self.q1_min - self.q2_min) - self._s[0] * h1 + self._s[1] * h2

    def chord(self, x):
        """Exact length [L] of the vertical section of the workspace at ``x``."""
        x = np.asarray(x, dtype=float)
        (a1, b1), (a2, b2) = self._strokes()
        S1, S2 = b1 - a1, b2 - a2
        d = self._d(x)
        g = np.maximum(0.0, np.minimum.reduce([np.full_like(d, S1), np.full_like(d, S2),
                                               d + S1, S2 - d]))
        xa, xb = self.x_range
        return np.where((x >= xa) & (x <= xb), g, 0.0)

    def workspace_area(self) -> float:
        """Exact area W [L^2] of the workspace of this mode (Stan eq. 8; module docstring)."""
        (a1, b1), (a2, b2) = self._strokes()
        S1, S2 = b1 - a1, b2 - a2
        L = self.l2
        pts = self._breakpoints()
        total = 0.0
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
            ih1 = float(_g.chord_integral(L, x0 - self._g[0], x1 - self._g[0]))
            ih2 = float(_g.chord_integral(L, x0 - self._g[1], x1 - self._g[1]))
            int_d = (a1 - a2) * dx - self._s[0] * ih1 + self._s[1] * ih2
            total += (int_d + S1 * dx) if k == 2 else (S2 * dx - int_d)
        return float(total)

    def tqi_of_x(self, x):
        """TQI (Stan eq. 9) as a function of ``x`` alone: ``2 |t1 - t2| / (t1^2 + t2^2 + 2)``
        with ``t_i = (x - g_i)/(y - q_i)`` the slopes of ``J``'s rows; 0 on type-I lines."""
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
        """
        pts = self._breakpoints()
        if method == "gauss":
            t, w = _gauss_nodes()
            total = 0.0
            for x0, x1 in zip(pts[:-1], pts[1:]):
                if x1 > x0:
                    xs = 0.5 * (x1 - x0) * t + 0.5 * (x0 + x1)
                    total += 0.5 * (x1 - x0) * float(np.sum(w * self.tqi_of_x(xs) * self.chord(xs)))
            return (total, float("nan")) if return_error else total
        total, err = 0.0, 0.0
        f = lambda t: float(self.tqi_of_x(t) * self.chord(t))  # noqa: E731
        # an absolute floor far below the result: a sliver interval (1e-8 wide at an end
        # of the x range) cannot reach the relative tolerance in floating point
        epsabs = 1e-14 * self.length_scale ** 2
        for x0, x1 in zip(pts[:-1], pts[1:]):
            if x1 <= x0:
                continue
            from scipy import integrate  # only the adaptive rule needs scipy

            v, e = integrate.quad(f, x0, x1, epsabs=epsabs, epsrel=_QUAD_EPSREL, limit=200)
            total += v
            err += e
        return (total, err) if return_error else total

    def gtqi(self, method: str = "quad", step=None) -> float:
        """Area mean of the TQI (Stan eq. 9) over the workspace of this mode.

        ``method="quad"``: :meth:`tqi_integral` / :meth:`workspace_area` (TQI depends
        on x only, so the 2-D mean is a 1-D integral of exact chord lengths; relative
        error ~1e-10); ``method="gauss"``: the same with the fixed Gauss rule of
        :meth:`tqi_integral` (~3e-8, 100x faster). ``method="raster"``: mid-point mean over the reachable cells of
        :func:`mechopt.quadrature.grid_over` with side ``step`` [L] (default: the
        smaller side of the bounding box / 400); first-order error in ``step``.
        NaN for an empty workspace.
        """
        _v.choice("method", method, GTQI_METHODS)
        if method in ("quad", "gauss"):
            w = self.workspace_area()
            return float(self.tqi_integral(method=method) / w) if w > 0 else float("nan")
        return self.raster_mean(self.tqi, step, RASTER_CELLS)


def summary(mech: Biglide) -> dict:
    """Floats of :data:`SUMMARY_KEYS` for ``mechopt evaluate biglide``.

    ``workspace_area`` [L^2] exact (Stan eq. 8, mode of ``mech``); ``gtqi`` the area
    mean of the TQI (Stan eq. 9, 1-D quadrature, rel. error ~1e-10);
    ``tqi_integral`` [L^2] its numerator; ``k_av_1``, ``k_av_2`` Wu's eq. (7) over
    the whole x range (``inf`` when it contains that leg's guide, i.e. ``l2 >= 2 l1``);
    ``quadrature`` names the rule of the GTQI: ``"adaptive-1d"`` (exact area, adaptive
    1-D quadrature of the TQI's column integrals, relative tolerance 1e-10).
    """
    if not isinstance(mech, Biglide):
        raise ValueError(f"mech must be a Biglide, got {type(mech).__name__}")
    w = mech.workspace_area()
    ti = mech.tqi_integral()
    return {
        "workspace_area": w,
        "gtqi": ti / w if w > 0 else float("nan"),
        "tqi_integral": ti,
        "k_av_1": mech.k_av(1),
        "k_av_2": mech.k_av(2),
        "quadrature": "adaptive-1d",
    }
