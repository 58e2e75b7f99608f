"""The 2-DOF gantry of Wu, Wang, Wang, Shao (2008): two vertical sliders, three equal links.

Geometry (Wu 2008 Fig. 1-2, eq. 1-2). Two sliders ``B1``, ``B2`` run on vertical
columns at ``x = -d1`` and ``x = d1``; their heights are the actuator coordinates
``q1 = y_B1``, ``q2 = y_B2`` [L]. Links ``A_i B_i`` of the common length ``l`` join
them to the moving platform, whose reference point ``O' = (x, y)`` sits ``l2/2``
above the platform joints ``A1``, ``A2``. The left chain is a parallelogram: a third
link ``A3 B3`` of length ``l``, ``l2`` higher (the slider ``B1 B3`` is as tall as the
platform, ``l3 = l2``), keeps the platform from rotating. With ``theta_i`` the angle
of link ``A_i B_i`` from the vertical (eq. 1),

    sin(theta_i) = (x - x_Bi) / l,   cos(theta_i) = (y - l2/2 - q_i) / l,

and the inverse kinematics (eq. 2) is

    q_i = y - l2/2 (+/-) sqrt(l^2 - (x - x_Bi)^2),     x_B1 = -d1, x_B2 = d1.

Working modes are strings of the two signs of eq. (2), leg 1 first. The default
``"--"`` is the paper's configuration (sliders below the platform joints,
``0 < |theta_i| < pi/2``, sec. 3.1); ``"++"``, ``"-+"`` and ``"+-"`` are the other
branches. Eq. (1)-(2) give both lower platform joints the abscissa ``x`` of ``O'``,
so the platform half-width ``d2`` enters neither the kinematics nor the dynamics of
the paper: it is stored (Table 1 lists it) but changes no result.

Differentiating the closure ``(x - x_Bi)^2 + (y - l2/2 - q_i)^2 = l^2`` gives
``a_i . p_dot = c_i q_dot_i`` with ``a_i = A_i - B_i = l (sin theta_i, cos theta_i)``
and ``c_i = l cos(theta_i)``, so ``J = B^-1 A`` has rows ``(tan theta_i, 1)``: Wu
eq. (4)-(5). Type I (serial): ``cos theta_i = 0`` (a link horizontal); type II:
``sin(theta_1 - theta_2) = 0`` (the links parallel), which the modes ``"--"`` and
``"++"`` never reach because ``d1 > 0`` (Wu sec. 3.1); the mixed modes do.

The sliders' stroke ``[q_min, q_min + stroke]`` bounds the reachable set: for each
leg it is the region between two arcs of radius ``l`` (Wu Fig. 2, eq. 8-9), so the
reachable set is an intersection of two such regions and its area is closed form
(:meth:`Gantry.workspace_area`). Note that the arcs made by the stroke limits are
joint limits, not type-I loci: only the vertical sides ``x = +-(l - d1)`` are.

References
----------
Wu J, Wang J, Wang L, Shao H (2008), Dimensional synthesis and dynamic
manipulability of a planar two-degree-of-freedom parallel manipulator, Proc. IMechE
Part C: J. Mechanical Engineering Science 222, doi:10.1243/09544062JMES830,
eq. (1)-(18), Table 1.
"""
from __future__ import annotations

import math

import numpy as np

from .. import validation as _v
from .base import Parameter, PlanarMechanism, as_points

__all__ = [
    "Gantry",
    "MODES",
    "ASSEMBLY_MODES",
    "K_AV_READINGS",
    "dimensional_synthesis",
    "k_av_literal_of_design",
    "wu2008_gantry",
    "summary",
    "SUMMARY_KEYS",
]

MODES = ("--", "++", "-+", "+-")
ASSEMBLY_MODES = ("up", "down")
K_AV_READINGS = ("literal", "displacement", "max_speed")
_SIGN = {"+": 1.0, "-": -1.0}
_LENGTH_UNITS = {"mm": 1e-3, "m": 1.0}

#: abscissa of the task rectangle's lower edge of the Wu machine, placed so that
#: the path of Table 3 (y = 0.5 m) runs at mid-height of the 400 mm task height.
#: The paper gives no absolute height; no kinematic or dynamic index depends on it.
WU2008_TASK_Y_MIN_MM = 300.0


def _w(u, l):
    """``sqrt(l^2 - u^2)``; NaN where ``|u| > l``."""
    with np.errstate(invalid="ignore"):
        return np.sqrt(l * l - u * u)


