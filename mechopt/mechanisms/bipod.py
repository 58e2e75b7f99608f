"""The Bipod: planar RPRPR parallel mechanism with two variable-length struts.

Geometry (Stan, Maties, Balan 2008, Fig. 7 and sec. 3.1): base joints ``A1 = (0, 0)``
and ``A2 = (b, 0)``; two struts with actuated prismatic joints join them to the tool
centre point ``P = (x, y)``. The actuated coordinates are the strut lengths

    q1 = sqrt(x^2 + y^2),   q2 = sqrt((b - x)^2 + y^2)          (Stan eq. 6)

limited to strokes ``q_i_min <= q_i <= q_i_max``. Forward kinematics (Stan eq. 7):

    x = (q1^2 + b^2 - q2^2) / (2 b),   y = +/- sqrt(q1^2 - x^2),

here with ``y`` from Heron's formula, ``|y| = sqrt((q1+q2+b)(q2-q1+b)(q1-q2+b)(q1+q2-b)) / (2b)``,
which keeps full precision near ``y = 0``.

Workspace. The set of points the struts reach is the intersection of the two
annuli ``q_i_min <= |P - A_i| <= q_i_max`` (Stan Fig. 11, sec. 4.1 cases I-VII).
It is symmetric about the x axis; Stan's Fig. 16 and his number ``W = 4693,33 mm^2``
(sec. 5.1) take the half ``y > 0``. ``branch`` selects ``"up"`` (``y >= 0``, the
default and Stan's), ``"down"`` (``y <= 0``) or ``"full"`` (either sign).

Singularities. Differentiating ``q_i^2 = |P - A_i|^2`` gives the closure

    (P - A_i) . p_dot = q_i q_dot_i,    A = [P - A1; P - A2],   B = diag(q1, q2),

so ``J = B^-1 A`` has the unit strut directions ``e_i = (P - A_i)/q_i`` as rows.
Type I (``B_ii = 0``) needs a strut of zero length, excluded by ``q_i_min > 0``:
there is no type-I singularity in the workspace. Type II (``det A = b y = 0``)
is the x axis, where the struts are collinear. The boundary of the workspace is
therefore made of *stroke limits* (arcs where some ``q_i`` equals ``q_i_min`` or
``q_i_max``; ``J`` is regular there) and, for a half-plane branch whose region
touches it, of the type-II x axis.

TQI. With unit rows, ``J J^T = [[1, c], [c, 1]]`` with ``c = cos(gamma)``, ``gamma``
the angle between the struts at ``P``, so ``kappa = sqrt((1+|c|)/(1-|c|))`` and the
TQI of Stan eq. (9) (``2 kappa / (kappa^2 + 1)``, Frobenius norms) is ``|sin gamma| = |det J|``.
Because the area element is ``dA = dq1 dq2 / |det J|``, the integral of TQI over
the workspace is the area of the admissible actuator region::

    Q = [q1_min, q1_max] x [q2_min, q2_max] ^ {|q1 - q2| <= b <= q1 + q2}

(each ``q`` in ``Q`` is one pose per half plane). Hence the exact area mean
``GTQI = |Q| / W_half`` (:func:`gtqi`), with no quadrature at all.

Velocity output ratio. Wu et al. 2008's ``k_v = |x_dot / q_dot_i|`` at ``y_dot = 0``
(their eq. 6-7) rests on the Biglide property that a vertical motion is the common
motion of both sliders (``q1_dot = q2_dot = y_dot``); the Bipod has no such
decomposition, so ``k_v``/``k_av`` are not defined here (see
:mod:`mechopt.mechanisms.biglide`).

Units: lengths in any consistent unit [L] (Stan uses mm), areas in [L^2].

References
----------
Stan, Maties, Balan (2008), "Optimal Design of Parallel Kinematics Machines with 2
Degrees of Freedom", in Wu (ed.), Parallel Manipulators, Towards New Applications,
I-Tech, ISBN 978-3-902613-40-0: eq. (6)-(9), Figs. 7, 11, 16-24, 29, sec. 5.1.
"""
from __future__ import annotations

import numpy as np

from mechopt.core import geometry as _g
from mechopt.core import validation as _v
from mechopt.core.bodies import GROUND, Body, Shapes
from mechopt.core.design_spec import DesignSpec
from mechopt.core.kinematic_tree import BASE, CLOSURE_NAMES, ClosureFrame, KinematicTree, TreeJoint
from mechopt.core.error_spec import ErrorSpec
from mechopt.core.protocol import ASSEMBLY_MODES, Parameter, PlanarMechanism, as_points

