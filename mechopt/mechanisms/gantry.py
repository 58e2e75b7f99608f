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
from dataclasses import replace

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.protocol import Parameter, as_points
from mechopt.core.bodies import Body, Shapes
from mechopt.mechanisms.sliders import ASSEMBLY_MODES, K_AV_READINGS, GuideDesignSpec, TwoSliderMechanism

__all__ = [
    "Gantry",
    "GantryDesignSpec",
    "MODES",
    "ASSEMBLY_MODES",
    "K_AV_READINGS",
    "dimensional_synthesis",
    "k_av_literal_of_design",
    "wu2008_gantry",
    "check_synthesis",
    "SUMMARY_KEYS",
]

MODES = ("--", "++", "-+", "+-")
_LENGTH_UNITS = {"mm": 1e-3, "m": 1.0}

#: abscissa of the task rectangle's lower edge of the Wu machine, placed so that
#: the path of Table 3 (y = 0.5 m) runs at mid-height of the 400 mm task height.
#: The paper gives no absolute height; no kinematic or dynamic index depends on it.
WU2008_TASK_Y_MIN_MM = 300.0


def _arc_primitive(u, l):
    """``int_0^u sqrt(l^2 - t^2) dt`` for ``|u| <= l`` (clipped)."""
    u = np.clip(u, -l, l)
    return 0.5 * (u * np.sqrt(max(l * l - u * u, 0.0)) + l * l * math.asin(u / l))


def _wu2008_design() -> dict:
    """Wu's Table 1 machine as printed (``mechopt/data/wu2008.csv``): the task ``b``,
    ``h`` [mm], ``theta_1S`` [deg] and the platform ``d2``, ``l2`` [mm]."""
    from mechopt.data import published_values

    pub = published_values("wu2008")
    return {k: pub[("table1", k)][0] for k in ("b", "h", "theta_1S", "d2", "l2")}


def _wu2008_link_length_m() -> float:
    """Link length [m] of Wu's Table 1 design (eq. 15), the machine Table 2's inertias
    belong to (:meth:`mechopt.mechanisms.gantry_dynamics.GantryInertia.wu2008_scaled`)."""
    t1 = _wu2008_design()
    return dimensional_synthesis(t1["b"], t1["h"], math.radians(t1["theta_1S"]))[2] * _LENGTH_UNITS["mm"]


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

    Raises
    ------
    ValueError
        One line, for a non-positive ``b`` or ``h``, or ``theta_1S`` outside
        (0, pi/4).
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


def _per_unit_width(theta_1S):
    """``(k1, k2, k3)``: ``d1``, ``l`` and ``y_d1`` of :func:`dimensional_synthesis` for
    ``b = 1`` (the synthesis is linear in ``b``, and the stroke is ``y_d1 + h``)."""
    _, d1, l, stroke = dimensional_synthesis(1.0, 1.0, theta_1S)
    return d1, l, stroke - 1.0