def _arc_primitive(u, l):
    """``int_0^u sqrt(l^2 - t^2) dt`` for ``|u| <= l`` (clipped)."""
    u = np.clip(u, -l, l)
    return 0.5 * (u * np.sqrt(max(l * l - u * u, 0.0)) + l * l * math.asin(u / l))


def dimensional_synthesis(b, h, theta_1S):
    """Workspace-based dimensional synthesis of Wu 2008 sec. 4.2, eq. (10)-(16).

    Given the task rectangle ``b x h`` and the smallest link angle ``theta_1S``, with
    the 1:1 input/output condition of eq. (13) (``theta_1S + theta_2L = pi/2``)::

        d = b tan(theta_1S) / (1 - tan(theta_1S))            eq. (14)
        l = (b + d) / sin(theta_2L),  d1 = (b + 2 d) / 2     eq. (15)
        |q_iL - q_iS| = y_d1 + h,  y_d1 = b                  eq. (12)-(13), (16)

    Parameters
    ----------
    b, h : float
        Width and height of the rectangular task workspace [L], > 0.
    theta_1S : float
        Smallest angle of link ``A1B1`` from the vertical [rad], in (0, pi/4).

    Returns
    -------
    (d, d1, l, stroke) : tuple of float
        [L]. ``d`` is the horizontal distance from a column to the nearer side of the
        task rectangle (Wu Fig. 2), ``d1`` half the column distance, ``l`` the link
        length and ``stroke`` the slider travel ``|q_iL - q_iS|``.

    Examples
    --------
    Wu sec. 4.2 (theta_1S = 15 deg): d1 = 433, l = 707.1, stroke = 900 [mm];
    Table 1 (theta_1S = 10 deg): d1 = 357, l = 616.4, stroke = 900 [mm].
    """
    b = _v.positive_length("b", b)
    h = _v.positive_length("h", h)
    th = _v.finite_number("theta_1S", theta_1S)
    if not 0.0 < th < math.pi / 4:
        raise ValueError(
            f"theta_1S must lie in the open interval (0, pi/4) rad (0 to 45 deg), got {theta_1S!r}"
        )
    t = math.tan(th)
    d = b * t / (1.0 - t)  # eq. (14)
    theta_2L = math.pi / 2 - th  # eq. (13)
    l = (b + d) / math.sin(theta_2L)  # eq. (15)
    d1 = (b + 2.0 * d) / 2.0  # eq. (15)
    y_d1 = l * (math.cos(th) - math.sin(math.pi / 2 - theta_2L))  # eq. (12), = b
    stroke = y_d1 + h  # eq. (16)
    return d, d1, l, stroke


def k_av_literal_of_design(theta_1S):
    """Literal ``k_av`` (eq. 6-7) of a design of :func:`dimensional_synthesis`, vectorised.

    Over ``x in [-b/2, b/2]`` (eq. 17-18) ``sin(theta_1)`` runs from ``sin(theta_1S)`` to
    ``cos(theta_1S)`` and ``b = l (cos theta_1S - sin theta_1S)``, so the x-mean of
    ``|cot theta_1|`` depends on ``theta_1S`` only:

        k_av = [F(cos t) - F(sin t)] / (cos t - sin t),
        F(s) = sqrt(1 - s^2) - ln((1 + sqrt(1 - s^2)) / s).

    ``theta_1S`` in rad, in (0, pi/4). Decreases from +inf to 1 over that interval
    (Wu sec. 4.3: "k_av descends when theta_1 varies from 0 to 90 deg").
    """
    try:
        th = np.asarray(theta_1S, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"theta_1S must be a number or an array of numbers, got {_v.show(theta_1S)}") from None
    if np.any(~np.isfinite(th)) or np.any((th <= 0) | (th >= math.pi / 4)):
        raise ValueError(
            f"theta_1S must lie in the open interval (0, pi/4) rad, got {_v.show(theta_1S)}"
        )

    def F(s):
        c = np.sqrt(1.0 - s * s)
        return c - (np.log(1.0 + c) - np.log(s))  # (1 + c)/s overflows for a tiny theta_1S

    s0, s1 = np.sin(th), np.cos(th)
    return (F(s1) - F(s0)) / (s1 - s0)