__all__ = [
    "Bipod",
    "BipodDesignSpec",
    "BipodErrorSpec",
    "BRANCHES",
    "ASSEMBLY_MODES",
    "GTQI_METHODS",
    "bipod_workspace_area",
    "bipod_tqi_integral",
    "SUMMARY_KEYS",
]

#: workspace branches: half plane y >= 0, y <= 0, or both
BRANCHES = ("up", "down", "full")
#: forward-kinematics assembly modes: y >= 0 ("up") or y <= 0 ("down")
#: how :meth:`Bipod.gtqi` integrates: closed form, or mid-point raster
GTQI_METHODS = ("exact", "raster")

#: stroke limits are tested with this tolerance relative to ``length_scale``, so
#: that a pose computed from ``q = q_min`` or ``q_max`` (fk) is reachable
LIMIT_RTOL = _v.ROUNDING


def _stroke(name_min, q_min, name_max, q_max):
    return _v.stroke(name_min, q_min, name_max, q_max, positive=True)


def _half_factor(branch):
    return 1.0 if branch == "full" else 0.5


def bipod_workspace_area(b, q1_min, q1_max, q2_min, q2_max, branch="up"):
    """Exact workspace area [L^2] of a Bipod; vectorised over designs.

    The intersection of the annuli ``q_i_min <= |P - A_i| <= q_i_max`` around
    ``A1 = (0, 0)``, ``A2 = (b, 0)`` (inclusion-exclusion of four lens areas,
    :func:`mechopt.core.geometry.annuli_intersection_area`); half of it for the
    branches ``"up"``/``"down"``. No validation beyond the geometric one: use
    :class:`Bipod` for checked single designs.

    Parameters
    ----------
    b : array_like
        Base distance [L], > 0.
    q1_min, q1_max : array_like
        Stroke of strut 1 [L].
    q2_min, q2_max : array_like
        Stroke of strut 2 [L].
    branch : str
        ``"up"``, ``"down"`` or ``"full"``.

    Returns
    -------
    ndarray or float
        The area [L^2].
    """
    _v.choice("branch", branch, BRANCHES)
    b = np.asarray(b, dtype=float)
    zero = np.zeros_like(b)
    c1 = np.stack([zero, zero], -1)
    c2 = np.stack([b, zero], -1)
    full = _g.annuli_intersection_area(c1, q1_min, q1_max, c2, q2_min, q2_max)
    return _half_factor(branch) * full


def bipod_tqi_integral(b, q1_min, q1_max, q2_min, q2_max, branch="up"):
    """Exact ``int_W TQI dA`` [L^2] of a Bipod; vectorised over designs.

    Equals the area of the admissible actuator region ``Q`` (module docstring)
    per half plane: the box area minus the three corners cut off by the triangle
    inequalities ``q1 - q2 <= b``, ``q2 - q1 <= b``, ``q1 + q2 >= b`` (disjoint
    for positive strut lengths; ramp formulas of :mod:`mechopt.core.geometry`).

    Parameters
    ----------
    b : array_like
        Base distance [L], > 0.
    q1_min, q1_max : array_like
        Stroke of strut 1 [L].
    q2_min, q2_max : array_like
        Stroke of strut 2 [L].
    branch : str
        ``"up"``, ``"down"`` or ``"full"``.

    Returns
    -------
    ndarray or float
        The integral [L^2] (TQI is dimensionless; Stan 2008 eq. 9).
    """
    _v.choice("branch", branch, BRANCHES)
    a1, b1, a2, b2, c = (np.asarray(v, dtype=float) for v in (q1_min, q1_max, q2_min, q2_max, b))
    box = (b1 - a1) * (b2 - a2)
    cut = (
        _g.box_area_diff_above(a1, b1, a2, b2, c)  # q1 - q2 > b
        + _g.box_area_diff_above(a2, b2, a1, b1, c)  # q2 - q1 > b
        + _g.box_area_sum_below(a1, b1, a2, b2, c)  # q1 + q2 < b
    )
    q_area = np.maximum(box - cut, 0.0)
    return 2.0 * _half_factor(branch) * q_area


