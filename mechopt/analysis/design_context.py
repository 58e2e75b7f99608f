"""The sample context of one design evaluation: what every requirement and objective
of :mod:`mechopt.requirements` reads.

A :class:`DesignContext` holds the design's mechanism, the task's samples
(:func:`mechopt.analysis.sampling.samples`), the values several members need
(Jacobians, LCI, type-II function and serial clearance at the samples, each computed
once, on first use), whether minima are refined (:attr:`DesignContext.refine`, set
by the evaluator from the requirements' screens) and which requirements the samples
settle (:attr:`DesignContext.settled`: their minima stay unrefined), the searches of
:mod:`mechopt.analysis.sampling` bound to this design, and a memo through which two
members share a refined value.
"""
from __future__ import annotations

from functools import cached_property

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core.design_spec import DesignSpec
from mechopt.analysis import sampling as _s

__all__ = ["DesignContext"]


class DesignContext:
    """One design's evaluation context (module docstring).

    Parameters
    ----------
    spec : DesignSpec
        The mechanism's design spec.
    mech, check : PlanarMechanism
        The design's mechanism in the task frame (:meth:`DesignSpec.to_mech` maps task
        points into its frame); ``check`` the one whose serial clearance bounds the reach
        (the mechanism itself, or with padded strokes for slider mechanisms).
    samples : dict
        The task's samples (:func:`mechopt.analysis.sampling.samples`).
    req : Requirements
        The checked requirements.
    objectives : tuple
        The chosen objectives' names.
    unit : str
        The task's length unit.
    diameter : float
        The task's diameter [L] (the scale of the normalised constraints).
    max_length : float
        The longest link allowed [L].
    derived : dict
        Derived values of the design (strokes, joint ranges, link angles).
    refine : bool
        Whether minima are refined by zooming (the sampling asks it and every active
        requirement's screen passes).
    settled : frozenset
        Names of the requirements the samples settle
        (:meth:`mechopt.requirements.base.Requirement.settled`, with a sampling that
        settles): their minima are not refined.
    """

    def __init__(self, spec, mech, check, samples, req, objectives, unit, diameter, max_length, derived,
                 refine=True, settled=frozenset()):
        self.spec, self.mech, self.check, self.samples = spec, mech, check, samples
        self.req, self.objectives, self.unit = req, objectives, unit
        self.diameter, self.max_length, self.derived = diameter, max_length, derived
        self.refine, self.settled = refine, settled
        self._memo = {}

    # --- the samples ------------------------------------------------------------------
    @property
    def task(self):
        """The task as placed for this evaluation."""
        return self.samples["task"]

    @property
    def is_region(self) -> bool:
        return self.task.is_region

    @property
    def n_boundary(self) -> int:
        """Number of boundary samples (the first ones of ``allx, ally``)."""
        return self.samples["bx"].size

    @property
    def _mechanism_frame(self) -> bool:
        """Task points are the mechanism's own (:meth:`to_mech` is the identity): its
        compiled zoom kernels, which take mechanism points, apply."""
        return type(self.spec).to_mech is DesignSpec.to_mech

    def to_mech(self, x, y):
        """Task points in the mechanism's frame.

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].

        Returns
        -------
        x, y : ndarray
            The points in the mechanism's frame [L].
        """
        return self.spec.to_mech(self.mech, x, y)

    # --- values at the samples, computed once --------------------------------------------
    @cached_property
    def clearance(self) -> np.ndarray:
        """Serial clearance of ``check`` at every sample [L], unreachable samples ``-D``."""
        s = self.samples
        return _s.bad_to(self.check.serial_clearance(*self.spec.to_mech(self.check, s["allx"], s["ally"])),
                         -self.diameter)

    @cached_property
    def type2_raw(self) -> np.ndarray:
        """The type-II function (sine of the angle between the legs) at every sample."""
        s = self.samples
        return self.mech.type2_function(*self.to_mech(s["allx"], s["ally"]))

    @cached_property
    def jacobian(self) -> np.ndarray:
        """The Jacobian ``q_dot = J p_dot`` at every sample, shape ``(N, 2, 2)``."""
        s = self.samples
        return self.mech.jacobian(*self.to_mech(s["allx"], s["ally"]))

    @cached_property
    def lci(self) -> np.ndarray:
        """LCI at every sample (0 where unreachable: :func:`mechopt.core.indices.lci` maps a
        NaN Jacobian to 0)."""
        return _ix.lci(self.jacobian)

    # --- searches over the task ------------------------------------------------------------
    def refines(self, name) -> bool:
        """Whether the minima of requirement ``name`` are refined: :attr:`refine`, unless
        the samples settle it (:attr:`settled`).

        Parameters
        ----------
        name : str
            A requirement's name.

        Returns
        -------
        bool
            True when its searches zoom.
        """
        return self.refine and name not in self.settled

    def region_min(self, f, vals, refine=None) -> float:
        """Minimum over the task of ``f(x, y)`` (values ``vals`` at the samples), refined
        when ``refine`` (default :attr:`refine`; :func:`mechopt.analysis.sampling.region_mins`).

        Parameters
        ----------
        f : callable
            ``f(x, y)`` -> values at task points.
        vals : ndarray
            ``f`` at the samples.
        refine : bool, optional
            Refine by zooming (default :attr:`refine`).

        Returns
        -------
        float
            The minimum.
        """
        return self.region_mins(lambda x, y: f(x, y)[None], vals[None], refine)[0]

    def quantity_min(self, quantity, vals, scale=1.0, bad=0.0, refine=None) -> float:
        """Minimum over the task of ``scale * q`` (non-finite values replaced by ``bad``)
        for the mechanism's quantity ``q``: ``"lci"`` (the LCI of its Jacobian) or
        ``"type2"`` (its type-II function), values ``vals`` at the samples: by the
        mechanism's compiled zoom where it has one
        (:meth:`~mechopt.core.protocol.PlanarMechanism.zoom_kernel`,
        :func:`mechopt.analysis.sampling.compiled_region_min`), else by
        :meth:`region_min`; the same minimum bit for bit.

        Parameters
        ----------
        quantity : str
            ``"lci"`` or ``"type2"``.
        vals : ndarray
            ``scale * q`` (``bad`` where not finite) at the samples.
        scale, bad : float
            The factor and the replacement of a non-finite value.
        refine : bool, optional
            Refine by zooming (default :attr:`refine`).

        Returns
        -------
        float
            The minimum.
        """
        refine = self.refine if refine is None else refine
        if refine and self._mechanism_frame:
            kernel = self.mech.zoom_kernel(quantity)
            both = None if kernel is None else _s.compiled_region_min(self.samples, kernel, scale, bad, vals)
            if both is not None:
                return min(both)  # region_mins' min(boundary, interior)
        raw = {"lci": lambda x, y: _ix.lci(self.mech.jacobian(x, y)), "type2": self.mech.type2_function}[quantity]
        return self.region_min(lambda x, y: _s.bad_to(scale * raw(*self.to_mech(x, y)), bad), vals, refine)

    def quantity_mins(self, quantity, F, vals, refine=None) -> list:
        """:meth:`region_mins` of ``F``, the rows of the mechanism's quantity
        ``quantity`` (``"box"``: the per-actuator speed and force factors of its Jacobian,
        :func:`mechopt.core.indices.box_rows_of_matrix`), each row by the mechanism's
        compiled zoom where it has one (:meth:`quantity_min`), the same minima bit for bit.

        Parameters
        ----------
        quantity : str
            The quantity ``F`` computes.
        F : callable
            ``F(x, y)`` -> shape ``(m, N)``.
        vals : ndarray
            ``F`` at the samples.
        refine : bool, optional
            Refine by zooming (default :attr:`refine`).

        Returns
        -------
        list of float
            The minimum of each row.
        """
        refine = self.refine if refine is None else refine
        kernel = self.mech.zoom_kernel(quantity) if refine and self._mechanism_frame else None
        if kernel is not None:
            rows = [_s.compiled_region_min(self.samples, kernel.with_row(r), 1.0, 0.0, v) for r, v in enumerate(vals)]
            if all(b is not None for b in rows):
                return [min(b) for b in rows]  # region_mins' min(boundary, interior)
        return self.region_mins(F, vals, refine)

    def region_mins(self, F, vals, refine=None) -> list:
        """Minima over the task of the rows of ``F(x, y)`` (values ``vals`` at the samples).

        Parameters
        ----------
        F : callable
            ``F(x, y)`` -> shape ``(m, N)``.
        vals : ndarray
            ``F`` at the samples.
        refine : bool, optional
            Refine by zooming (default :attr:`refine`).

        Returns
        -------
        list of float
            The minimum of each row.
        """
        return _s.region_mins(self.samples, F, self.refine if refine is None else refine, vals)

    def leg_ranges(self, legs, bad=(np.inf, np.inf), refine=None) -> list:
        """Ranges over the task's boundary of the two values of ``legs(x, y)``
        (:func:`mechopt.analysis.sampling.leg_ranges`).

        Parameters
        ----------
        legs : callable
            ``legs(x, y) -> (v1, v2)``: one value per leg (actuator or link angle).
        bad : tuple of float
            Replacements of NaN for the minimum and the maximum.
        refine : bool, optional
            Refine by zooming (default :attr:`refine`).

        Returns
        -------
        list of tuple
            ``[(lo1, hi1), (lo2, hi2)]``.
        """
        return _s.leg_ranges(self.samples, legs, self.refine if refine is None else refine, bad)

    def joint_ranges(self, refine=None) -> list:
        """The crank ranges over the task's boundary (:meth:`leg_ranges` of
        :meth:`~mechopt.core.protocol.PlanarMechanism.ik`); unrefined ones are computed once.

        Parameters
        ----------
        refine : bool, optional
            Refine by zooming (default :attr:`refine`).

        Returns
        -------
        list of tuple
            ``[(lo1, hi1), (lo2, hi2)]`` [rad].
        """
        def angles(x, y):
            return self.mech.ik(*self.to_mech(x, y))

        if self.refine if refine is None else refine:
            kernel = self.mech.zoom_kernel("ik") if self._mechanism_frame else None
            return _s.leg_ranges(self.samples, angles, True, kernel=kernel)
        return self.memo("joint_ranges_sampled", lambda: self.leg_ranges(angles, refine=False))

    # --- sharing between members -----------------------------------------------------------
    def memo(self, key, compute):
        """``compute()``, computed once per evaluation under ``key``.

        Parameters
        ----------
        key : str
            The value's name.
        compute : callable
            ``compute()`` -> the value.

        Returns
        -------
        object
            The value.
        """
        if key not in self._memo:
            self._memo[key] = compute()
        return self._memo[key]

    def has(self, key) -> bool:
        """True when a member computed the value ``key`` (:meth:`memo`).

        Parameters
        ----------
        key : str
            A memo key.

        Returns
        -------
        bool
            Whether it was computed.
        """
        return key in self._memo
