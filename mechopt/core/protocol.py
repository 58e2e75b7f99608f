"""The mechanism protocol shared by every 2-DOF planar parallel manipulator.

Every mechanism maps a platform point ``P = (x, y)`` to actuator coordinates
``q = (q1, q2)`` (angles in rad or slider/strut lengths) and differentiates the
closure equations of its two legs into

    A(P) p_dot = B(P) q_dot,      B diagonal,

so that the Jacobian used throughout mechopt is ``J = B^-1 A`` with
``q_dot = J p_dot`` (Liu 2006 eq. 1). ``det A = 0`` is the type-II (parallel,
"uncertainty") singularity and ``B_ii = 0`` the type-I (serial, "stationary") one
(Gosselin & Angeles 1990). A subclass implements :meth:`closure`, :meth:`ik`,
:meth:`fk`, :meth:`reachable`, :meth:`serial_clearance` and :meth:`bounding_box`;
everything else (Jacobian, singular values, local indices, singularity
classification) is derived here once.

All methods broadcast over NumPy arrays of points; scalars give 0-d arrays.
"""
from __future__ import annotations

import weakref
from abc import ABC, abstractmethod

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core import validation as _v
from mechopt.core.quadrature import RASTER_CELLS

__all__ = ["PlanarMechanism", "Parameter", "REQUIRED", "PARAMETER_KINDS", "ASSEMBLY_MODES", "as_points",
           "mark_in_reach"]

#: the two assembly modes of the forward problem of a two-legged mechanism: which side
#: of the line through its two distal joints (or base joints) the platform point lies on
ASSEMBLY_MODES = ("up", "down")

#: the kinds of a declared parameter (the CLI's converters and the fuzz tests' value
#: generators both follow them): a positive length, a length that may vanish, a signed
#: position, an angle in degrees, a fraction in (0, 1), one string of ``choices``
PARAMETER_KINDS = ("length", "length0", "position", "angle_deg", "fraction", "choice")


class _Required:
    def __repr__(self):
        return "REQUIRED"


#: default of a parameter that must be given
REQUIRED = _Required()


class Parameter:
    """A declared input of a mechanism (a constructor argument, or an option of its
    evaluation): ``name`` (a Python identifier; the CLI option is ``--name`` with
    dashes), ``kind`` (:data:`PARAMETER_KINDS`), ``unit`` ([L], deg, ...), ``help``,
    ``default`` (:data:`REQUIRED` when it must be given) and ``choices``.

    Parameters
    ----------
    name : str
        A Python identifier; the option is ``--name`` with dashes.
    kind : str
        One of :data:`PARAMETER_KINDS`.
    unit : str
        The unit as shown in help texts ([L], deg, ...).
    help : str
        One line for ``--help``.
    default : object, optional
        The default; :data:`REQUIRED` (the default) when the parameter must be given.
    choices : sequence of str, optional
        The allowed strings, exactly for kind ``"choice"``.

    Raises
    ------
    ValueError
        For an unknown kind, or choices given for another kind than ``"choice"`` (or missing
        for it).
    """

    __slots__ = ("name", "kind", "unit", "help", "default", "choices")

    def __init__(self, name, kind, unit, help, default=REQUIRED, choices=None):
        if kind not in PARAMETER_KINDS:
            raise ValueError(f"kind must be one of {PARAMETER_KINDS}, got {kind!r}")
        if (kind == "choice") != (choices is not None):
            raise ValueError("choices are given exactly for kind 'choice'")
        self.name, self.kind, self.unit, self.help = name, kind, unit, help
        self.default, self.choices = default, None if choices is None else tuple(choices)

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    @property
    def option(self) -> str:
        return "--" + self.name.replace("_", "-")

    def __repr__(self):
        return f"Parameter({self.name!r}, {self.kind!r}, {self.unit!r})"


#: a coordinate beyond this magnitude lies out of reach of every admissible design
#: (lengths are at most ``validation.LENGTH_MAX``); it is treated as NaN, so that
#: squares and products of it cannot overflow
POINT_MAX = 1e3 * _v.LENGTH_MAX