class Gantry(PlanarMechanism):
    """Wu 2008 gantry ``Gantry(d1, l, stroke, q_min=0, l2=0, d2=0, mode="--")``.

    Parameters
    ----------
    d1 : float
        Half the distance between the slider columns [L], > 0 (columns at ``x = -+d1``).
    l : float
        Length of the three links [L], > d1 (Wu sec. 3.1: ``2 l > 2 d1``).
    stroke : float
        Slider travel ``|q_iL - q_iS|`` [L], > 0 (eq. 16).
    q_min : float
        Lower stroke limit ``q_iS`` of both sliders [L]; ``q_max = q_min + stroke``.
    l2 : float
        Platform height [L], >= 0: ``O'`` is ``l2/2`` above the platform joints (eq. 1).
    d2 : float
        Platform half-width [L], >= 0 (enters no equation of the paper, see module doc).
    mode : {"--", "++", "-+", "+-"}
        Signs of eq. (2) for legs 1 and 2; ``"--"`` is the paper's.
    task_workspace : tuple, optional
        ``(xmin, xmax, ymin, ymax)`` of the rectangular task workspace ``W_t`` [L]
        (Wu Fig. 2: ``Q1Q2Q3Q4``); set by :meth:`from_synthesis`.

    Lengths may be in any consistent unit [L]; angles are in rad. The actuator
    coordinates are lengths, so the Jacobian is dimensionless and invariant under a
    change of length unit (see :meth:`scaled`).
    """

    cli_name = "gantry"
    cli_help = "Wu 2008 gantry: synthesis (eq. 10-16), k_av, eta_D, GTQI"
    parameters = (
        Parameter("b", "length", "length unit", "task width", 500.0),
        Parameter("h", "length", "length unit", "task height", 400.0),
        Parameter("theta_1s_deg", "angle_deg", "deg", "smallest link angle theta_1S, in (0, 45)", 10.0),
        Parameter("d2", "length0", "length unit", "platform half-width", 100.0),
        Parameter("l2", "length0", "length unit", "platform height", 200.0),
        Parameter("length_unit", "choice", "-", "unit of the lengths given and printed", "mm",
                  tuple(_LENGTH_UNITS)),
    )
    modes = MODES
    assembly_modes = ASSEMBLY_MODES
    joint_names = ("q1", "q2")
    angular_joints = False
    #: the inputs of :meth:`from_parameters` when the gantry was synthesized from them
    synthesis_inputs: dict | None = None
    #: the boundary of the reachable set includes stroke-limit arcs (joint limits),
    #: which are not type-I loci (see the module docstring)
    reachable_boundary_is_type1 = False

    def __init__(self, d1, l, stroke, q_min=0.0, l2=0.0, d2=0.0, mode: str = "--",
                 task_workspace=None):
        self.d1 = _v.positive_length("d1", d1)
        self.l = _v.positive_length("l", l)
        if not self.l > self.d1:
            raise ValueError(f"l must be greater than d1 = {self.d1!r} (Wu sec. 3.1), got {l!r}")
        self.stroke = _v.positive_length("stroke", stroke)
        self.q_min = _v.coordinate("q_min", q_min)
        self.l2 = _v.nonnegative_length("l2", l2)
        self.d2 = _v.nonnegative_length("d2", d2)
        self.mode = _v.choice("mode", mode, MODES)
        self._s = (_SIGN[mode[0]], _SIGN[mode[1]])
        if task_workspace is not None:
            try:
                tw = tuple(_v.coordinate("task_workspace", v) for v in task_workspace)
            except TypeError:
                raise ValueError(
                    f"task_workspace must be (xmin, xmax, ymin, ymax), got {_v.show(task_workspace)}"
                ) from None
            if len(tw) != 4 or not (tw[0] < tw[1] and tw[2] < tw[3]):
                raise ValueError(
                    "task_workspace must be (xmin, xmax, ymin, ymax) with xmin < xmax and "
                    f"ymin < ymax, got {_v.show(task_workspace)}"
                )
            task_workspace = tw
        self.task_workspace = task_workspace

    # --- constructors ---------------------------------------------------------
    @classmethod
    def from_synthesis(cls, b, h, theta_1S, l2=0.0, d2=0.0, task_y_min=0.0):
        """The design of :func:`dimensional_synthesis`, with its task rectangle in place.

        The task rectangle is ``[-b/2, b/2] x [task_y_min, task_y_min + h]`` (eq. 17-18).
        The lower stroke limit follows from Wu Fig. 2: at ``Q2 = (-b/2, task_y_min)``
        slider 1 is at ``q_1S`` with ``theta_1 = theta_1S``, so
        ``q_min = task_y_min - l2/2 - l cos(theta_1S)``; the corners ``Q1``-``Q4`` then lie
        on the boundary of the reachable set.
        """
        d, d1, l, stroke = dimensional_synthesis(b, h, theta_1S)
        y0 = _v.coordinate("task_y_min", task_y_min)
        l2 = _v.nonnegative_length("l2", l2)
        q_min = y0 - l2 / 2.0 - l * math.cos(theta_1S)
        return cls(d1, l, stroke, q_min=q_min, l2=l2, d2=d2, mode="--",
                   task_workspace=(-b / 2.0, b / 2.0, y0, y0 + h))

    @classmethod
    def from_parameters(cls, b=500.0, h=400.0, theta_1s_deg=10.0, d2=100.0, l2=200.0,
                        length_unit="mm") -> "Gantry":
        """The design of Wu's synthesis (eq. 10-16) for a ``b x h`` task and ``theta_1S``
        [deg], task rectangle at its place (:meth:`from_synthesis`)."""
        unit = _v.choice("length_unit", length_unit, tuple(_LENGTH_UNITS))
        deg = _v.finite_number("theta_1s_deg", theta_1s_deg)
        if not 0.0 < deg < 45.0:
            raise ValueError(f"theta_1s_deg must lie in (0, 45) deg (eq. 14), got {_v.show(theta_1s_deg)}")
        g = cls.from_synthesis(b, h, math.radians(deg), l2=l2, d2=d2)
        g.synthesis_inputs = dict(b=float(b), h=float(h), theta_1s_deg=deg, d2=float(d2),
                                  l2=float(l2), length_unit=unit)
        return g

    def parameter_values(self) -> dict:
        """The synthesis inputs of :meth:`from_parameters` (None if made otherwise)."""
        if self.synthesis_inputs is None:
            return {k: getattr(self, k) for k in ("d1", "l", "stroke", "q_min", "l2", "d2", "mode")}
        return dict(self.synthesis_inputs)

    def summary(self) -> dict:
        """:data:`SUMMARY_KEYS` of the synthesized design (see :func:`summary`)."""
        if self.synthesis_inputs is None:
            raise ValueError("summary needs a gantry made by Gantry.from_parameters (Wu's synthesis)")
        kw = dict(self.synthesis_inputs)
        deg = kw.pop("theta_1s_deg")
        return summary(theta_1S=math.radians(deg), **kw)

    def __repr__(self):
        return (f"Gantry(d1={self.d1!r}, l={self.l!r}, stroke={self.stroke!r}, "
                f"q_min={self.q_min!r}, l2={self.l2!r}, d2={self.d2!r}, mode={self.mode!r})")

    def with_mode(self, mode: str) -> "Gantry":
        """The same dimensions in another working mode."""
        return Gantry(self.d1, self.l, self.stroke, self.q_min, self.l2, self.d2, mode,
                      self.task_workspace)

    def scaled(self, factor) -> "Gantry":
        """Every length (and the task rectangle) multiplied by ``factor``, e.g. 1e-3 for mm -> m.

        With prismatic actuators the Jacobian does not change (a five-bar's scales as 1/D).
        """
        f = _v.positive_length("factor", factor)
        tw = None if self.task_workspace is None else tuple(f * v for v in self.task_workspace)
        return Gantry(self.d1 * f, self.l * f, self.stroke * f, self.q_min * f, self.l2 * f,
                      self.d2 * f, self.mode, tw)

    # --- basic geometry ---------------------------------------------------------
    @property
    def q_max(self) -> float:
        return self.q_min + self.stroke

    @property
    def column_x(self):
        """``(x_B1, x_B2) = (-d1, d1)``."""
        return (-self.d1, self.d1)

    @property
    def length_scale(self) -> float:
        return self.l

    @property
    def x_range(self):
        """``(d1 - l, l - d1)``: abscissae where both links reach their columns."""
        return (self.d1 - self.l, self.l - self.d1)

    def _offsets(self, x):
        """``c_i = y - l2/2 - q_i = l cos(theta_i)`` as a function of x only, per leg."""
        s1, s2 = self._s
        c1 = -s1 * _w(x + self.d1, self.l)
        c2 = -s2 * _w(x - self.d1, self.l)
        return c1, c2

    def link_angles(self, x, y):
        """``(theta_1, theta_2)`` of eq. (1) [rad], in (-pi, pi]; NaN where unreachable."""
        x, y = as_points(x, y)
        ok = self.reachable(x, y)
        c1, c2 = self._offsets(x)
        t1 = np.arctan2(x + self.d1, c1)
        t2 = np.arctan2(x - self.d1, c2)
        return np.where(ok, t1, np.nan), np.where(ok, t2, np.nan)

    def y_interval(self, x):
        """``(y_lo, y_hi)`` of the reachable set at abscissa ``x`` (NaN where empty).

        Leg i admits ``y in [q_min + l2/2 + c_i(x), q_max + l2/2 + c_i(x)]`` (eq. 8-9).
        """
        x = np.asarray(x, dtype=float)
        c1, c2 = self._offsets(x)
        base = self.l2 / 2.0
        lo = self.q_min + base + np.maximum(c1, c2)
        hi = self.q_max + base + np.minimum(c1, c2)
        empty = ~(lo <= hi)
        return np.where(empty, np.nan, lo), np.where(empty, np.nan, hi)

    # --- protocol ------------------------------------------------------------------
    def legs(self, x, y):
        """``(q1, q2, c1, c2, reachable)`` without masking: slider positions (eq. 2) and
        ``c_i = l cos(theta_i)`` [L] of both legs (for the dynamics' ``tan theta_i``)."""
        c1, c2 = self._offsets(x)
        y_a = y - self.l2 / 2.0
        q1 = y_a - c1
        q2 = y_a - c2
        # the task rectangle of a synthesized design touches the stroke ends exactly
        # (eq. 16), so accept rounding-level excursions past them
        tol = 1e-12 * max(abs(self.q_min), abs(self.q_max), self.length_scale)
        lo, hi = self.q_min - tol, self.q_max + tol
        with np.errstate(invalid="ignore"):
            ok = (q1 >= lo) & (q1 <= hi) & (q2 >= lo) & (q2 <= hi)
        return q1, q2, c1, c2, ok

    def reachable(self, x, y):
        x, y = as_points(x, y)
        return self.legs(x, y)[4]

    def ik(self, x, y):
        """Slider heights ``(q1, q2, reachable)`` of eq. (2) in the working mode [L]."""
        x, y = as_points(x, y)
        q1, q2, _, _, ok = self.legs(x, y)
        return np.where(ok, q1, np.nan), np.where(ok, q2, np.nan), ok

    def closure(self, x, y):
        """``A p_dot = B q_dot`` with ``a_i = A_i - B_i`` and ``B_ii = c_i = l cos(theta_i)``.

        Rows of ``J = B^-1 A`` are ``(tan theta_i, 1)`` (Wu eq. 4-5).
        """
        x, y = as_points(x, y)
        _, _, c1, c2, ok = self.legs(x, y)
        u1 = x + self.d1
        u2 = x - self.d1
        A = np.stack([np.stack([u1, c1], -1), np.stack([u2, c2], -1)], -2)
        b = np.stack([c1, c2], -1)
        A = np.where(ok[..., None, None], A, np.nan)
        b = np.where(ok[..., None], b, np.nan)
        return A, b, ok

    def fk(self, q1, q2, assembly: str = "up"):
        """Forward kinematics: intersect the circles of radius ``l`` about ``B1``, ``B2``.

        The lower platform joint ``A = (x, y - l2/2)`` is at distance ``l`` from both
        ``B1 = (-d1, q1)`` and ``B2 = (d1, q2)`` (eq. 8-9). ``assembly="up"`` puts ``A``
        on the left of the vector ``B1 -> B2`` (above the line ``B1 B2``), ``"down"`` on
        its right. ``valid`` is False (and ``x``, ``y`` NaN) where the circles do not
        meet or a slider is outside its stroke ``[q_min, q_max]``.
        """
        _v.choice("assembly", assembly, ASSEMBLY_MODES)
        q1, q2 = as_points(q1, q2)
        mx = 2.0 * self.d1
        my = q2 - q1
        m2 = mx * mx + my * my
        h2 = self.l * self.l / m2 - 0.25
        with np.errstate(invalid="ignore"):
            valid = ((h2 >= 0) & (q1 >= self.q_min) & (q1 <= self.q_max)
                     & (q2 >= self.q_min) & (q2 <= self.q_max))
        h = np.sqrt(np.clip(h2, 0.0, None)) * (1.0 if assembly == "up" else -1.0)
        ax = 0.0 - h * my  # midpoint of B1 B2 has x = 0
        ay = 0.5 * (q1 + q2) + h * mx
        y = ay + self.l2 / 2.0
        return np.where(valid, ax, np.nan), np.where(valid, y, np.nan), valid

    def assembly_of(self, x, y):
        """Which :meth:`fk` assembly mode (``"up"``/``"down"``) a pose of this working mode is in."""
        x, y = as_points(x, y)
        q1, q2, _ = self.ik(x, y)
        ay = y - self.l2 / 2.0
        cross = 2.0 * self.d1 * (ay - q1) - (q2 - q1) * (x + self.d1)
        return np.where(cross >= 0, "up", "down")

    def serial_clearance(self, x, y):
        """Signed distance to the boundary of the reachable set, positive inside.

        Exact inside: the minimum over both legs of the distance to the two
        stroke-limit arcs and the two vertical sides ``|x - x_Bi| = l`` of the leg's
        region (Wu Fig. 2). Outside the value is negative; its magnitude is the
        distance to the nearest violated piece, a lower bound of the distance to the
        set. Only the vertical sides are type-I loci; the arcs are joint limits.
        """
        x, y = as_points(x, y)
        base = self.l2 / 2.0
        lo, hi = self.q_min + base, self.q_max + base
        out = []
        for xb, s in zip(self.column_x, self._s):
            u = x - xb
            if s < 0:  # "-": region between upper half circles about (xb, lo), (xb, hi)
                out.append(self._leg_clearance(u, y, lo, hi))
            else:  # "+": mirror image in y
                out.append(self._leg_clearance(u, -y, -hi, -lo))
        return np.minimum(out[0], out[1])

    def _leg_clearance(self, u, v, lo, hi):
        """Signed distance for ``{|u| <= l, lo + w(u) <= v <= hi + w(u)}``, ``w = sqrt(l^2-u^2)``."""
        l = self.l
        au = np.abs(u)
        # lower arc: upper half circle of radius l about (0, lo)
        lower = np.where(v >= lo, np.hypot(u, v - lo) - l, -np.hypot(l - au, v - lo))
        # upper arc: upper half circle about (0, hi); below its diameter the side is nearer
        upper = np.where(v >= hi, l - np.hypot(u, v - hi), np.inf)
        side = l - au
        return np.minimum(np.minimum(lower, upper), side)

    def bounding_box(self):
        """``(xmin, xmax, ymin, ymax)``, tight: the extremes of :meth:`y_interval`.

        Between the candidate abscissae (the ends of :attr:`x_range`, ``0``, ``+-d1`` and
        the breakpoints of :meth:`workspace_area`) both offsets ``c_i(x)`` are monotone,
        so the lower and upper bounds of the set reach their extremes at candidates.
        """
        xmin, xmax = self.x_range
        xs = np.array([p for p in self._candidates() if xmin <= p <= xmax])
        c1, c2 = self._offsets(xs)
        base = self.l2 / 2.0
        lo = self.q_min + base + np.maximum(c1, c2)
        hi = self.q_max + base + np.minimum(c1, c2)
        keep = lo <= hi + 1e-9 * self.l  # non-empty (to rounding at pinch points)
        return (float(xmin), float(xmax), float(np.min(lo[keep])), float(np.max(hi[keep])))

    def _candidates(self):
        """Abscissae where ``c_1 - c_2`` is ``0`` or ``+-stroke``, the x range ends and ``+-d1``."""
        xmin, xmax = self.x_range
        l, d1, S = self.l, self.d1, self.stroke
        pts = {xmin, xmax, 0.0, -d1, d1}
        rhs = S * S * (4 * l * l - 4 * d1 * d1 - S * S) / (16 * d1 * d1 + 4 * S * S)
        if rhs >= 0:
            r = math.sqrt(rhs)
            pts.update((r, -r))
        return sorted(pts)

    # --- workspace -----------------------------------------------------------------
    def workspace_area(self) -> float:
        """Exact area of the reachable set [L^2] (closed form, to rounding).

        At abscissa ``x`` the set is the interval of :meth:`y_interval`, of length
        ``max(0, stroke - |c_1(x) - c_2(x)|)`` (eq. 8-9). Its breakpoints, where
        ``c_1 - c_2`` equals ``0`` or ``+-stroke``, satisfy (squaring twice)
        ``x^2 = k^2 (4 l^2 - 4 d1^2 - k^2) / (16 d1^2 + 4 k^2)`` with ``k`` = stroke, or
        ``x = 0``; between them the integrand is a fixed combination of
        ``sqrt(l^2 - (x -+ d1)^2)``, integrated with its primitive. Spurious roots of the
        squaring only split a piece, so the result is exact.
        """
        xmin, xmax = self.x_range
        l, d1, S = self.l, self.d1, self.stroke
        pts = [p for p in self._candidates() if xmin <= p <= xmax]
        s1, s2 = self._s
        area = 0.0
        for a, b in zip(pts[:-1], pts[1:]):
            if b <= a:
                continue
            m = 0.5 * (a + b)
            c1, c2 = self._offsets(np.float64(m))
            diff = float(c1 - c2)
            if abs(diff) >= S:
                continue
            sig = 1.0 if diff >= 0 else -1.0
            # int (c1 - c2) dx with c_i = -s_i sqrt(l^2 - (x - x_Bi)^2)
            i1 = _arc_primitive(b + d1, l) - _arc_primitive(a + d1, l)
            i2 = _arc_primitive(b - d1, l) - _arc_primitive(a - d1, l)
            area += S * (b - a) - sig * (-s1 * i1 + s2 * i2)
        return float(area)

    def task_workspace_area(self) -> float:
        """Area of the task rectangle ``W_t`` [L^2] (``b h``)."""
        xmin, xmax, ymin, ymax = self._task("task_workspace_area")
        return (xmax - xmin) * (ymax - ymin)

    def _task(self, what):
        if self.task_workspace is None:
            raise ValueError(f"{what} needs a task_workspace, got None (use Gantry.from_synthesis)")
        return self.task_workspace

    # --- velocity output ratio (Wu sec. 3.3) -------------------------------------
    def velocity_output_ratio(self, x, leg: int = 1):
        """``k_v(i) = |x_dot / q_dot_i|`` at ``y_dot = 0`` (Wu eq. 6): ``|cot theta_i|``.

        Depends on ``x`` only; ``inf`` where the link is vertical, NaN outside the
        range of :attr:`x_range`.
        """
        leg = _v.choice("leg", leg, (1, 2))
        x = np.asarray(x, dtype=float)
        u = x - self.column_x[leg - 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            return _w(u, self.l) / np.abs(u)

    def k_av(self, x_min=None, x_max=None, leg: int = 1, reading: str = "literal") -> float:
        """Global velocity output ratio ``k_av`` of Wu eq. (7) over ``[x_min, x_max]``.

        The range defaults to the task rectangle's ``[-b/2, b/2]`` (eq. 17-18).

        ``reading`` selects how eq. (6)-(7) are read; ``"literal"`` is the one used
        throughout mechopt:

        ``"literal"`` (default)
            the x-mean of ``k_v(i) = |cot theta_i|`` (eq. 6 with ``y_dot = 0``, then eq. 7),
            integrated in closed form with the primitive
            ``sqrt(l^2-u^2) - l ln((l + sqrt(l^2-u^2))/|u|)`` of ``sqrt(l^2-u^2)/|u|``.
            Table 1's design gives 1.787, not the printed 1.05.
        ``"displacement"``
            the x travel over the slider travel at ``y_dot = 0``,
            ``(x_max - x_min) / int |tan theta_i| dx`` (the harmonic x-mean of ``k_v``).
            Every design of eq. (13) gives exactly 1 (``y_d1 = b``).
        ``"max_speed"``
            the x-mean of the largest ``|x_dot|`` with both sliders at unit speed and
            ``y_dot`` free, ``2 / |tan theta_1 - tan theta_2|`` (leg-independent),
            by 64-point Gauss-Legendre (smooth integrand; error below 1e-10 for
            the designs of eq. 14-16). Table 1's design gives 1.109.

        None of these (nor the others listed in ``tests/test_gantry.py``) reproduces
        Table 1's ``k_av = 1.05``; the literal reading is kept.
        """
        reading = _v.choice("reading", reading, K_AV_READINGS)
        leg = _v.choice("leg", leg, (1, 2))
        if x_min is None or x_max is None:
            txmin, txmax, _, _ = self._task("k_av without x_min/x_max")
            x_min = txmin if x_min is None else x_min
            x_max = txmax if x_max is None else x_max
        x_min = _v.finite_number("x_min", x_min)
        x_max = _v.finite_number("x_max", x_max)
        if not x_min < x_max:
            raise ValueError(f"x_max must exceed x_min = {x_min!r}, got {x_max!r}")
        lo, hi = self.x_range
        if x_min < lo or x_max > hi:
            raise ValueError(
                f"[x_min, x_max] must lie in the reachable x range [{lo!r}, {hi!r}], "
                f"got [{x_min!r}, {x_max!r}]"
            )
        l = self.l
        if reading == "max_speed":
            g, gw = np.polynomial.legendre.leggauss(64)
            xs = 0.5 * (x_max - x_min) * g + 0.5 * (x_max + x_min)
            t1 = (xs + self.d1) / _w(xs + self.d1, l)
            t2 = (xs - self.d1) / _w(xs - self.d1, l)
            f = 2.0 / np.abs(t1 - t2)
            return float(0.5 * np.dot(gw, f))
        xb = self.column_x[leg - 1]
        a, b = x_min - xb, x_max - xb  # u = x - x_Bi
        if reading == "literal":
            if a <= 0.0 <= b:
                return math.inf  # |cot| ~ 1/|u| is not integrable at a vertical link

            def F(u):  # primitive of sqrt(l^2-u^2)/u on u > 0
                w = math.sqrt(max(l * l - u * u, 0.0))
                return w - l * math.log((l + w) / u)

            ua, ub = sorted((abs(a), abs(b)))
            return (F(ub) - F(ua)) / (x_max - x_min)
        # displacement: int |u| / sqrt(l^2-u^2) du = |w(u1) - w(u2)| on each side of 0

        def wf(u):
            return math.sqrt(max(l * l - u * u, 0.0))

        if a < 0.0 < b:
            travel = (l - wf(a)) + (l - wf(b))
        else:
            travel = abs(wf(a) - wf(b))
        return (x_max - x_min) / travel if travel > 0 else math.inf


def wu2008_gantry(theta_1S_deg: float = 10.0, unit: str = "mm") -> Gantry:
    """The gantry of Wu 2008 Table 1 (``theta_1S = 10`` deg) or of sec. 4.2 (15 deg).

    ``b = 500``, ``h = 400``, ``d2 = 100``, ``l2 = 200`` mm (sec. 4.2); the task rectangle
    is placed at ``y in [300, 700]`` mm (:data:`WU2008_TASK_Y_MIN_MM`, an assumption).
    ``unit="m"`` returns the same machine in metres, as the dynamics needs.
    """
    unit = _v.choice("unit", unit, tuple(_LENGTH_UNITS))
    th = math.radians(_v.finite_number("theta_1S_deg", theta_1S_deg))
    g = Gantry.from_synthesis(500.0, 400.0, th, l2=200.0, d2=100.0,
                              task_y_min=WU2008_TASK_Y_MIN_MM)
    return g if unit == "mm" else g.scaled(1e-3)


SUMMARY_KEYS = ("workspace_area", "k_av", "d", "d1", "l", "stroke", "eta_d", "gtqi", "quadrature")


def summary(b=500.0, h=400.0, theta_1S=math.radians(10.0), d2=100.0, l2=200.0,
            length_unit: str = "mm", inertia=None, n: int = 48) -> dict:
    """Every number of ``mechopt evaluate gantry`` for one synthesized design (floats).

    Parameters
    ----------
    b, h : float
        Task rectangle [length_unit], > 0.
    theta_1S : float
        Smallest link angle [rad], in (0, pi/4).
    d2, l2 : float
        Platform half-width and height [length_unit], >= 0.
    length_unit : {"mm", "m"}
        Unit of the lengths given and returned; the dynamics run in metres.
    inertia : mechopt.dynamics.GantryInertia, optional
        Masses and inertias (default: Wu Table 2 carried over to this design's link
        length, :meth:`mechopt.dynamics.GantryInertia.wu2008_scaled`; Table 2 itself at
        ``theta_1S = 10`` deg).
    n : int
        Gauss-Legendre nodes per axis of the task-rectangle means (eta_D, GTQI).

    Returns
    -------
    dict with :data:`SUMMARY_KEYS`: ``workspace_area`` (exact area of the reachable
    set, [length_unit^2]), ``k_av`` (literal reading of eq. 7 over ``[-b/2, b/2]``),
    ``d``, ``d1``, ``l``, ``stroke`` (eq. 14-16, [length_unit]), ``eta_d`` (eq. 44,
    area mean of kappa_D over the task rectangle) and ``gtqi`` (area mean of
    :func:`mechopt.indices.tqi` over the task rectangle); ``quadrature`` names their
    rule, ``"gauss-legendre-NxN"`` (tensor Gauss-Legendre, ``n`` nodes per axis).
    """
    from .. import dynamics as _dyn  # late import: dynamics imports this module

    length_unit = _v.choice("length_unit", length_unit, tuple(_LENGTH_UNITS))
    d, d1, l, stroke = dimensional_synthesis(b, h, theta_1S)
    g = Gantry.from_synthesis(b, h, theta_1S, l2=l2, d2=d2)
    k_av = g.k_av(reading="literal")
    g_m = g.scaled(_LENGTH_UNITS[length_unit])
    if inertia is None:
        l0 = dimensional_synthesis(500.0, 400.0, math.radians(10.0))[2] * _LENGTH_UNITS["mm"]
        inertia = _dyn.GantryInertia.wu2008_scaled(g_m.l, l0)
    dyn = _dyn.GantryDynamics(g_m, inertia)
    eta = dyn.eta_d(n=n)
    xs, ys, w = _dyn.rectangle_rule(g.task_workspace, n)
    gtqi = float(np.sum(w * g.tqi(xs, ys)))
    out = dict(workspace_area=g.workspace_area(), k_av=k_av, d=d, d1=d1, l=l, stroke=stroke,
               eta_d=eta, gtqi=gtqi)
    res = {k: float(out[k]) for k in SUMMARY_KEYS[:-1]}
    res["quadrature"] = f"gauss-legendre-{n}x{n}"
    return res