def check_synthesis(b, h, theta_1S, scales=(1.0,), unit: str = "") -> None:
    """ValueError (one line, in terms of ``b``, ``h``, ``theta_1S``) when the gantry of
    :func:`dimensional_synthesis` has a length outside the admissible
    ``[LENGTH_MIN, LENGTH_MAX]`` of :mod:`mechopt.core.validation`, in its own unit or
    multiplied by one of ``scales`` (e.g. ``1e-3``: the dynamics run in metres).

    For a fixed ``theta_1S`` the machine is linear in the task (``d1 = k1 b``,
    ``l = k2 b``, stroke ``k3 b + h``), so the message names the range of ``b`` that
    works for this ``theta_1S``, the largest ``b + h``, and the range of ``theta_1S``
    that works for this ``b`` (``k1``, ``k2`` grow with ``theta_1S``).

    Parameters
    ----------
    b, h : float
        The task rectangle [L].
    theta_1S : float
        Smallest link angle [rad].
    scales : tuple of float
        Factors the lengths must also be admissible under.
    unit : str
        The length unit, for the message.

    Raises
    ------
    ValueError
        One line, when a length is not admissible.
    """
    _, d1, l, stroke = dimensional_synthesis(b, h, theta_1S)
    lo = _v.LENGTH_MIN / min(min(scales), 1.0)
    hi = _v.LENGTH_MAX / max(max(scales), 1.0)
    lengths = (("the half column distance d1", d1), ("the link length l", l), ("the stroke", stroke))
    bad = [(name, v) for name, v in lengths if not lo <= v <= hi]
    if not bad:
        return
    k1, k2, k3 = _per_unit_width(theta_1S)
    u = f" {unit}" if unit else ""
    name, v = bad[0]
    limit, default = (lo, _v.LENGTH_MIN) if v < lo else (hi, _v.LENGTH_MAX)
    where = "below the smallest" if v < lo else "above the largest"
    note = "" if limit == default else " (the dynamics run in metres)"
    shown = f"{v:.3g}" if f"{v:.3g}" != f"{limit:.3g}" else repr(v)
    deg = f"{math.degrees(theta_1S):.10g}"
    b_lo, b_hi = max(lo / k1, (lo - h) / k3, _v.LENGTH_MIN), hi / k2
    msg = (f"Wu's synthesis (eq. 14-16) of the task b = {b:g}, h = {h:g}{u} with theta_1S = "
           f"{deg} deg gives {name} = {shown}{u}, {where} admissible length {limit:g}{u}{note}: "
           f"for theta_1S = {deg} deg, b must lie in [{b_lo:.3g}, {b_hi:.3g}]{u} and b + h be "
           f"at most {hi:g}{u}")

    def first(holds):  # the smallest theta_1S in (0, pi/4) from which holds(theta_1S) does
        t0, t1 = 0.0, math.pi / 4
        for _ in range(48):  # to 1e-14 rad, every midpoint inside the open interval
            m = 0.5 * (t0 + t1)
            t0, t1 = (t0, m) if holds(m) else (m, t1)
        return t1

    t_min = first(lambda t: b * _per_unit_width(t)[0] >= lo)  # d1 large enough from here
    t_max = first(lambda t: b * _per_unit_width(t)[1] > hi)  # l too large from here
    if t_min < t_max:
        t_lo = "(0" if t_min < _v.ROUNDING else f"[{math.degrees(t_min):.4g}"
        t_hi = "45)" if t_max > math.pi / 4 - _v.ROUNDING else f"{math.degrees(t_max):.4g}]"
        msg += f"; for b = {b:g}{u}, theta_1S must lie in {t_lo}, {t_hi} deg"
    raise ValueError(msg)