#: read-only float arrays already found within :data:`POINT_MAX` (no NaN), by identity:
#: ``id -> weak reference``, an entry leaving with its array. A design evaluation hands
#: the task's samples to a dozen kinematic calls, each of which would check them again
#: (two reductions a call: a tenth of a search evaluation).
_IN_REACH = {}


def mark_in_reach(*arrays):
    """Check the read-only float arrays ``arrays`` once: those within
    :data:`POINT_MAX` (every coordinate finite) are passed on unchecked by
    :func:`as_points` from then on, while they live.

    Parameters
    ----------
    *arrays : ndarray
        Read-only float64 arrays (the task's samples of an evaluation); a writeable one
        is not marked (it could change after the check).
    """
    for v in arrays:
        if (type(v) is np.ndarray and v.dtype == np.float64 and not v.flags.writeable
                and (not v.size or (v.max() <= POINT_MAX and v.min() >= -POINT_MAX))):
            key = id(v)
            _IN_REACH[key] = weakref.ref(v, lambda _, key=key: _IN_REACH.pop(key, None))


def _within_reach(v):
    """``v`` (a float array) with the coordinates beyond :data:`POINT_MAX` set to NaN."""
    ref = _IN_REACH.get(id(v))
    if ref is not None and ref() is v:  # checked when marked (mark_in_reach)
        return v
    if v.size == 1 and -POINT_MAX <= v.item() <= POINT_MAX:  # one point: no reductions
        return v
    if v.size and not (v.max() <= POINT_MAX and v.min() >= -POINT_MAX):  # NaN or far away
        v = np.where(np.abs(v) > POINT_MAX, np.nan, v)
    return v


