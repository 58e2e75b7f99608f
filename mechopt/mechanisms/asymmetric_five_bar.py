"""The general (asymmetric) five-bar 5R: each leg has its own crank and distal link.

Geometry: base joints ``A1 = (-r3, 0)``, ``A2 = (r3, 0)``; leg ``i`` has a crank
``A_i B_i`` of length ``a_i`` (actuated angle ``theta_i`` from the x axis) and a
distal link ``B_i P`` of length ``c_i``. With ``a1 = a2`` and ``c1 = c2`` it is the
symmetric :class:`~mechopt.FiveBar` (same working modes, same poses, same
Jacobian): the kinematics are the five-bar's own functions
(:func:`mechopt.mechanisms.five_bar.model.legs_elbows`, ``legs_ik``, ``legs_fk``, ...),
written once in terms of per-leg lengths, so with equal legs the two agree bit for
bit (``tests/test_asymmetric_five_bar.py`` checks them against an independent
computation). The elbow of leg ``i`` is the circle intersection
``B_i = A_i + a_i R(s_i alpha_i) (P - A_i) / |P - A_i|`` with ``alpha_i`` from the law
of cosines, and ``theta1 = beta1 + s1 alpha1``, ``theta2 = pi - beta2 + s2 alpha2`` as
in Le 2013 eq. (17)-(18).

The closure ``|P - B_i|^2 = c_i^2`` differentiates to ``a_i . p_dot = (B_i - A_i) x a_i
theta_dot_i`` with ``a_i = P - B_i``: ``J = B^-1 A`` as for every mechanism of the
protocol. The mechanism is not symmetric about the y axis, so the Liu 2006 disk
indices (MIC centred on the y axis) are not offered (``disk_indices = False``); its
own numbers (:meth:`AsymmetricFiveBar.summary`) are the reachable area and the area
means of the LCI and the TQI over it.

This module is the whole implementation: the contract suite (a case in
``tests/mechanism_cases.py``), ``mechopt evaluate asymmetric-five-bar``,
:func:`mechopt.analysis.evaluate.evaluate` and, through its design specification
(:class:`AsymmetricFiveBarDesignSpec`), ``mechopt design asymmetric-five-bar`` pick it
up from :func:`mechopt.mechanisms.registry`.

References
----------
Le, Kang, Doan (2013), ICCAIS, doi:10.1109/ICCAIS.2013.6720521, eq. (9)-(19) (the
symmetric case).
"""
from __future__ import annotations


from mechopt.core import validation as _v
from mechopt.core.protocol import Parameter, PlanarMechanism
from mechopt.core.quadrature import RASTER_CELLS, grid_over
from mechopt.mechanisms.five_bar import model as _fb
from mechopt.mechanisms.five_bar.model import ASSEMBLY_MODES, MODES

__all__ = ["AsymmetricFiveBar", "AsymmetricFiveBarDesignSpec", "MODES", "ASSEMBLY_MODES"]


