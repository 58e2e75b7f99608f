"""The design specification of a mechanism: how ``mechopt design`` sizes it.

A mechanism of the protocol offers itself to :func:`mechopt.workflows.design.design`
by setting :attr:`PlanarMechanism.design_spec <mechopt.core.protocol.PlanarMechanism.design_spec>`
to a subclass of :class:`DesignSpec` defined next to it in its own module:
:func:`mechopt.analysis.task.get_spec` finds it through
:func:`mechopt.mechanisms.registry`, so a new mechanism is sized without an edit in
the design machinery (:class:`mechopt.analysis.task.DesignEvaluator`, the problem, the
CLI, the figure).

A spec states, in the task's length unit [L]: the design variables (:attr:`DesignSpec.lengths`)
and their lower bounds, the working modes, the mechanism built from them
(:meth:`DesignSpec.build`) in the task frame (base midpoint at the origin, y away from
the base; :meth:`DesignSpec.to_mech` maps a task point into the mechanism's own
frame), the ``size`` objective, the joints whose distance from the base midpoint is
the ``footprint``, the holes of the reachable set (the reach certificate of
:mod:`mechopt.analysis.task` needs a base joint in every bounded component of the
complement of the reachable set), bounds on the reach for the input checks, and the
sketch of :func:`mechopt.workflows.design.plot_design`, and the bodies of the mechanism
as capsules (:meth:`DesignSpec.links`, :mod:`mechopt.core.bodies`) with the speeds of their
joints (:meth:`DesignSpec.joint_speeds`) for the collision and keep-out checks of
:mod:`mechopt.analysis.collisions`.

Two kinds of actuators are covered: angular (cranks, :attr:`DesignSpec.angular`: joint
ranges are reported, ``joint_limits`` apply) and prismatic with derived strokes
(:attr:`DesignSpec.derived_strokes`: the stroke of each actuator is not searched but
taken as the range of its coordinate over the task, :meth:`DesignSpec.positions`).
"""
from __future__ import annotations

import math

__all__ = ["DesignSpec"]