class BipodDesignSpec(DesignSpec):
    """``mechopt design bipod``: the base distance ``b`` [L], the branch ``"up"`` (default)
    or ``"down"``; the strut strokes are the ranges of ``q1``, ``q2`` over the task and
    the struts at full extension are bounded by ``max_length``. The task frame has the
    base midpoint at the origin, the bipod's own frame ``A1`` (:meth:`to_mech`); the
    holes of the reachable set are the disks ``|P - A_i| < q_min`` about the base
    joints."""

    name = "bipod"
    lengths = ("b",)
    modes, default_mode = ASSEMBLY_MODES, "up"
    length_constraint = True  # the struts at full extension are links too
    derived_strokes = True
    size_from_lengths = False  # the struts' full extension follows the task's placement

    def to_mech(self, mech, x, y):
        return x + 0.5 * mech.b, y

    def positions(self, v, mode, x, y):
        b = v["b"]
        return np.hypot(x + 0.5 * b, y), np.hypot(x - 0.5 * b, y)

    def build(self, v, mode, strokes=None, pad=0.0):
        (a1, b1), (a2, b2) = strokes
        lo = lambda a: max(a - pad, _v.RESOLUTION * v["b"])  # noqa: E731
        return Bipod(v["b"], lo(a1), b1 + pad, lo(a2), b2 + pad, branch=mode)

    def size(self, mech, derived):
        """``b + q1_max + q2_max``: the base and both struts at full extension.

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
        return mech.b + mech.q1_max + mech.q2_max

    def joints(self, mech, x, y):
        return [(np.full_like(x, -0.5 * mech.b), np.zeros_like(x)),
                (np.full_like(x, 0.5 * mech.b), np.zeros_like(x)), (x, y)]

    def holes(self, mech):
        return [(-0.5 * mech.b, 0.0), (0.5 * mech.b, 0.0)]

    def links(self, mech, x, y, shapes=None):
        """The housings of the strut pivots (discs about ``A_i = (-+b/2, 0)`` in the task
        frame, ``"housing1"``, ``"housing2"``) and the struts ``A_i P`` (``"strut1"``,
        ``"strut2"``: one capsule each, cylinder and rod together), joints ``A1, A2, P``;
        NaN where the pose is out of reach.

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
        ok = mech.reachable(*self.to_mech(mech, x, y))
        px, py = np.where(ok, x, np.nan), np.where(ok, y, np.nan)
        out = []
        for i, ax in enumerate((-0.5 * mech.b, 0.5 * mech.b), start=1):
            a = f"A{i}"
            out += [Body.make(f"housing{i}", "housing", (a,), (GROUND, GROUND), (ax, 0.0), (ax, 0.0),
                              shapes, x.shape),
                    Body.make(f"strut{i}", "distal", (a, "P"), (a, "P"), (ax, 0.0), (px, py), shapes)]
        return out

    def joint_speeds(self, mech, x, y, radius=0.0):
        """The pivots ``A_i``: 0; the tool ``P``: 1.

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
        return {"A1": np.zeros_like(x), "A2": np.zeros_like(x), "P": np.ones_like(x)}

    def reach_radius(self, lmax):
        return lmax

    def placement_above_base(self, mode):
        return mode != "down"

    def sketch(self, mech, px, py, mx, my):
        bases = [(-mech.b / 2, 0), (mech.b / 2, 0)]
        return [[bases[0], (px, py)], [bases[1], (px, py)]], bases


class BipodErrorSpec(ErrorSpec):
    """The perturbable geometry of the Bipod (:mod:`mechopt.core.error_spec`): leg ``i``
    holds ``P`` on the circle of centre the base joint ``A_i`` and radius the strut
    length ``q_i``. Deviations: the strut coordinates ``q1``, ``q2`` (actuator) and
    the struts' length offsets ``s1``, ``s2`` (the strut's length at a given reading:
    link) [L]; the base joints' coordinates ``A1x, A1y, A2x, A2y`` [L]. Passive joints
    with clearance: the base joints ``A1``, ``A2`` (leg ``i``'s centre moves) and the
    platform joint ``P`` (the pin on strut 2 is the tool point; strut 1's bore moves
    leg 1's centre). Every centre and radius is affine in the deviations."""

    scalars = (("q1", "actuator"), ("q2", "actuator"), ("s1", "link"), ("s2", "link"),
               ("A1x", "base"), ("A1y", "base"), ("A2x", "base"), ("A2y", "base"))
    joints = (("A1", (0,)), ("A2", (1,)), ("P", (0,)))

    def circles(self, mech, q1, q2, d):
        g = lambda k: d.get(k, 0.0)  # noqa: E731
        return (g("A1x") + 0.0 * q1, g("A1y") + 0.0 * q1, q1 + g("q1") + g("s1"),
                mech.b + g("A2x") + 0.0 * q2, g("A2y") + 0.0 * q2, q2 + g("q2") + g("s2"))

    def circle_jacobian(self, mech, q1, q2):
        q1, _ = np.broadcast_arrays(np.asarray(q1, float), np.asarray(q2, float))
        D = np.zeros(q1.shape + (6, 8))
        D[..., 2, 0] = D[..., 5, 1] = D[..., 2, 2] = D[..., 5, 3] = 1.0  # radii: q_i, s_i
        D[..., 0, 4] = D[..., 1, 5] = D[..., 3, 6] = D[..., 4, 7] = 1.0  # centres: A_i
        return D


class Bipod(PlanarMechanism):
    """Bipod (RPRPR) ``Bipod(b, q1_min, q1_max, q2_min=None, q2_max=None, branch="up")``.

    See the module docstring for the kinematics, singularities and references.

    Parameters
    ----------
    b : float
        Distance between the base joints ``A1 = (0, 0)`` and ``A2 = (b, 0)`` [L], > 0.
    q1_min, q1_max : float
        Stroke of strut 1 [L], ``0 < q1_min < q1_max``.
    q2_min, q2_max : float, optional
        Stroke of strut 2 [L]; default to ``q1_min``, ``q1_max`` (Stan eq. 13).
    branch : {"up", "down", "full"}
        Working region: ``y >= 0`` (Stan's), ``y <= 0`` or both. Exposed as
        ``mode`` (one of ``modes``) for code written for any mechanism.

    Raises
    ------
    ValueError
        One line, for a non-positive base or an invalid stroke or branch.
    """

    cli_name = "bipod"
    design_spec = BipodDesignSpec
    error_spec = BipodErrorSpec
    cli_help = "Bipod RPRPR (Stan 2008): exact workspace area and global TQI"
    parameters = (
        Parameter("b", "length", "L", "base distance [L]"),
        Parameter("q1_min", "length", "L", "shortest strut 1 [L]"),
        Parameter("q1_max", "length", "L", "longest strut 1 [L]"),
        Parameter("q2_min", "length", "L", "shortest strut 2 [L] (default: q1-min)", None),
        Parameter("q2_max", "length", "L", "longest strut 2 [L] (default: q1-max)", None),
        Parameter("branch", "choice", "-", "workspace half plane: up (y > 0), down or full", "up",
                  BRANCHES),
    )
    modes = BRANCHES
    assembly_modes = ASSEMBLY_MODES
    joint_names = ("q1", "q2")
    angular_joints = False
    #: the keys of :meth:`summary`, in order
    summary_keys = ("workspace_area", "gtqi", "tqi_integral", "q1_min_over_b", "quadrature")
    #: areas scale as ``D^2``, the mean and the ratio not at all (prismatic actuators)
    summary_powers = {"workspace_area": 2, "gtqi": 0, "tqi_integral": 2, "q1_min_over_b": 0}

    def __init__(self, b, q1_min, q1_max, q2_min=None, q2_max=None, branch: str = "up"):
        self.b = _v.positive_length("b", b)
        self.q1_min, self.q1_max = _stroke("q1_min", q1_min, "q1_max", q1_max)
        q2_min = self.q1_min if q2_min is None else q2_min
        q2_max = self.q1_max if q2_max is None else q2_max
        self.q2_min, self.q2_max = _stroke("q2_min", q2_min, "q2_max", q2_max)
        self.branch = _v.choice("branch", branch, BRANCHES)

    def __repr__(self):
        return (
            f"Bipod(b={self.b!r}, q1_min={self.q1_min!r}, q1_max={self.q1_max!r}, "
            f"q2_min={self.q2_min!r}, q2_max={self.q2_max!r}, branch={self.branch!r})"
        )

    @property
    def mode(self) -> str:
        """The branch, under the protocol's name for a working mode."""
        return self.branch

    def with_branch(self, branch: str) -> "Bipod":
        """The same dimensions on another branch.

        Parameters
        ----------
        branch : str
            ``"up"``, ``"down"`` or ``"full"``.

        Returns
        -------
        Bipod
            A new instance.
        """
        return Bipod(self.b, self.q1_min, self.q1_max, self.q2_min, self.q2_max, branch)

    def with_mode(self, mode: str) -> "Bipod":
        """The same dimensions on another branch (the Bipod's working mode).

        Parameters
        ----------
        mode : str
            One of :attr:`modes`.

        Returns
        -------
        PlanarMechanism
            A new instance.
        """
        return self.with_branch(mode)

    def summary(self) -> dict:
        """Floats of :attr:`summary_keys` for ``mechopt evaluate bipod``.

        ``workspace_area`` [L^2] exact (Stan eq. 8, branch of the design), ``gtqi`` the
        exact area mean of the TQI (Stan eq. 9), ``tqi_integral`` [L^2] its
        numerator, ``q1_min_over_b`` Stan's design variable (eq. 11); ``quadrature`` names
        how the mean is taken: ``"exact"`` (closed form, no quadrature).

        Parameters
        ----------
        **options : 
            Options of :attr:`summary_options` (a quadrature, ...).

        Returns
        -------
        dict
            ``{key: float or str}`` with the keys :attr:`summary_keys`, in the mechanism's
            units.
        """
        return {
            "workspace_area": self.workspace_area(),
            "gtqi": self.gtqi("exact"),
            "tqi_integral": self.tqi_integral(),
            "q1_min_over_b": self.q1_min / self.b,
            "quadrature": "exact",
        }

    def scaled(self, factor: float) -> "Bipod":
        """``b`` and the strokes multiplied by ``factor`` (the Jacobian of these
        prismatic actuators is unchanged, areas scale as ``factor^2``).

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
        return Bipod(self.b * f, self.q1_min * f, self.q1_max * f, self.q2_min * f,
                     self.q2_max * f, self.branch)

    @property
    def length_scale(self) -> float:
        """Mean of ``b``, ``q1_max`` and ``q2_max`` [L]."""
        return (self.b + self.q1_max + self.q2_max) / 3.0

    @property
    def base_joints(self):
        """``((0, 0), (b, 0))``."""
        return (0.0, 0.0), (self.b, 0.0)

    @property
    def joint_limits(self):
        """``((q1_min, q1_max), (q2_min, q2_max))`` [L]."""
        return (self.q1_min, self.q1_max), (self.q2_min, self.q2_max)

    # --- bodies (the mass model and the dynamics) ------------------------------
    def bodies(self):
        """The declared bodies (:class:`mechopt.core.rigid_bodies.BodySpec`): per strut ``i`` a
        motor on ``A_i`` (on the frame), the cylinder pivoting about ``A_i`` (a tube as
        long as the retracted strut, ``q_i_min``) and the rod sliding in it (a tube as
        long as the stroke, ``q_i_max - q_i_min``, from ``P`` back into the cylinder,
        joined to it at the prismatic joint ``C_i``); the payload at ``P``.

        Returns
        -------
        list of mechopt.core.rigid_bodies.BodySpec
            The bodies.
        """
        from mechopt.core.rigid_bodies import BodySpec

        out = []
        for i, (lo, hi) in enumerate(self.joint_limits, 1):
            out += [BodySpec(f"motor{i}", "motor", 0.0, (f"A{i}",), leg=i),
                    BodySpec(f"cylinder{i}", "cylinder", lo, (f"A{i}", f"C{i}"), leg=i),
                    BodySpec(f"rod{i}", "rod", hi - lo, ("P", f"C{i}"), leg=i)]
        return tuple(out + [BodySpec("payload", "payload", 0.0, ("P",))])

    def body_frames(self, x, y, xd, yd, xdd, ydd):
        """``(q, qd, qdd, frames)`` of :meth:`bodies` along a motion of ``P``.

        With ``u_i = (P - A_i) / q_i`` the closure ``q_i^2 = |P - A_i|^2`` differentiated
        once and twice gives ``q_dot_i = u_i . P_dot`` and ``q_ddot_i = u_i . P_ddot +
        (|P_dot|^2 - q_dot_i^2) / q_i``. The cylinder's frame has its origin at ``A_i``,
        the rod's at ``P``, both with the x axis along ``P - A_i``; NaN where unreachable.

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

        x, y = as_points(x, y)
        q1, q2, _ = self.ik(x, y)
        P = _b.stack2(x, y)
        Pd, Pdd = _b.stack2(xd, yd), _b.stack2(xdd, ydd)
        zero = np.zeros(P.shape)
        q, qd, qdd, frames = [], [], [], {}
        for i, (A, qi) in enumerate(zip(self.base_joints, (q1, q2)), 1):
            r = P - np.asarray(A)
            with np.errstate(divide="ignore", invalid="ignore"):
                w = np.sum(r * Pd, -1) / qi
                al = np.sum(r * Pdd, -1) / qi + (np.sum(Pd * Pd, -1) - w * w) / qi
            frames[f"motor{i}"] = _b.fixed_frame(A, x.shape)
            frames[f"cylinder{i}"] = (np.broadcast_to(np.asarray(A, float), P.shape), zero, zero, r, Pd, Pdd)
            frames[f"rod{i}"] = (P, Pd, Pdd, r, Pd, Pdd)
            q.append(qi), qd.append(w), qdd.append(al)
        frames["payload"] = _b.translating_frame(P, Pd, Pdd)
        return np.stack(q, -1), np.stack(qd, -1), np.stack(qdd, -1), frames

    # --- kinematics ------------------------------------------------------------
    def strut_lengths(self, x, y):
        """``(q1, q2)`` of Stan eq. (6) at any point, ignoring strokes and branch.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        q1, q2 : ndarray
            The strut lengths [L].
        """
        x, y = as_points(x, y)
        return np.hypot(x, y), np.hypot(x - self.b, y)

    def _in_branch(self, y):
        if self.branch == "up":
            return y >= 0
        if self.branch == "down":
            return y <= 0
        return np.ones(y.shape, dtype=bool)

    def reachable(self, x, y):
        """Both strut lengths within their strokes (to ``LIMIT_RTOL * length_scale``)
        and ``y`` on the branch's side.

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
        q1, q2 = self.strut_lengths(x, y)
        return self._within_strokes(q1, q2, LIMIT_RTOL) & self._in_branch(y)

    def ik(self, x, y):
        """Strut lengths (Stan eq. 6) ``(q1, q2, reachable)`` [L]; NaN where unreachable.

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
        q1, q2 = self.strut_lengths(x, y)
        ok = self.reachable(x, y)
        return np.where(ok, q1, np.nan), np.where(ok, q2, np.nan), ok

    def fk(self, q1, q2, assembly: str = "up", limits: bool = True):
        """Forward kinematics (Stan eq. 7) ``(x, y, valid)``.

        ``assembly="up"`` gives ``y >= 0``, ``"down"`` its mirror image. ``valid``
        is False (and ``x``, ``y`` NaN) where the struts cannot meet
        (``|q1 - q2| <= b <= q1 + q2`` fails) or, with ``limits=True``, where a
        strut length lies outside its stroke.

        Parameters
        ----------
        q1 : array_like
            Length of strut 1 [L].
        q2 : array_like
            Length of strut 2 [L]; broadcast with ``q1``.
        assembly : str
            ``"up"`` (``y >= 0``) or ``"down"``.
        limits : bool
            Whether strut lengths outside their strokes are invalid.

        Returns
        -------
        x, y : ndarray
            The platform point [L]; NaN where invalid.
        valid : ndarray of bool
            Where the legs assemble in that mode.
        """
        _v.choice("assembly", assembly, ASSEMBLY_MODES)
        q1, q2 = as_points(q1, q2)
        b = self.b
        with np.errstate(invalid="ignore"):
            heron = (q1 + q2 + b) * (q2 - q1 + b) * (q1 - q2 + b) * (q1 + q2 - b)
            valid = (heron >= 0) & (q1 >= 0) & (q2 >= 0)
            if limits:
                valid &= self._within_strokes(q1, q2, LIMIT_RTOL)
            x = ((q1 - q2) * (q1 + q2) + b * b) / (2.0 * b)
            y = np.sqrt(np.where(valid, heron, 0.0)) / (2.0 * b)
        if assembly == "down":
            y = -y
        return np.where(valid, x, np.nan), np.where(valid, y, np.nan), valid

    def assembly_of(self, x, y):
        """``"up"`` where ``y >= 0``, else ``"down"``.

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
        return np.where(y >= 0, "up", "down")

    def closure(self, x, y):
        """``A = [P - A1; P - A2]``, ``b = (q1, q2)``: the halved derivative of
        ``q_i^2 = |P - A_i|^2``. NaN where unreachable.

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
        q1, q2, ok = self.ik(x, y)
        nan = np.where(ok, 0.0, np.nan)
        A = np.stack(
            [np.stack([x + nan, y + nan], -1), np.stack([x - self.b + nan, y + nan], -1)], -2
        )
        return A, np.stack([q1, q2], -1), ok

    def closure_enclosure(self, x, y, lengths=None):
        """Interval enclosure of :meth:`closure` over boxes: ``A = [P - A_1; P - A_2]``
        (``A_1 = (0, 0)``, ``A_2 = (b, 0)``), ``b = (|P - A_1|, |P - A_2|)``, each operation
        outward rounded (:mod:`mechopt.core.interval`). ``certain`` is False where an
        enclosed strut length is not inside its stroke widened by the point evaluator's
        tolerance (``LIMIT_RTOL * length_scale``), or the box may cross to the other side
        of the branch (``y >= 0`` for ``"up"``, ``y <= 0`` for ``"down"``).

        With ``lengths`` (``{"b": interval}``, a tolerance box) the enclosure holds for
        every bipod of base ``b'`` in the interval placed as the design spec places it,
        about the base's midpoint (:meth:`BipodDesignSpec.to_mech`): the point ``(x, y)`` of
        this frame is ``m = x - b/2`` from the midpoint, so ``P - A_1 = (m + b'/2, y)`` and
        ``P - A_2 = (m - b'/2, y)``. ``certain`` then tests the branch's side and that
        each strut is longer than the shortest stroke limit a design's build allows
        (``RESOLUTION * b'``, :meth:`BipodDesignSpec.build`), not the strokes: each bipod
        of a tolerance box is built with its own strokes, derived as the ranges of
        ``q_i`` over the task (:attr:`BipodDesignSpec.derived_strokes`), which contain
        every ``q_i`` of the task by construction; this bipod's strokes do not bound a
        neighbour's ``q_i`` (whether the derived strokes meet ``max_length`` is the
        length requirement's question).

        Parameters
        ----------
        x, y : mechopt.core.interval.Interval
            The boxes [L].
        lengths : dict, optional
            ``{"b": interval}`` [L], the base distance (the design spec's length).

        Returns
        -------
        tuple
            ``(A, b, certain)``, as the protocol's.

        Raises
        ------
        ValueError
            For a name in ``lengths`` other than ``b``.
        """
        from mechopt.core.interval import as_interval, hypot

        y = as_interval(y)
        if lengths:
            half = 0.5 * as_interval(self._length_intervals(("b",), lengths)["b"])
            m = x - 0.5 * self.b
            rows = ((m + half, y), (m - half, y))
        else:
            rows = ((x, y), (x - self.b, y))
        q = (hypot(*rows[0]), hypot(*rows[1]))
        if lengths:
            shortest = _v.RESOLUTION * (2.0 * half).hi
            certain = (q[0].lo > shortest) & (q[1].lo > shortest)
        else:
            t = LIMIT_RTOL * self.length_scale
            (lo1, hi1), (lo2, hi2) = self.joint_limits
            certain = ((q[0].lo >= lo1 - t) & (q[0].hi <= hi1 + t) & (q[1].lo >= lo2 - t) & (q[1].hi <= hi2 + t)
                       & (q[0].lo > 0.0) & (q[1].lo > 0.0))
        if self.branch == "up":
            certain &= y.lo >= 0.0
        elif self.branch == "down":
            certain &= y.hi <= 0.0
        return rows, q, certain

    def actuator_enclosure(self, x, y, lengths=None):
        """Interval enclosure of the strut lengths of :meth:`ik` over boxes: ``b`` of
        :meth:`closure_enclosure`, ``(|P - A_1|, |P - A_2|)`` (each a norm of variables
        appearing once: the exact range up to the outward rounding), and its ``certain``.

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
        _, q, certain = self.closure_enclosure(x, y, lengths)
        return q, certain

    # --- the kinematic tree (mechopt.core.kinematic_tree; mechopt export) -----------------
    def kinematic_tree(self):
        """Per strut ``i`` the passive ``base<i>`` on the base at ``A_i`` (body
        ``cylinder<i>``, x along the strut), the actuated prismatic ``q<i>`` along that x
        axis from ``A_i`` (body ``rod<i>``, its origin at the strut's end: ``q_i`` is the
        strut length, limited to the stroke) and the closure frame at the origin of
        ``rod<i>``: the platform point.

        Returns
        -------
        mechopt.core.kinematic_tree.KinematicTree
            The tree.
        """
        joints, closure = [], []
        for i, ((ax, ay), lim) in enumerate(zip(self.base_joints, self.joint_limits), 1):
            joints += [TreeJoint(f"base{i}", "revolute", BASE, f"cylinder{i}", (ax, ay)),
                       TreeJoint(f"q{i}", "prismatic", f"cylinder{i}", f"rod{i}", (0.0, 0.0), (1.0, 0.0), True,
                                 tuple(lim))]
            closure.append(ClosureFrame(CLOSURE_NAMES[i - 1], f"rod{i}", (0.0, 0.0)))
        return KinematicTree(self.cli_name, tuple(joints), tuple(closure))

    def tree_configuration(self, x, y) -> dict:
        """Every joint of :meth:`kinematic_tree` at ``(x, y)``: ``base<i>`` the strut's
        angle ``atan2(y, x - x_Ai)`` [rad], ``q<i>`` its length from :meth:`ik`; NaN out
        of reach.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        dict
            ``{joint: ndarray}`` [L or rad].
        """
        x, y = as_points(x, y)
        q1, q2, ok = self.ik(x, y)
        out = {}
        for i, ((ax, ay), q) in enumerate(zip(self.base_joints, (q1, q2)), 1):
            out[f"base{i}"] = np.where(ok, np.arctan2(y - ay, x - ax), np.nan)
            out[f"q{i}"] = q
        return out

    def serial_clearance(self, x, y):
        """Signed distance to the boundary of the reachable set, positive inside.

        ``min(q1 - q1_min, q1_max - q1, q2 - q2_min, q2_max - q2)`` (each term is
        the exact distance to a stroke-limit circle), and also ``y`` (``"up"``) or
        ``-y`` (``"down"``), the distance to the type-II x axis. Inside the
        reachable set this is the exact distance to its boundary; outside it is
        negative but not the distance. The stroke-limit arcs are joint limits,
        not type-I loci (the Bipod has none, see the module docstring).

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
        q1, q2 = self.strut_lengths(x, y)
        terms = [q1 - self.q1_min, self.q1_max - q1, q2 - self.q2_min, self.q2_max - q2]
        if self.branch == "up":
            terms.append(y)
        elif self.branch == "down":
            terms.append(-y)
        return np.minimum.reduce(terms)

    def bounding_box(self):
        """``(xmin, xmax, ymin, ymax)``: the intersection of the two outer disks'
        boxes, cut to the branch's half plane.

        Returns
        -------
        tuple of float
            ``(xmin, xmax, ymin, ymax)`` [L].
        """
        xmin = max(-self.q1_max, self.b - self.q2_max)
        xmax = min(self.q1_max, self.b + self.q2_max)
        r = min(self.q1_max, self.q2_max)
        ymin, ymax = {"up": (0.0, r), "down": (-r, 0.0), "full": (-r, r)}[self.branch]
        return (xmin, xmax, ymin, ymax)

    # --- global measures ---------------------------------------------------------
    def _design(self):
        return (self.b, self.q1_min, self.q1_max, self.q2_min, self.q2_max, self.branch)

    def workspace_area(self) -> float:
        """Exact area W [L^2] of the workspace on this branch (Stan eq. 8).

        Returns
        -------
        float
            The area [L^2].
        """
        return float(bipod_workspace_area(*self._design()))

    def tqi_integral(self) -> float:
        """Exact ``int_W TQI dA`` [L^2] (module docstring).

        Returns
        -------
        float
            The integral [L^2].
        """
        return float(bipod_tqi_integral(*self._design()))

    def gtqi(self, method: str = "exact", step=None) -> float:
        """Area mean of the TQI (Stan eq. 9) over the workspace.

        ``method="exact"`` is ``tqi_integral() / workspace_area()`` (closed form,
        rounding error only). ``method="raster"`` is the mid-point mean over the
        cells of :func:`mechopt.core.quadrature.grid_over` whose centres are reachable,
        with cells of side ``step`` [L] (default: the smaller side of the bounding
        box / :data:`~mechopt.core.quadrature.RASTER_CELLS`); its error is first order
        in ``step`` (boundary cells): for Stan's design 9e-4 relative at ``step = 2``
        mm, 4e-5 at the default (0.325 mm), 3e-6 at 0.1 mm. NaN for an empty workspace.

        Parameters
        ----------
        method : str
            ``"exact"`` or ``"raster"``.
        step : float, optional
            Raster cell side [L].

        Returns
        -------
        float
            The GTQI (dimensionless).
        """
        _v.choice("method", method, GTQI_METHODS)
        if method == "exact":
            w = self.workspace_area()
            return float(self.tqi_integral() / w) if w > 0 else float("nan")
        return self.raster_mean(self.tqi, step)


#: the keys of :meth:`Bipod.summary`
SUMMARY_KEYS = Bipod.summary_keys