def _coordinates(name, v):
    _v.real_array_dtype(name, np.asarray(v) if not hasattr(v, "dtype") else v)
    try:
        v = np.asarray(v, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be a number or an array of numbers, got {_v.show(v)}") from None
    return _within_reach(v)


def as_points(x, y):
    """Broadcast ``x`` and ``y`` to float arrays of a common shape (coordinates
    beyond :data:`POINT_MAX` become NaN: unreachable).

    Parameters
    ----------
    x : array_like
        Abscissae of platform points [L] (base frame).
    y : array_like
        Ordinates [L]; broadcast with ``x``.

    Returns
    -------
    tuple of ndarray
        ``(x, y)`` as float arrays broadcast to one shape; coordinates beyond
        :data:`POINT_MAX` are NaN (unreachable).

    Raises
    ------
    ValueError
        When a coordinate is not numeric or ``x`` and ``y`` do not broadcast.
    """
    if (type(x) is np.ndarray and type(y) is np.ndarray and x.dtype == np.float64
            and y.dtype == np.float64 and x.shape == y.shape):
        # the kinematics pass their points on to one another: nothing to convert or
        # broadcast (a tenth of the time of a small design evaluation went here)
        return _within_reach(x), _within_reach(y)
    x = _coordinates("x", x)
    y = _coordinates("y", y)
    try:
        return np.broadcast_arrays(x, y)
    except ValueError:
        raise ValueError(
            f"x and y must broadcast to a common shape, got {x.shape} and {y.shape}"
        ) from None


class PlanarMechanism(ABC):
    """Abstract 2-DOF planar parallel mechanism (see the module docstring).

    Every member a mechanism has is declared here, with its contract; the contract
    suite (``tests/test_contract.py``) checks each on every implementation. A new
    mechanism is one module of :mod:`mechopt.mechanisms` defining a subclass with a
    ``cli_name``: :func:`mechopt.mechanisms.registry` finds it, and ``mechopt
    evaluate`` offers it with the options of its :attr:`parameters`; with a
    :attr:`design_spec`, ``mechopt design`` sizes it too.
    """

    #: name under ``mechopt evaluate`` (None: not offered there, e.g. a base class)
    cli_name: str | None = None
    #: one line for ``mechopt evaluate --help``
    cli_help: str = ""
    #: the inputs of :meth:`from_parameters` (declared, so the CLI is generated)
    parameters: tuple[Parameter, ...] = ()
    #: the options of :meth:`summary` (e.g. a quadrature)
    summary_options: tuple[Parameter, ...] = ()
    #: the keys of :meth:`summary`, in order
    summary_keys: tuple[str, ...] = ()
    #: ``{key: p}``: the number ``key`` of :meth:`summary` of the design scaled by ``D``
    #: (:meth:`scaled`) is ``D**p`` times the design's, so that
    #: :func:`mechopt.analysis.evaluate.evaluate` computes it in units of the design's size; None
    #: when the summary is not homogeneous in the lengths (then evaluated as given)
    summary_powers: dict | None = None
    #: True when the Liu 2006 indices over the MIC (a disk centred on the y axis)
    #: apply: the mechanism is symmetric about the y axis
    disk_indices: bool = False
    #: True when :meth:`explicit_workspace` gives the MIC explicitly (the symmetric
    #: five-bar; informational: :mod:`mechopt.analysis.workspace` asks the hook)
    explicit_mic: bool = False
    #: working modes (inverse-kinematics branches) the mechanism supports
    modes: tuple[str, ...] = ()
    #: assembly modes of the forward problem (``fk(q1, q2, assembly)``)
    assembly_modes: tuple[str, ...] = ASSEMBLY_MODES
    #: names of the two actuator coordinates, for tables and plots
    joint_names: tuple[str, str] = ("q1", "q2")
    #: True when the actuator coordinates are angles (reported in degrees)
    angular_joints: bool = False
    #: the working mode of this instance (one of :attr:`modes`)
    mode: str
    #: how ``mechopt design`` sizes the mechanism: a subclass of
    #: :class:`mechopt.core.design_spec.DesignSpec` (its variables, modes, construction
    #: in the task frame, size, joints, holes, reach, sketch), defined in the
    #: mechanism's own module; None: not offered by ``mechopt design``
    #: (:func:`mechopt.analysis.task.get_spec` lists those that are)
    design_spec: type | None = None
    #: what of the mechanism is perturbable (actuator errors, link lengths, base
    #: placement, joint clearances) and how it moves the pose: a subclass of
    #: :class:`mechopt.core.error_spec.ErrorSpec` defined in the mechanism's own module
    #: (:mod:`mechopt.analysis.accuracy` bounds the pose error with it); None: no model
    error_spec: type | None = None

    @classmethod
    def from_parameters(cls, **values) -> "PlanarMechanism":
        """The mechanism of the declared :attr:`parameters` (keyword values).

        Parameters
        ----------
        **values : 
            The declared :attr:`parameters` as keywords.

        Returns
        -------
        PlanarMechanism
            The mechanism.
        """
        return cls(**values)

    def parameter_values(self) -> dict:
        """``{name: value}`` of the declared :attr:`parameters` of this instance.

        Returns
        -------
        dict
            ``{name: value}``.
        """
        return {p.name: getattr(self, p.name) for p in self.parameters}

    def summary(self, **options) -> dict:
        """The mechanism's own global numbers (areas, means over its workspace) for
        ``mechopt evaluate``, as ``{name: float or str}`` with the keys
        :attr:`summary_keys`; options of :attr:`summary_options`. Default: none.
        The one entry point of a mechanism's numbers (:func:`mechopt.analysis.evaluate.evaluate`
        calls it).

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
        return {}

    @abstractmethod
    def with_mode(self, mode: str) -> "PlanarMechanism":
        """The same dimensions in another working mode (one of :attr:`modes`).

        Parameters
        ----------
        mode : str
            One of :attr:`modes`.

        Returns
        -------
        PlanarMechanism
            A new instance.
        """

    @abstractmethod
    def assembly_of(self, x, y):
        """Array of strings: the assembly mode (:attr:`assembly_modes`) of each pose,
        i.e. the ``fk`` solution that returns it.

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

    # --- to implement -------------------------------------------------------
    @abstractmethod
    def closure(self, x, y):
        """Return ``(A, b, reachable)`` of the differentiated closure equations.

        ``A`` has shape ``(..., 2, 2)``, ``b`` shape ``(..., 2)`` holds the diagonal
        of ``B``; both are NaN where ``reachable`` is False.

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

    @abstractmethod
    def ik(self, x, y):
        """Inverse kinematics in the mechanism's working mode: ``(q1, q2, reachable)``.

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

    @abstractmethod
    def fk(self, q1, q2, assembly):
        """Forward kinematics for one assembly mode: ``(x, y, valid)``.

        Parameters
        ----------
        q1 : array_like
            First actuator coordinate [rad or L].
        q2 : array_like
            Second actuator coordinate [rad or L]; broadcast with ``q1``.
        assembly : str
            One of :attr:`assembly_modes`.

        Returns
        -------
        x, y : ndarray
            The platform point [L]; NaN where invalid.
        valid : ndarray of bool
            Where the legs assemble in that mode.
        """

    @abstractmethod
    def reachable(self, x, y):
        """Boolean array: the point can be reached (all legs assemble).

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

    @abstractmethod
    def serial_clearance(self, x, y):
        """Signed distance from a point to the boundary of the reachable set
        (positive inside). Exact: the boundary is made of type-I loci.

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

    @abstractmethod
    def bounding_box(self):
        """``(xmin, xmax, ymin, ymax)`` enclosing every reachable point.

        Returns
        -------
        tuple of float
            ``(xmin, xmax, ymin, ymax)`` [L].
        """

    @property
    @abstractmethod
    def length_scale(self) -> float:
        """A characteristic length, used to set tolerances and grid steps."""

    @abstractmethod
    def scaled(self, factor: float) -> "PlanarMechanism":
        """The same mechanism with every length (links, strokes, offsets, task
        regions) multiplied by ``factor`` > 0, e.g. 1e-3 for mm -> m.

        Contract (checked on every case of the contract suite): the pose
        ``factor * p`` of the scaled mechanism has the same LCI and TQI as ``p``;
        areas scale as ``factor^2``; the Jacobian scales as ``1/factor`` for angular
        joints and is unchanged for prismatic ones (``q`` is then a length).

        Parameters
        ----------
        factor : float
            The scale factor, > 0.

        Returns
        -------
        PlanarMechanism
            A new instance.
        """

    def closure_enclosure(self, x, y, lengths=None):
        """Interval enclosure of :meth:`closure` over boxes of platform points (for the
        proven bounds of :mod:`mechopt.analysis.bounds`): ``(A, b, certain)`` with
        ``A[i][j]`` and ``b[i]`` :class:`~mechopt.core.interval.Interval` arrays that
        contain the exact ``A`` and ``diag B`` of :meth:`closure` (same working and
        assembly mode, same row scaling) at every point of each box where ``certain``;
        ``certain`` False where some point of the box may be out of reach (there ``A``
        and ``b`` enclose nothing). Written from positions (no angles), each mechanism's
        argument and rounding in its implementation's docstring. With ``lengths``
        (``{parameter: interval}``, a tolerance box), the enclosure holds for every
        mechanism whose named lengths lie in their intervals (a mechanism that does not
        support it raises ValueError). Default None: no enclosure (the bounds then report
        none).

        Parameters
        ----------
        x : mechopt.core.interval.Interval
            Abscissae of the boxes [L] (base frame).
        y : mechopt.core.interval.Interval
            Ordinates [L]; same shape.
        lengths : dict, optional
            Declared length parameters as intervals [L] replacing the instance's.

        Returns
        -------
        tuple or None
            ``(A, b, certain)``: ``A`` a pair of pairs of intervals, ``b`` a pair of
            intervals, ``certain`` a bool array; or None.
        """
        return None

    def actuator_enclosure(self, x, y, lengths=None):
        """Interval enclosure of the actuator coordinates of :meth:`ik` over boxes of
        platform points (for the proven ranges of :mod:`mechopt.analysis.bounds`):
        ``(q, certain)`` with ``q = (q1, q2)`` :class:`~mechopt.core.interval.Interval`
        arrays that contain the exact (real-number) values of the formulas of :meth:`ik`
        (same working mode) at every point of each box where ``certain``; ``certain`` False
        where some point of the box may be out of reach or a coordinate may jump inside it
        (an angle's branch cut), there ``q`` encloses nothing. Each mechanism's argument
        and rounding in its implementation's docstring. ``lengths`` as for
        :meth:`closure_enclosure`. Default None: no enclosure (no proven ranges).

        Parameters
        ----------
        x : mechopt.core.interval.Interval
            Abscissae of the boxes [L] (base frame).
        y : mechopt.core.interval.Interval
            Ordinates [L]; same shape.
        lengths : dict, optional
            Declared length parameters as intervals [L] replacing the instance's.

        Returns
        -------
        tuple or None
            ``((q1, q2), certain)`` [rad or L], or None.
        """
        return None

    def zoom_kernel(self, quantity):
        """The compiled zoom of :mod:`mechopt.core.zoom` for ``quantity`` at this
        mechanism's lengths: ``"lci"`` (:meth:`lci` of :meth:`jacobian`) or ``"type2"``
        (:meth:`type2_function`), minima by :func:`~mechopt.core.zoom.zoom_minimum`;
        ``"box"`` (the per-actuator speed and force factors of :meth:`jacobian`,
        :func:`~mechopt.core.indices.box_rows_of_matrix`, a row per
        :meth:`~mechopt.core.zoom.ZoomKernel.with_row`), minima too; ``"ik"`` (the two
        actuator coordinates of :meth:`ik`), ranges by
        :func:`~mechopt.core.zoom.zoom_ranges`; as a :class:`~mechopt.core.zoom.ZoomKernel`
        whose searches give the NumPy searches' results bit for bit. None where the
        mechanism has none (default), for an unknown quantity, or when the compiled
        twins do not run (:meth:`mechopt.core.jit.Twin.compiled`).

        Parameters
        ----------
        quantity : str
            ``"lci"``, ``"type2"``, ``"box"`` or ``"ik"``.

        Returns
        -------
        mechopt.core.zoom.ZoomKernel or None
            The compiled search, or None.
        """
        return None

    def _length_intervals(self, names, lengths):
        """``{name: value}`` of this mechanism's lengths ``names`` (its attributes), those
        in ``lengths`` (a :meth:`closure_enclosure`'s intervals) replacing them; ValueError
        for a name not among them."""
        lengths = dict(lengths or {})
        unknown = set(lengths) - set(names)
        if unknown:
            raise ValueError(f"{type(self).__name__} has no length {sorted(unknown)[0]!r} (it has {', '.join(names)})")
        return {n: lengths.get(n, getattr(self, n)) for n in names}

    @property
    def joint_limits(self):
        """``((q1_lo, q1_hi), (q2_lo, q2_hi))``: the actuator ranges, or None for a
        mechanism whose joints turn freely (the five-bar's cranks)."""
        return None

    def explicit_workspace(self):
        """Mechanism-specific workspace geometry for :mod:`mechopt.analysis.workspace`, or
        None. Default None: no explicit MIC, so :func:`~mechopt.analysis.workspace.mic`
        uses its generic ray method (root finding of :meth:`type2_function`), the usable
        region evaluates :meth:`type2_function` on the whole raster and the error
        messages name no condition on the inputs.

        A mechanism whose singular loci are known explicitly (the symmetric five-bar:
        :class:`mechopt.mechanisms.five_bar.mic.FiveBarWorkspace`) returns an object with

        * ``mic()``: ``(radius, center_y)`` [L] of the largest disk centred on the y
          axis (``center_y > 0``) free of singular points of the working mode; a
          radius of at most ``1e-9 * length_scale`` means there is none;
        * ``reach_filter()``: a function ``near(x, y)`` of arrays of points, False only
          where :meth:`type2_function` is certainly NaN (the raster skips those cells);
        * ``no_mic_reason()``: why there is no MIC, one clause in terms of the inputs;
        * ``step_text``: the default raster step ``length_scale/400`` in the inputs'
          terms, and ``radius_bound(step, given_step)``: the clause (starting ``"; "``)
          on the MIC radius that a raster of that step needs, for the message of a
          usable workspace too thin for its raster.
        """
        return None

    # --- derived once for every mechanism ------------------------------------
    def _within_strokes(self, q1, q2, rtol: float = _v.ROUNDING):
        """Actuator values inside ``self.joint_limits`` (for mechanisms with stroke
        limits), widened by ``rtol * length_scale`` so that a pose computed by
        ``fk`` from a limit value stays reachable despite rounding."""
        (lo1, hi1), (lo2, hi2) = self.joint_limits
        t = rtol * self.length_scale
        return (q1 >= lo1 - t) & (q1 <= hi1 + t) & (q2 >= lo2 - t) & (q2 <= hi2 + t)


    def jacobian(self, x, y):
        """``J = B^-1 A`` with ``q_dot = J p_dot``; shape ``(..., 2, 2)``, NaN where unreachable.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            ``J``, shape ``(..., 2, 2)`` [rad/L for cranks, dimensionless for sliders].
        """
        A, b, _ = self.closure(x, y)
        with np.errstate(divide="ignore", invalid="ignore"):
            return A / b[..., :, None]

    def type2_function(self, x, y):
        """``det A / (|a1| |a2|)``: the sine of the angle between the leg directions.

        Zero on the type-II locus and changes sign across it; NaN where unreachable.
        Dimensionless, so root finding needs no scale.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            The sine, in [-1, 1] (dimensionless).
        """
        A, _, _ = self.closure(x, y)
        det = A[..., 0, 0] * A[..., 1, 1] - A[..., 0, 1] * A[..., 1, 0]
        n1 = np.hypot(A[..., 0, 0], A[..., 0, 1])
        n2 = np.hypot(A[..., 1, 0], A[..., 1, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            return det / (n1 * n2)

    def singular_values(self, x, y):
        """``(s_max, s_min)`` of J at each point.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        s_max, s_min : ndarray
            The largest and smallest singular values of ``J`` (its unit); NaN where
            unreachable.
        """
        return _ix.singular_values(self.jacobian(x, y))

    def lci(self, x, y):
        """Local conditioning index ``1/kappa_J`` in [0, 1]; 0 where unreachable or singular.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            ``s_min / s_max`` of ``J`` (dimensionless, Liu 2006 eq. 3).
        """
        return _ix.lci(self.jacobian(x, y))

    def tqi(self, x, y):
        """Transmission quality index (Stan 2008 eq. 9); 0 where unreachable or singular.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            The TQI (dimensionless).
        """
        return _ix.tqi(self.jacobian(x, y))

    def velocity_extremes(self, x, y):
        """``(|V|max, |V|min)`` of Liu eq. (10).

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        v_max, v_min : ndarray
            ``(1/s_min, 1/s_max)``: the largest and smallest platform speed for unit
            actuator speeds [L/rad for cranks, dimensionless for sliders] (Liu 2006 eq.
            10).
        """
        return _ix.velocity_extremes(self.jacobian(x, y))

    def payload_extremes(self, x, y):
        """``(|tau|max, |tau|min)`` of Liu eq. (13).

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        tau_max, tau_min : ndarray
            ``(s_max, s_min)`` of ``J``: the largest and smallest platform force [N per
            unit actuator effort] (Liu 2006 eq. 13).
        """
        return _ix.payload_extremes(self.jacobian(x, y))

    def stiffness_extremes(self, x, y):
        """``(|D|max, |D|min)`` of Liu eq. (18) with unit actuator stiffness.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        d_max, d_min : ndarray
            ``(1/s_min^2, 1/s_max^2)``: the largest and smallest platform deflection for a
            unit force, ``K = J^T J`` with unit actuator stiffness (Liu 2006 eq. 16-18).
        """
        return _ix.stiffness_extremes(self.jacobian(x, y))

    def manipulability(self, x, y):
        """``sqrt(det(J^-1 J^-T)) = 1/|det J|`` (Yoshikawa), inf at type-II singularities.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        ndarray
            The manipulability [L^2/rad^2 for cranks].
        """
        return _ix.manipulability(self.jacobian(x, y))

    def local_indices(self, x, y) -> dict:
        """Every local index of :data:`mechopt.core.indices.LOCAL_INDEX_NAMES`.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.

        Returns
        -------
        dict
            ``{name: ndarray}``, one array per index.
        """
        return _ix.local_indices(self.jacobian(x, y))

    def raster_mean(self, local, step=None, cells: int = RASTER_CELLS) -> float:
        """Area mean of ``local(x, y)`` (e.g. ``self.tqi``) over the reachable set, by the
        mid-point rule on square cells of side ``step`` [L] (default: the smaller side
        of :meth:`bounding_box` / ``cells``); first-order error in ``step``. NaN when
        nothing is reachable.

        Parameters
        ----------
        local : callable
            ``local(x, y)`` -> array of the local quantity.
        step : float, optional
            Cell side [L].
        cells : int
            Cells along the smaller side of the box when ``step`` is None.

        Returns
        -------
        float
            The area mean of ``local`` over the reachable cells; NaN when none is reachable.

        Raises
        ------
        ValueError
            For a non-positive or non-finite ``step``.
        """
        from mechopt.core import validation as _v
        from mechopt.core.quadrature import grid_over

        box = self.bounding_box()
        if step is None:
            side = min(box[1] - box[0], box[3] - box[2])
            if not side > 0:
                return float("nan")
            step = side / cells
        grid = grid_over(box, _v.positive_length("step", step))
        X, Y = grid.points()
        mask = self.reachable(X, Y)
        if not np.any(mask):
            return float("nan")
        return grid.mean(local(X, Y), mask)

    def classify_singularity(self, x, y, tol: float = _v.RESOLUTION):
        """Array of strings: ``"none"``, ``"type-I"``, ``"type-II"``, ``"both"`` or
        ``"unreachable"``. Measures are made dimensionless: ``|B_ii|`` relative to
        ``|A_i| * length_scale`` and ``det A`` relative to ``|a1||a2|``.

        The type-I measure is compared squared: near a serial boundary it grows
        like the square root of the distance (a leg folding), so a pose on the
        boundary up to rounding has a measure of order sqrt(eps) ~ 1e-8.

        Parameters
        ----------
        x : array_like
            Abscissae of platform points [L] (base frame).
        y : array_like
            Ordinates [L]; broadcast with ``x``.
        tol : float
            The threshold of both dimensionless measures (default
            :data:`mechopt.core.validation.RESOLUTION`), >= 0.

        Returns
        -------
        ndarray of str
            The class of each point.

        Raises
        ------
        ValueError
            For a negative or non-finite ``tol``.
        """
        tol = _v.finite_number("tol", tol)
        if tol < 0.0:
            raise ValueError(f"tol must be >= 0, got {_v.show(tol)}")
        A, b, ok = self.closure(x, y)
        n = np.hypot(A[..., :, 0], A[..., :, 1])
        # B_ii / |a_i| has units of length for angular joints, none for sliders
        scale = self.length_scale if self.angular_joints else 1.0
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = np.any((b / (n * scale)) ** 2 <= tol, axis=-1)
        t2 = np.abs(self.type2_function(x, y)) <= tol
        out = np.full(np.shape(ok), "none", dtype=object)
        out[t1 & ~t2] = "type-I"
        out[t2 & ~t1] = "type-II"
        out[t1 & t2] = "both"
        out[~ok] = "unreachable"
        return out