class DesignSpec:
    """How one mechanism of the protocol is sized (module docstring).

    Instances carry no state: :func:`mechopt.analysis.task.get_spec` builds one with
    no argument, and :class:`~mechopt.analysis.task.DesignEvaluator` pickles it to
    its workers (so a spec class lives at module level). Lengths are in the task's
    unit [L]; a design ``v`` is a dict ``{name: value}`` over :attr:`lengths`.
    """

    #: the mechanism's ``cli_name`` (``mechopt design NAME``)
    name: str = ""
    #: names of the design variables, all lengths [L], in the order of ``--shape``
    lengths: tuple[str, ...] = ()
    #: the working modes a design may take (``--mode``), and the default one
    modes: tuple[str, ...] = ()
    default_mode: str = ""
    #: True for cranks (angles in rad: joint ranges, ``joint_limits``), False for
    #: prismatic actuators (strokes, ``max_stroke``)
    angular: bool = False
    #: True when derived lengths (the bipod's struts at full extension) are links
    #: too: the ``lengths`` requirement bounds them by ``max_length``
    length_constraint: bool = False
    #: True when the actuator strokes are derived from the task (:meth:`positions`);
    #: then :meth:`build` takes ``strokes`` and ``pad``
    derived_strokes: bool = False
    #: the size depends on the lengths alone (not on the task placement: no derived stroke in it)
    size_from_lengths: bool = True
    #: None, or a method ``link_angles(mech, x, y) -> (angle1, angle2)`` [rad] in
    #: ``[0, pi/2]`` at task points: then the ``link_angle`` requirement applies. Their
    #: extremes over the task must lie on its boundary (e.g. angles depending on x alone)
    link_angles = None

    # --- the variables --------------------------------------------------------------
    def lower_bounds(self, lmin) -> list:
        """Lower bound of each of :attr:`lengths` [L] given the shortest link ``lmin``.

        Parameters
        ----------
        lmin : float
            The shortest link [L].

        Returns
        -------
        list of float
            One bound per length [L].
        """
        return [lmin] * len(self.lengths)

    def validity(self, v, lmax) -> float:
        """<= 0 when the variables describe a mechanism (normalised by ``lmax``).

        Parameters
        ----------
        v : dict
            The design: ``{name: value}`` over :attr:`lengths` [L].
        lmax : float
            The longest link allowed [L].

        Returns
        -------
        float
            The validity measure (dimensionless); -1 by default.
        """
        return -1.0

    def size_of(self, v) -> float:
        """:meth:`size` from the lengths of ``v`` alone (``size_from_lengths`` specs).

        Parameters
        ----------
        v : dict
            The design: ``{name: value}`` over :attr:`lengths` [L].

        Returns
        -------
        float
            The size [L].
        """
        from types import SimpleNamespace

        return float(self.size(SimpleNamespace(**{n: v[n] for n in self.lengths}), {}))

    def size_bound(self, lmax) -> float:
        """An upper bound [L] of :meth:`size` over designs with every length <= ``lmax``
        (the reference range of the ``size`` objective's hypervolume). Default: three times
        ``lmax`` per design variable (every size here counts each length at most three
        times, the bipod's struts, bounded by ``lmax``, included).

        Parameters
        ----------
        lmax : float
            The longest link allowed [L].

        Returns
        -------
        float
            The bound [L].
        """
        return 3.0 * len(self.lengths) * lmax

    # --- the mechanism ----------------------------------------------------------------
    def build(self, v, mode, strokes=None, pad=0.0):
        """The mechanism of the design ``v`` in working ``mode``; with
        :attr:`derived_strokes`, ``strokes = ((lo1, hi1), (lo2, hi2))`` [L] are the
        actuator ranges over the task and ``pad`` [L] widens each.

        Parameters
        ----------
        v : dict
            The design: ``{name: value}`` over :attr:`lengths` [L].
        mode : str
            A working mode of :attr:`modes`.
        strokes : tuple, optional
            ``((lo1, hi1), (lo2, hi2))`` [L], with :attr:`derived_strokes`.
        pad : float
            Widening of each stroke [L].

        Returns
        -------
        PlanarMechanism
            The mechanism.

        Raises
        ------
        NotImplementedError
            In the base class: each spec implements it.
        """
        raise NotImplementedError(f"{type(self).__name__} does not build its mechanism")

    def positions(self, v, mode, x, y):
        """``(q1, q2)`` [L] at task points ``(x, y)`` (NaN out of reach), for
        :attr:`derived_strokes` specs: the strokes are their ranges over the task.

        Parameters
        ----------
        v : dict
            The design: ``{name: value}`` over :attr:`lengths` [L].
        mode : str
            A working mode.
        x : array_like
            Task points' abscissae [L, task frame].
        y : array_like
            Ordinates [L, task frame]; shape of ``x``.

        Returns
        -------
        q1, q2 : ndarray
            Actuator positions [L], NaN out of reach.

        Raises
        ------
        NotImplementedError
            In the base class: each spec implements it.
        """
        raise NotImplementedError(f"{type(self).__name__} derives no strokes")

    def to_mech(self, mech, x, y):
        """Task-frame points in the mechanism's own frame (default: the same).

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        x : array_like
            Task points' abscissae [L, task frame].
        y : array_like
            Ordinates [L, task frame]; shape of ``x``.

        Returns
        -------
        x, y : ndarray
            The points in the mechanism's frame [L].
        """
        return x, y

    # --- what is measured -------------------------------------------------------------
    def size(self, mech, derived) -> float:
        """The ``size`` objective [L] of ``mech`` (``derived``: the evaluation's derived
        values, e.g. strokes); each spec's docstring says which lengths it sums.

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

        Raises
        ------
        NotImplementedError
            In the base class: each spec implements it.
        """
        raise NotImplementedError(f"{type(self).__name__} defines no size")

    def joints(self, mech, x, y) -> list:
        """``[(jx, jy), ...]`` arrays of every joint position [L, task frame] with the
        platform at task points ``(x, y)`` (the ``footprint`` objective).

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        x : array_like
            Task points' abscissae [L, task frame].
        y : array_like
            Ordinates [L, task frame]; shape of ``x``.

        Returns
        -------
        list of tuple
            ``[(jx, jy), ...]`` arrays [L, task frame].

        Raises
        ------
        NotImplementedError
            In the base class: each spec implements it.
        """
        raise NotImplementedError(f"{type(self).__name__} defines no joints")

    def links(self, mech, x, y, shapes=None) -> list:
        """Every body of ``mech`` with the platform at task points ``(x, y)`` [L, task
        frame]: a list of :class:`~mechopt.core.bodies.Body` (links, motor housings,
        carriages, guides as capsules of the sizes of ``shapes``, a
        :class:`~mechopt.core.bodies.Shapes`; default :meth:`Shapes.default()
        <mechopt.core.bodies.Shapes.default>`, millimetres), their end points arrays of
        the shape of ``x``; NaN where the pose is out of reach. Two bodies carrying a
        common joint name are adjacent (:mod:`mechopt.core.bodies`).

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

        Raises
        ------
        NotImplementedError
            In the base class: each spec implements it.
        """
        raise NotImplementedError(f"{type(self).__name__} declares no links")

    def joint_speeds(self, mech, x, y, radius=0.0) -> dict:
        """``{name: bound}`` for every moving point named in the ``ends`` of
        :meth:`links` (``"ground"`` excepted): an upper bound of its speed per unit
        platform speed [L/L], over the platform positions within ``radius`` [L] of each
        task point ``(x, y)`` (arrays; ``inf`` where no bound holds, e.g. a disc that
        reaches a type-I singularity). With ``radius = 0`` it is the speed at the pose:
        the norm of the point's Jacobian ``d(point)/d(platform)``.

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

        Raises
        ------
        NotImplementedError
            In the base class: each spec implements it.
        """
        raise NotImplementedError(f"{type(self).__name__} declares no joint speeds")

    def holes(self, mech) -> list:
        """``[(x, y), ...]``: one point [L, task frame] in each bounded component of the
        complement of the reachable set; the reach certificate requires none of them
        inside the task (:mod:`mechopt.analysis.task`, "reach").

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).

        Returns
        -------
        list of tuple
            ``[(x, y), ...]`` [L, task frame] (default none).
        """
        return []

    # --- bounds on the reach (input checks, the placement search) ----------------------
    def placement_scale(self, v, lmax) -> float:
        """Length [L] over which a free task placement is searched (the design's reach).

        Parameters
        ----------
        v : dict
            The design: ``{name: value}`` over :attr:`lengths` [L].
        lmax : float
            The longest link allowed [L].

        Returns
        -------
        float
            The length [L] (default ``lmax``).
        """
        return lmax

    def placement_above_base(self, mode) -> bool:
        """True when a free placement of the task is searched above the base only
        (``task_y`` from half the task's height up), for ``mode`` (None with
        ``mode="any"``): its reachable set is symmetric about the base line (the
        five-bar), so the mirrored half adds nothing, or lies above it (the bipod's
        ``"up"`` branch).

        Parameters
        ----------
        mode : str or None
            A working mode, or None for ``mode="any"``.

        Returns
        -------
        bool
            False by default.
        """
        return False

    def placement_both_sides(self, mode) -> bool:
        """True when a free placement searched above the base line
        (:meth:`placement_above_base`) is searched below it too, for ``mode``: the
        mirror image about the line of a design in one working mode is a design in
        another (the five-bar's ``"+-"`` mirrored is ``"-+"``), so with one mode fixed
        the designs below the line are not those above. ``mechopt design`` then runs a
        second search below the line, the mirror image of the first
        (:mod:`mechopt.workflows.design`).

        Parameters
        ----------
        mode : str or None
            A working mode, or None for ``mode="any"``.

        Returns
        -------
        bool
            False by default.
        """
        return False

    def reach_radius(self, lmax) -> float:
        """No design within the length bounds reaches a point farther than this [L] from
        the base midpoint (a necessary condition, checked before any run).

        Parameters
        ----------
        lmax : float
            The longest link allowed [L].

        Returns
        -------
        float
            The radius [L] (default infinite).
        """
        return math.inf

    def x_reach(self, lmax) -> float:
        """No design within the length bounds reaches ``|x|`` beyond this [L].

        Parameters
        ----------
        lmax : float
            The longest link allowed [L].

        Returns
        -------
        float
            The bound [L] (default infinite).
        """
        return math.inf

    # --- the figure of the chosen design ----------------------------------------------
    def sketch(self, mech, px, py, mx, my):
        """The legs with the platform at the task point ``(px, py)`` (``(mx, my)`` in the
        mechanism's frame): ``(chains, bases)``, ``chains`` a list of polylines
        ``[(x, y), ...]`` (one per leg, base to platform) and ``bases`` the base-side
        joints to mark, all in the task frame [L].

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        px : float
            Task point abscissa [L, task frame].
        py : float
            Task point ordinate [L, task frame].
        mx : float
            The point's abscissa in the mechanism's frame [L].
        my : float
            Its ordinate in the mechanism's frame [L].

        Returns
        -------
        chains : list
            Polylines ``[(x, y), ...]`` [L], one per leg.
        bases : list
            Base-side joints ``(x, y)`` [L].

        Raises
        ------
        NotImplementedError
            In the base class: each spec implements it.
        """
        raise NotImplementedError(f"{type(self).__name__} draws no sketch")

    def actuator_paths(self, mech, strokes) -> list:
        """Segments ``((x0, y0), (x1, y1))`` [L] drawn under the legs: the actuators'
        travel over the task (``strokes`` as in :meth:`build`). Default none.

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
        return []

    def joint_arc_radius(self, mech, leg):
        """Radius [L] of the arc drawn about the base joint of ``leg`` (0 or 1) over its
        joint range, or None for no arc (prismatic actuators).

        Parameters
        ----------
        mech : PlanarMechanism
            The built mechanism (:meth:`build`).
        leg : int
            0 or 1.

        Returns
        -------
        float or None
            The radius [L].
        """
        return None

    def variable_lines(self, variables, unit) -> list:
        """The figure's text lines naming the design: ``variables`` holds the lengths
        and ``mode``.

        Parameters
        ----------
        variables : dict
            The lengths [unit] and ``mode``.
        unit : str
            The length unit.

        Returns
        -------
        list of str
            The lines.
        """
        return [f"{self.name} ({variables['mode']}): " + ", ".join(
            f"{k} = {variables[k]:.4g} {unit}" for k in self.lengths)]