class AsymmetricFiveBarDesignSpec(_fb.FiveBarDesignSpec):
    """``mechopt design asymmetric-five-bar``: the lengths ``a1, c1, a2, c2`` (crank and
    distal link of each leg) and ``r3`` (the half base, from 0) [L], the modes of the
    five-bar (default ``"+-"``), cranks. As for the five-bar the reachable set is the
    intersection of the legs' annuli ``|a_i - c_i| <= |P - A_i| <= a_i + c_i``,
    symmetric about the base line; each bounded component of its complement lies in
    the union of the inner disks, so it holds a base joint (the holes). The joints,
    holes, reach and sketch are the five-bar's (its elbows by leg); with equal legs
    (``a1 = a2 = r1``, ``c1 = c2 = r2``) every number equals the five-bar's."""

    name = "asymmetric-five-bar"
    lengths = ("a1", "c1", "a2", "c2", "r3")

    def lower_bounds(self, lmin):
        return [lmin, lmin, lmin, lmin, 0.0]

    def build(self, v, mode, strokes=None, pad=0.0):
        return AsymmetricFiveBar(v["a1"], v["c1"], v["a2"], v["c2"], v["r3"], mode)

    def size(self, mech, derived):
        """``a1 + c1 + a2 + c2 + 2 r3``: both legs and the base distance (the five-bar's
        ``2 (r1 + r2 + r3)`` for equal legs).

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
        return mech.a1 + mech.c1 + mech.a2 + mech.c2 + 2.0 * mech.r3

    def placement_scale(self, v, lmax):
        return max(v["a1"] + v["c1"], v["a2"] + v["c2"])

    def joint_arc_radius(self, mech, leg):
        return 0.35 * (mech.a1, mech.a2)[leg]


class AsymmetricFiveBar(PlanarMechanism):
    """``AsymmetricFiveBar(a1, c1, a2, c2, r3, mode="+-")``: cranks ``a_i``, distal links
    ``c_i`` [L] (> 0), half base distance ``r3`` [L] (>= 0), working mode as for the
    symmetric five-bar.

    Parameters
    ----------
    a1, c1 : float
        Crank and distal link of leg 1 (base joint ``(-r3, 0)``) [L], > 0.
    a2, c2 : float
        Crank and distal link of leg 2 (base joint ``(r3, 0)``) [L], > 0.
    r3 : float
        Half the base distance [L], >= 0.
    mode : {"+-", "-+", "++", "--"}
        Working mode (elbow signs, as for :class:`~mechopt.mechanisms.five_bar.model.FiveBar`).

    Raises
    ------
    ValueError
        One line, for a non-positive link, a negative ``r3`` or an unknown mode.
    """

    cli_name = "asymmetric-five-bar"
    cli_help = "5R with unequal legs: reachable area, mean LCI and TQI (raster)"
    parameters = (
        Parameter("a1", "length", "L", "crank of leg 1 [L]"),
        Parameter("c1", "length", "L", "distal link of leg 1 [L]"),
        Parameter("a2", "length", "L", "crank of leg 2 [L]"),
        Parameter("c2", "length", "L", "distal link of leg 2 [L]"),
        Parameter("r3", "length0", "L", "half the base distance [L]"),
        Parameter("mode", "choice", "-", "working mode (elbow signs, leg 1 first)", "+-", MODES),
    )
    modes = MODES
    assembly_modes = ASSEMBLY_MODES
    joint_names = ("theta1", "theta2")
    angular_joints = True
    design_spec = AsymmetricFiveBarDesignSpec
    error_spec = _fb.FiveBarErrorSpec
    #: the keys of :meth:`summary`, in order
    summary_keys = ("workspace_area", "mean_lci", "mean_tqi", "quadrature")
    #: the area scales as ``D^2``, the means of indices not at all
    summary_powers = {"workspace_area": 2, "mean_lci": 0, "mean_tqi": 0}

    def __init__(self, a1, c1, a2, c2, r3, mode: str = "+-"):
        self.a1, self.c1 = _v.positive_length("a1", a1), _v.positive_length("c1", c1)
        self.a2, self.c2 = _v.positive_length("a2", a2), _v.positive_length("c2", c2)
        self.r3 = _v.nonnegative_length("r3", r3)
        self.mode = _v.choice("mode", mode, MODES)
        self._s = _fb.elbow_signs(mode)

    def __repr__(self):
        return (f"AsymmetricFiveBar(a1={self.a1!r}, c1={self.c1!r}, a2={self.a2!r}, "
                f"c2={self.c2!r}, r3={self.r3!r}, mode={self.mode!r})")

    def _legs(self):
        """``(crank, distal link, elbow sign)`` of leg 1 (on ``(-r3, 0)``) and leg 2."""
        return (self.a1, self.c1, self._s[0]), (self.a2, self.c2, self._s[1])

    def with_mode(self, mode: str) -> "AsymmetricFiveBar":
        return AsymmetricFiveBar(self.a1, self.c1, self.a2, self.c2, self.r3, mode)

    def scaled(self, factor: float) -> "AsymmetricFiveBar":
        f = _v.positive_length("factor", factor)
        return AsymmetricFiveBar(self.a1 * f, self.c1 * f, self.a2 * f, self.c2 * f, self.r3 * f,
                                 self.mode)

    @property
    def length_scale(self) -> float:
        return (self.a1 + self.c1 + self.a2 + self.c2) / 4.0 + self.r3 / 2.0

    # --- geometry: the five-bar's, with this mechanism's legs ---------------------------
    def elbows(self, x, y):
        """``(b1x, b1y, b2x, b2y, reachable)`` of the working mode; NaN where unreachable.

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
        return _fb.legs_elbows(x, y, self.r3, self._legs())

    def bodies(self):
        """The declared bodies (:func:`~mechopt.mechanisms.five_bar.model.legs_bodies`).

        Returns
        -------
        list of mechopt.core.rigid_bodies.BodySpec
            The bodies.
        """
        return _fb.legs_bodies(self.r3, self._legs())

    def body_frames(self, x, y, xd, yd, xdd, ydd):
        """``(q, qd, qdd, frames)`` along a motion of ``P``
        (:func:`~mechopt.mechanisms.five_bar.model.legs_body_frames`).

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
            Actuator positions [rad], rates and accelerations (per second, per second
            squared).
        frames : dict
            Per body its frame along the motion (:mod:`mechopt.core.rigid_bodies`).
        """
        return _fb.legs_body_frames(x, y, xd, yd, xdd, ydd, self.r3, self._legs())

    def closure(self, x, y):
        """``A p_dot = B theta_dot``: ``a_i = P - B_i``, ``B_ii = (B_i - A_i) x a_i``.

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
        return _fb.legs_closure(x, y, self.r3, self._legs())

    def closure_enclosure(self, x, y, lengths=None):
        """Interval enclosure of :meth:`closure` over boxes
        (:func:`mechopt.mechanisms.five_bar.model.legs_closure_enclosure`), for every
        mechanism with its lengths in ``lengths`` (intervals) where given.

        Parameters
        ----------
        x, y : mechopt.core.interval.Interval
            The boxes [L].
        lengths : dict, optional
            ``{"a1" | "c1" | "a2" | "c2" | "r3": interval}`` [L].

        Returns
        -------
        tuple
            ``(A, b, certain)``.
        """
        return _fb.legs_closure_enclosure(x, y, *self._interval_legs(lengths))

    def _interval_legs(self, lengths):
        """``(r3, legs)`` of :meth:`_legs` with the lengths in ``lengths`` (intervals)
        replacing the instance's, for the enclosures."""
        L = self._length_intervals(("a1", "c1", "a2", "c2", "r3"), lengths)
        return L["r3"], ((L["a1"], L["c1"], self._s[0]), (L["a2"], L["c2"], self._s[1]))

    def actuator_enclosure(self, x, y, lengths=None):
        """Interval enclosure of the crank angles of :meth:`ik` over boxes
        (:func:`mechopt.mechanisms.five_bar.model.legs_actuator_enclosure`), for every
        mechanism with its lengths in ``lengths`` (intervals) where given.

        Parameters
        ----------
        x, y : mechopt.core.interval.Interval
            The boxes [L].
        lengths : dict, optional
            ``{"a1" | "c1" | "a2" | "c2" | "r3": interval}`` [L].

        Returns
        -------
        tuple
            ``(theta, certain)``.
        """
        return _fb.legs_actuator_enclosure(x, y, *self._interval_legs(lengths))

    def reachable(self, x, y):
        return _fb.legs_reachable(x, y, self.r3, self._legs())

    def serial_clearance(self, x, y):
        """Signed distance to the nearest of the four circles bounding the legs' annuli.

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
        return _fb.legs_serial_clearance(x, y, self.r3, self._legs())

    def bounding_box(self):
        return _fb.legs_bounding_box(self.r3, self._legs())

    def ik(self, x, y):
        """Crank angles (rad) of the working mode, unwrapped as by :meth:`~mechopt.FiveBar.ik`.

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
        return _fb.legs_ik(x, y, self.r3, self._legs())

    def fk(self, theta1, theta2, assembly: str = "up"):
        """Intersection of the distal circles about ``B_1``, ``B_2``; ``"up"``: ``P`` left of
        ``B1 -> B2``. Returns ``(x, y, valid)``.

        Parameters
        ----------
        theta1 : array_like
            Crank angle of leg 1 [rad].
        theta2 : array_like
            Crank angle of leg 2 [rad]; broadcast with ``theta1``.
        assembly : str
            One of :attr:`assembly_modes`.

        Returns
        -------
        x, y : ndarray
            The platform point [L]; NaN where invalid.
        valid : ndarray of bool
            Where the legs assemble in that mode.
        """
        return _fb.legs_fk(theta1, theta2, self.r3, self._legs(), assembly)

    def assembly_of(self, x, y):
        return _fb.legs_assembly_of(x, y, self.r3, self._legs())

    def kinematic_tree(self):
        """Bodies and joints, the loop cut at the platform (the five-bar's
        :func:`~mechopt.mechanisms.five_bar.model.legs_tree` with this mechanism's legs).

        Returns
        -------
        mechopt.core.kinematic_tree.KinematicTree
            The tree.
        """
        return _fb.legs_tree(self.cli_name, self.r3, self._legs())

    def tree_configuration(self, x, y) -> dict:
        """Every joint of :meth:`kinematic_tree` at ``(x, y)``.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L].
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        dict
            ``{joint: ndarray}`` [rad or rad].
        """
        return _fb.legs_tree_configuration(x, y, self.r3, self._legs())

    # --- global numbers -----------------------------------------------------------
    def summary(self) -> dict:
        """Reachable area [L^2] and the area means of the LCI and the TQI over it, by the
        mid-point rule on a raster of :data:`~mechopt.core.quadrature.RASTER_CELLS` cells
        across the bounding box's smaller side (first-order error in the cell size). An
        empty workspace is a result: area 0 and NaN means, also for legs that never meet
        (an empty bounding box, e.g. ``r3`` beyond both legs' reach).

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
        empty = {"workspace_area": 0.0, "mean_lci": float("nan"), "mean_tqi": float("nan"),
                 "quadrature": f"raster-{RASTER_CELLS}"}
        box = self.bounding_box()
        if not (box[1] > box[0] and box[3] > box[2]):  # the legs' reaches do not overlap
            return empty
        step = min(box[1] - box[0], box[3] - box[2]) / RASTER_CELLS
        grid = grid_over(box, step)
        X, Y = grid.points()
        mask = self.reachable(X, Y)
        area = grid.area(mask)
        if not mask.any():
            return empty
        return {"workspace_area": area, "mean_lci": self.raster_mean(self.lci, step),
                "mean_tqi": self.raster_mean(self.tqi, step), "quadrature": f"raster-{RASTER_CELLS}"}