def k_av_literal_of_design(theta_1S):
    """Literal ``k_av`` (eq. 6-7) of a design of :func:`dimensional_synthesis`, vectorised.

    Over ``x in [-b/2, b/2]`` (eq. 17-18) ``sin(theta_1)`` runs from ``sin(theta_1S)`` to
    ``cos(theta_1S)`` and ``b = l (cos theta_1S - sin theta_1S)``, so the x-mean of
    ``|cot theta_1|`` depends on ``theta_1S`` only:

        k_av = [F(cos t) - F(sin t)] / (cos t - sin t),
        F(s) = sqrt(1 - s^2) - ln((1 + sqrt(1 - s^2)) / s).

    ``theta_1S`` in rad, in (0, pi/4). Decreases from +inf to 1 over that interval
    (Wu sec. 4.3: "k_av descends when theta_1 varies from 0 to 90 deg").

    Parameters
    ----------
    theta_1S : array_like
        Smallest link angle [rad], in (0, pi/4).

    Returns
    -------
    ndarray or float
        ``k_av`` (dimensionless).

    Raises
    ------
    ValueError
        For an angle outside (0, pi/4).
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


class GantryDesignSpec(GuideDesignSpec):
    """``mechopt design gantry``: the lengths ``d1`` (half the column distance) and ``l``
    (the three links) [L], ``l > d1``, the modes :data:`MODES` (default ``"--"``), a
    platform of no height (``l2 = 0``); the stroke is the range of ``q1``, ``q2`` over
    the task (both sliders share it, Wu eq. 16)."""

    name = "gantry"
    lengths = ("d1", "l")
    guide, link = "d1", "l"
    modes, default_mode = MODES, "--"

    def positions(self, v, mode, x, y):
        s1, s2 = (1.0 if c == "+" else -1.0 for c in mode)
        l, d1 = v["l"], v["d1"]
        with np.errstate(invalid="ignore"):
            w1 = np.sqrt(l * l - (x + d1) ** 2)
            w2 = np.sqrt(l * l - (x - d1) ** 2)
        # q_i = y - l2/2 - c_i, c_i = -s_i w_i (Gantry._offsets, l2 = 0)
        return y + s1 * w1, y + s2 * w2

    def build(self, v, mode, strokes=None, pad=0.0):
        (a1, b1), (a2, b2) = strokes
        lo, hi = min(a1, a2) - pad, max(b1, b2) + pad
        return Gantry(v["d1"], v["l"], hi - lo, q_min=lo, mode=mode)

    def size(self, mech, derived):
        """``2 d1 + 3 l``: the column distance and the three equal links (Wu Fig. 1).

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
        return 2.0 * mech.d1 + 3.0 * mech.l

    def links(self, mech, x, y, shapes=None):
        """The two-slider bodies (:meth:`GuideDesignSpec.links`); with a platform of height
        ``l2 > 0`` also the parallelogram of leg 1 (Wu Fig. 1): the third link ``"link3"``
        from ``S3 = S1 + (0, l2)`` to ``A3 = A + (0, l2)``, the platform ``A A3``
        (``"platform"``), carriage 1 spanning ``S1 S3`` and its guide ``l2`` longer. With
        ``l2 = 0`` (the designed gantries) the third link lies on the first: not drawn.

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
        bodies = super().links(mech, x, y, shapes)
        if mech.l2 == 0:
            return bodies
        shapes = shapes or Shapes.default()
        h = mech.l2
        by = {b.name: b for b in bodies}
        g1, c1, l1 = by["guide1"], by["carriage1"], by["link1"]
        bodies[bodies.index(g1)] = replace(g1, y1=g1.y1 + h)
        bodies[bodies.index(c1)] = replace(c1, joints=("S1", "S3"), ends=("S1", "S3"), y1=c1.y1 + h)
        bodies += [Body.make("link3", "distal", ("S3", "A3"), ("S3", "A3"), (l1.x0, l1.y0 + h),
                             (l1.x1, l1.y1 + h), shapes),
                   Body.make("platform", "platform", ("A", "A3"), ("A", "A3"), (l1.x1, l1.y1),
                             (l1.x1, l1.y1 + h), shapes)]
        return bodies

    def joint_speeds(self, mech, x, y, radius=0.0):
        """Those of :meth:`GuideDesignSpec.joint_speeds`; ``S3`` moves with ``S1`` and
        ``A3`` with the platform.

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
        out = super().joint_speeds(mech, x, y, radius)
        out.update(S3=out["S1"], A3=out["A"])
        return out


class Gantry(TwoSliderMechanism):
    """Wu 2008 gantry ``Gantry(d1, l, stroke, q_min=0, l2=0, d2=0, mode="--")``.

    Lengths may be in any consistent unit [L]; angles are in rad. The actuator
    coordinates are lengths, so the Jacobian is dimensionless and invariant under a
    change of length unit (see :meth:`scaled`). The kinematics, the exact area and
    ``k_av`` are those of the two-slider topology (:mod:`mechopt.mechanisms.sliders`)
    with the columns as guides (leg 1 on the left) and the platform offset ``l2/2``.

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

    Raises
    ------
    ValueError
        One line, for invalid lengths, strokes or mode (``l <= d1`` included).
    """

    cli_name = "gantry"
    design_spec = GantryDesignSpec
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
    #: the keys of :meth:`summary`, in order
    summary_keys = ("workspace_area", "k_av", "d", "d1", "l", "stroke", "eta_d", "gtqi", "quadrature")
    #: not homogeneous in the lengths (Wu's synthesis and the inertia law of eta_D
    #: depend on the unit): evaluated as given
    summary_powers = None
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
        stroke_limits = (self.q_min, self.q_max)
        self._set_sliders(self.d1, self.l, False, mode, (stroke_limits, stroke_limits),
                          (self.stroke, self.stroke), self.l2 / 2.0)

    # --- constructors ---------------------------------------------------------
    @classmethod
    def from_synthesis(cls, b, h, theta_1S, l2=0.0, d2=0.0, task_y_min=0.0):
        """The design of :func:`dimensional_synthesis`, with its task rectangle in place.

        The task rectangle is ``[-b/2, b/2] x [task_y_min, task_y_min + h]`` (eq. 17-18).
        The lower stroke limit follows from Wu Fig. 2: at ``Q2 = (-b/2, task_y_min)``
        slider 1 is at ``q_1S`` with ``theta_1 = theta_1S``, so
        ``q_min = task_y_min - l2/2 - l cos(theta_1S)``; the corners ``Q1``-``Q4`` then lie
        on the boundary of the reachable set. A task whose machine has a length outside
        the admissible range is refused in terms of ``b``, ``h``, ``theta_1S``
        (:func:`check_synthesis`).

        Parameters
        ----------
        b, h : float
            Task width and height [L].
        theta_1S : float
            Smallest link angle [rad], in (0, pi/4).
        l2 : float
            Platform height [L].
        d2 : float
            Platform half-width [L].
        task_y_min : float
            Lower edge of the task rectangle [L].

        Returns
        -------
        Gantry
            The design.

        Raises
        ------
        ValueError
            One line, in terms of ``b``, ``h``, ``theta_1S``.
        """
        check_synthesis(b, h, theta_1S)
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
        [deg], task rectangle at its place (:meth:`from_synthesis`), lengths in
        ``length_unit``; its lengths in metres (the dynamics' unit) must be admissible too.

        Parameters
        ----------
        b, h : float
            Task width and height [length_unit].
        theta_1s_deg : float
            Smallest link angle [deg], in (0, 45).
        d2 : float
            Platform half-width [length_unit].
        l2 : float
            Platform height [length_unit].
        length_unit : str
            ``"mm"`` or ``"m"``.

        Returns
        -------
        Gantry
            The design.

        Raises
        ------
        ValueError
            One line, for invalid inputs or a machine whose lengths are not admissible.
        """
        unit = _v.choice("length_unit", length_unit, tuple(_LENGTH_UNITS))
        deg = _v.finite_number("theta_1s_deg", theta_1s_deg)
        if not 0.0 < deg < 45.0:
            raise ValueError(f"theta_1s_deg must lie in (0, 45) deg (eq. 14), got {_v.show(theta_1s_deg)}")
        check_synthesis(b, h, math.radians(deg), scales=(1.0, _LENGTH_UNITS[unit]), unit=unit)
        g = cls.from_synthesis(b, h, math.radians(deg), l2=l2, d2=d2)
        g.synthesis_inputs = dict(b=float(b), h=float(h), theta_1s_deg=deg, d2=float(d2),
                                  l2=float(l2), length_unit=unit)
        return g

    def parameter_values(self) -> dict:
        """The synthesis inputs of :meth:`from_parameters` (None if made otherwise).

        Returns
        -------
        dict
            ``{name: value}``.
        """
        if self.synthesis_inputs is None:
            return {k: getattr(self, k) for k in ("d1", "l", "stroke", "q_min", "l2", "d2", "mode")}
        return dict(self.synthesis_inputs)

    def __repr__(self):
        return (f"Gantry(d1={self.d1!r}, l={self.l!r}, stroke={self.stroke!r}, "
                f"q_min={self.q_min!r}, l2={self.l2!r}, d2={self.d2!r}, mode={self.mode!r})")

    def with_mode(self, mode: str) -> "Gantry":
        """The same dimensions in another working mode.

        Parameters
        ----------
        mode : str
            One of :attr:`modes`.

        Returns
        -------
        PlanarMechanism
            A new instance.
        """
        return Gantry(self.d1, self.l, self.stroke, self.q_min, self.l2, self.d2, mode,
                      self.task_workspace)

    def scaled(self, factor) -> "Gantry":
        """Every length (and the task rectangle) multiplied by ``factor``, e.g. 1e-3 for mm -> m.

        With prismatic actuators the Jacobian does not change (a five-bar's scales as 1/D).

        Parameters
        ----------
        factor : float
            The scale factor, > 0.

        Returns
        -------
        PlanarMechanism
            A new instance.
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
        """``(x_B1, x_B2) = (-d1, d1)``: the guides of the two-slider topology."""
        return self.guides

    # --- bodies (the mass model and the dynamics) ------------------------------
    def bodies(self):
        """The declared bodies of Wu's machine (sec. 5, Table 2; the table of
        :mod:`mechopt.mechanisms.gantry_dynamics`): carriages on ``B_1``, ``B_2``; links
        ``A1B1``, ``A2B2`` and the parallelogram's ``A3B3`` (``B_3 = B_1 + (0, l2)``,
        ``A_3 = A_1 + (0, l2)``); counterweights hanging at ``-q_i``; the platform.

        Returns
        -------
        list of mechopt.core.rigid_bodies.BodySpec
            The bodies.
        """
        from mechopt.core.rigid_bodies import BodySpec

        return (BodySpec("carriage1", "carriage", 0.0, ("B1",), leg=1),
                BodySpec("carriage2", "carriage", 0.0, ("B2",), leg=2),
                BodySpec("A1B1", "link", self.l, ("B1", "A1"), leg=1),
                BodySpec("A2B2", "link", self.l, ("B2", "A2"), leg=2),
                BodySpec("A3B3", "link", self.l, ("B3", "A3"), leg=1),
                BodySpec("counterweight1", "counterweight", 0.0, ("B1",), leg=1),
                BodySpec("counterweight2", "counterweight", 0.0, ("B2",), leg=2),
                BodySpec("platform", "payload", 0.0, ("A1", "A2", "A3")))

    def body_frames(self, x, y, xd, yd, xdd, ydd):
        """``(q, qd, qdd, frames)`` of :meth:`bodies` along a motion of ``O' = (x, y)``
        (:meth:`~mechopt.mechanisms.sliders.TwoSliderMechanism.slider_motion`).

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
            Actuator positions [L], rates and accelerations (per second, per second
            squared).
        frames : dict
            Per body its frame along the motion (:mod:`mechopt.core.rigid_bodies`).
        """
        from mechopt.core import rigid_bodies as _b

        q, qd, qdd, S, A = self.slider_motion(x, y, xd, yd, xdd, ydd)
        up = np.array([0.0, self.l2])
        flip = np.array([1.0, -1.0])
        frames = {}
        for i, Si in enumerate(S, 1):
            frames[f"carriage{i}"] = _b.translating_frame(*Si)
            frames[f"A{i}B{i}"] = _b.segment_frame(Si, A)
            frames[f"counterweight{i}"] = _b.translating_frame(*(v * flip for v in Si))
        frames["A3B3"] = _b.segment_frame((S[0][0] + up, S[0][1], S[0][2]), (A[0] + up, A[1], A[2]))
        frames["platform"] = _b.translating_frame(A[0] + np.array([0.0, self.l2 / 2.0]), A[1], A[2])
        return q, qd, qdd, frames

    def default_masses(self, length_unit: float = 1.0) -> dict:
        """Wu's Table 2 (:meth:`~mechopt.mechanisms.gantry_dynamics.GantryInertia.wu2008_scaled`:
        exactly Table 2 for the Table 1 machine, carried over to this link length
        otherwise) as ``{body: (mass [kg], com along the link from B [m], central inertia
        [kg m^2])}``, the lengths in metres with ``length_unit`` [m/L]; and the gravity
        [m/s^2] of the table under the key ``"g"``.

        Parameters
        ----------
        length_unit : float
            Metres per length unit of this gantry [m/L].

        Returns
        -------
        dict
            ``{body: (mass, com, inertia)}`` and ``"g"``.
        """
        from mechopt.mechanisms.gantry_dynamics import GantryInertia

        l = self.l * length_unit
        p = GantryInertia.wu2008_scaled(l, _wu2008_link_length_m())
        s = l / 2.0  # Table 2 prints no offset: mid-link (the module's stated assumption)
        link = lambda m, I: (m, s, I - m * s * s)  # noqa: E731  (I about B -> about the centre)
        return {"carriage1": (p.m11, 0.0, 0.0), "carriage2": (p.m21, 0.0, 0.0),
                "A1B1": link(p.m12, p.I12), "A2B2": link(p.m22, p.I22),
                "A3B3": link(p.m4, p.I12 if p.I4 is None else p.I4),
                "counterweight1": (p.m13, 0.0, 0.0), "counterweight2": (p.m23, 0.0, 0.0),
                "platform": (p.mN, 0.0, 0.0), "g": p.g}

    def _segment_integral(self, u0, u1) -> float:
        """The circular-segment area of the workspace's column integrals with the C
        library's ``asin`` (``math``): the gantry's areas keep the digits they had
        before the two-slider base (NumPy's ``arcsin``, which the Biglide's use, differs
        from it in the last bit for about 7 % of the designs)."""
        return _arc_primitive(u1, self.l) - _arc_primitive(u0, self.l)

    def serial_clearance(self, x, y):
        """Signed distance to the boundary of the reachable set, positive inside.

        Exact inside: the minimum over both legs of the distance to the two
        stroke-limit arcs and the two vertical sides ``|x - x_Bi| = l`` of the leg's
        region (Wu Fig. 2). Outside the value is negative; its magnitude is the
        distance to the nearest violated piece, a lower bound of the distance to the
        set. Only the vertical sides are type-I loci; the arcs are joint limits.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            The signed distance [L], positive inside.
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

    # --- task workspace -------------------------------------------------------------
    def task_workspace_area(self) -> float:
        """Area of the task rectangle ``W_t`` [L^2] (``b h``).

        Returns
        -------
        float
            The area [L^2].
        """
        xmin, xmax, ymin, ymax = self._task("task_workspace_area")
        return (xmax - xmin) * (ymax - ymin)

    def _task(self, what):
        if self.task_workspace is None:
            raise ValueError(f"{what} needs a task_workspace, got None (use Gantry.from_synthesis)")
        return self.task_workspace

    def _k_av_default_range(self):
        """The task rectangle's ``[-b/2, b/2]`` (Wu eq. 17-18)."""
        txmin, txmax, _, _ = self._task("k_av without x_min/x_max")
        return txmin, txmax

    # --- dynamics (Wu sec. 5-6) ---------------------------------------------------------
    def dynamics(self, inertia=None, length_unit: str | None = None):
        """The rigid-body model (:class:`mechopt.mechanisms.gantry_dynamics.GantryDynamics`) of this gantry
        in metres.

        ``length_unit`` is the unit of this gantry's lengths, ``"mm"`` or ``"m"``
        (default: that of :meth:`from_parameters`' inputs; required otherwise).
        ``inertia`` defaults to Wu's Table 2 carried over to this design's link length
        (:meth:`mechopt.mechanisms.gantry_dynamics.GantryInertia.wu2008_scaled`; Table 2 itself for
        the Table 1 design, ``theta_1S = 10`` deg).

        Parameters
        ----------
        inertia : mechopt.mechanisms.gantry_dynamics.GantryInertia, optional
            Masses and inertias (default: Wu's Table 2 carried over).
        length_unit : str, optional
            The unit of this gantry's lengths, ``"mm"`` or ``"m"`` (default: that of
            :meth:`from_parameters`' inputs).

        Returns
        -------
        mechopt.mechanisms.gantry_dynamics.GantryDynamics
            The model in metres.

        Raises
        ------
        ValueError
            When the length unit is unknown and not given.
        """
        from mechopt.mechanisms import gantry_dynamics as _dyn  # late import: the dynamics is not needed otherwise

        if length_unit is None:
            if self.synthesis_inputs is None:
                raise ValueError("length_unit must be given ('mm' or 'm') for a gantry not made "
                                 "by Gantry.from_parameters, got None")
            length_unit = self.synthesis_inputs["length_unit"]
        unit = _v.choice("length_unit", length_unit, tuple(_LENGTH_UNITS))
        g_m = self.scaled(_LENGTH_UNITS[unit])
        if inertia is None:
            inertia = _dyn.GantryInertia.wu2008_scaled(g_m.l, _wu2008_link_length_m())
        return _dyn.GantryDynamics(g_m, inertia)

    def eta_d(self, n: int = 48, inertia=None, length_unit: str | None = None) -> float:
        """``eta_D`` of Wu eq. (44): the area mean of ``kappa_D`` over the task rectangle,
        by an ``n x n`` Gauss-Legendre rule, of :meth:`dynamics` (same arguments).

        Parameters
        ----------
        n : int
            Gauss-Legendre nodes per side.
        inertia : mechopt.mechanisms.gantry_dynamics.GantryInertia, optional
            Masses and inertias (default: Wu's Table 2 carried over).
        length_unit : str, optional
            The unit of this gantry's lengths, ``"mm"`` or ``"m"`` (default: that of
            :meth:`from_parameters`' inputs).

        Returns
        -------
        float
            ``eta_D`` (dimensionless).
        """
        return self.dynamics(inertia, length_unit).eta_d(n=n)

    def summary(self, inertia=None, n: int = 48, length_unit: str | None = None) -> dict:
        """Every number of ``mechopt evaluate gantry`` (:attr:`summary_keys`, floats), for
        a gantry however it was made.

        ``workspace_area`` (exact area of the reachable set, [length_unit^2]), ``k_av``
        (literal reading of eq. 7 over the task rectangle's ``[x_min, x_max]``), ``d``
        (the distance from a column to the nearer side of the task rectangle, Wu Fig. 2),
        ``d1``, ``l``, ``stroke`` ([length_unit]; for a gantry of :meth:`from_parameters`
        the values of eq. 14-16), ``eta_d`` (eq. 44, area mean of kappa_D over the task
        rectangle, :meth:`eta_d` with ``inertia``, default Wu's Table 2 carried over to
        this link length) and ``gtqi`` (area mean of :func:`mechopt.core.indices.tqi` over
        the task rectangle, not over the workspace as :meth:`gtqi`); ``quadrature`` names
        their rule, ``"gauss-legendre-NxN"`` (tensor Gauss-Legendre, ``n`` nodes per axis).

        A gantry made by its own constructor: without a ``task_workspace``, ``k_av``,
        ``d``, ``eta_d`` and ``gtqi`` (which are defined over the task rectangle) are NaN;
        ``eta_d`` also needs ``length_unit`` (``"mm"`` or ``"m"``: the dynamics is in
        metres), NaN without it.

        Parameters
        ----------
        inertia : GantryInertia, optional
            The masses of :meth:`dynamics`.
        n : int
            Gauss-Legendre nodes per axis of the task rectangle.
        length_unit : str, optional
            The unit of this gantry's lengths (default: that of :meth:`from_parameters`).

        Returns
        -------
        dict
            ``{key: float}`` for :attr:`summary_keys` but ``quadrature`` (a str).
        """
        from mechopt.mechanisms.gantry_dynamics import rectangle_rule

        nan = float("nan")
        if self.synthesis_inputs is not None:
            kw = self.synthesis_inputs
            d, d1, l, stroke = dimensional_synthesis(kw["b"], kw["h"], math.radians(kw["theta_1s_deg"]))
        else:
            d1, l, stroke = self.d1, self.l, self.stroke
            d = nan if self.task_workspace is None else min(self.d1 - self.task_workspace[1],
                                                           self.task_workspace[0] + self.d1)
        out = dict(workspace_area=self.workspace_area(), d=d, d1=d1, l=l, stroke=stroke,
                   k_av=nan, eta_d=nan, gtqi=nan)
        if self.task_workspace is not None:
            xs, ys, w = rectangle_rule(self.task_workspace, n)
            out.update(k_av=self.k_av(reading="literal"), gtqi=float(np.sum(w * self.tqi(xs, ys))))
            if self.synthesis_inputs is not None or length_unit is not None:
                out["eta_d"] = self.eta_d(n, inertia, length_unit)
        res = {k: float(out[k]) for k in self.summary_keys[:-1]}
        res["quadrature"] = f"gauss-legendre-{n}x{n}"
        return res


def wu2008_gantry(theta_1S_deg: float = 10.0, unit: str = "mm") -> Gantry:
    """The gantry of Wu 2008 Table 1 (``theta_1S = 10`` deg) or of sec. 4.2 (15 deg).

    The task and platform of Table 1 (``b = 500``, ``h = 400``, ``d2 = 100``, ``l2 = 200``
    mm, read from ``mechopt/data/wu2008.csv``); the task rectangle is placed at
    ``y in [300, 700]`` mm (:data:`WU2008_TASK_Y_MIN_MM`, an assumption).
    ``unit="m"`` returns the same machine in metres, as the dynamics needs.

    Parameters
    ----------
    theta_1S_deg : float
        10 (Table 1) or 15 (sec. 4.2) [deg].
    unit : str
        ``"mm"`` or ``"m"``.

    Returns
    -------
    Gantry
        The machine, with its task workspace.
    """
    unit = _v.choice("unit", unit, tuple(_LENGTH_UNITS))
    th = math.radians(_v.finite_number("theta_1S_deg", theta_1S_deg))
    t1 = _wu2008_design()
    g = Gantry.from_synthesis(t1["b"], t1["h"], th, l2=t1["l2"], d2=t1["d2"],
                              task_y_min=WU2008_TASK_Y_MIN_MM)
    return g if unit == "mm" else g.scaled(1e-3)


#: the keys of :meth:`Gantry.summary`
SUMMARY_KEYS = Gantry.summary_keys
