"""The error specification of a mechanism: what is perturbable and how it moves the pose.

Every mechanism ``mechopt design`` sizes closes its two legs on one platform point
``P``: leg ``i`` holds ``P`` on the circle of centre ``C_i`` and radius ``R_i``

* five-bar (symmetric or not): ``C_i = B_i`` the elbow, ``R_i`` the distal link;
* bipod: ``C_i = A_i`` the base joint, ``R_i = q_i`` the strut length;
* biglide, gantry: ``C_i = S_i = (g_i, q_i)`` the slider joint, ``R_i`` the link,

and the pose is the intersection of the two circles on the side of the line
``C_1 -> C_2`` the nominal pose lies on (its assembly mode). A mechanism declares in its
own module, as a subclass of :class:`ErrorSpec` set as its
:attr:`~mechopt.core.protocol.PlanarMechanism.error_spec`, the perturbable
quantities and ``C_i``, ``R_i`` as functions of the actuator coordinates and of
them (exact, for the Monte Carlo of :mod:`mechopt.analysis.accuracy`), their first
derivatives (analytic) and a bound on what the first order leaves out:

* :attr:`ErrorSpec.scalars` - ``(name, kind)`` of each scalar deviation, ``kind`` one of
  :data:`SCALAR_KINDS`: ``"actuator"`` (the coordinate ``q_i`` [rad or L]), ``"link"``
  (a link length [L]) or ``"base"`` (a coordinate of a base joint or guide [L]);
* :attr:`ErrorSpec.joints` - ``(name, legs)`` of each passive joint: its radial
  clearance is a vector ``delta`` [L] in a disk; the circle centre of each leg of
  ``legs`` moves by ``delta`` (the bore of one link about the pin of the other);
* :meth:`ErrorSpec.circles` - ``(c1x, c1y, r1, c2x, c2y, r2)`` [L] at actuator values
  ``q1, q2`` with the scalar deviations ``d`` (clearances apart: the generic code
  adds them);
* :meth:`ErrorSpec.circle_jacobian` - their derivatives with respect to the scalars,
  at zero deviation;
* :meth:`ErrorSpec.centre_curvature` - ``(k1, k2)`` [L]: bounds over the tolerance box
  of ``|C_i(d) - C_i(0) - dC_i/dd . d|``, the part of the centres the first order
  misses (0 where ``C_i`` is affine in the deviations; the radii are affine in all of
  them for every mechanism here).
"""
from __future__ import annotations

__all__ = ["ErrorSpec", "SCALAR_KINDS"]

#: the kinds of a scalar deviation: an actuator coordinate, a link length, a base coordinate
SCALAR_KINDS = ("actuator", "link", "base")


class ErrorSpec:
    """What of a mechanism is perturbable and how (module docstring). Stateless: the
    methods take the mechanism."""

    #: ``(name, kind)`` of every scalar deviation, kind in :data:`SCALAR_KINDS`
    scalars: tuple = ()
    #: ``(name, legs)`` of every passive joint with radial clearance; ``legs``: the leg
    #: indices (0, 1) whose circle centre its clearance vector moves
    joints: tuple = ()

    def check(self, mech) -> None:
        """ValueError when the error model does not cover this instance (default: all do).

        Parameters
        ----------
        mech : PlanarMechanism
            The mechanism.

        Raises
        ------
        ValueError
            One line, when the error model does not cover this instance.
        """

    def circles(self, mech, q1, q2, d):
        """``(c1x, c1y, r1, c2x, c2y, r2)`` [L], exact, at actuator values ``q1, q2`` with
        the scalar deviations ``d`` (``{name: array}``, a missing name is 0).

        Parameters
        ----------
        mech : PlanarMechanism
            The mechanism.
        q1 : array_like
            First actuator value [rad or L].
        q2 : array_like
            Second actuator value [rad or L].
        d : dict
            ``{name: array}`` of scalar deviations (a missing name is 0) [L or rad].

        Returns
        -------
        tuple of ndarray
            ``(c1x, c1y, r1, c2x, c2y, r2)`` [L].

        Raises
        ------
        NotImplementedError
            In the base class.
        """
        raise NotImplementedError(f"{type(self).__name__} declares no circles")

    def circle_jacobian(self, mech, q1, q2):
        """Array ``(..., 6, K)``: the derivatives of :meth:`circles`' six numbers with
        respect to the ``K`` scalars (order of :attr:`scalars`), at zero deviation.

        Parameters
        ----------
        mech : PlanarMechanism
            The mechanism.
        q1 : array_like
            First actuator value [rad or L].
        q2 : array_like
            Second actuator value [rad or L].

        Returns
        -------
        ndarray
            Shape ``(..., 6, K)``.

        Raises
        ------
        NotImplementedError
            In the base class.
        """
        raise NotImplementedError(f"{type(self).__name__} declares no circle derivatives")

    def centre_curvature(self, mech, q1, q2, half):
        """``(k1, k2)`` [L]: bounds over the box ``|d_k| <= half[k]`` of the distance of each
        circle centre from its first-order value. Default: 0 (affine centres).

        Parameters
        ----------
        mech : PlanarMechanism
            The mechanism.
        q1 : array_like
            First actuator value [rad or L].
        q2 : array_like
            Second actuator value [rad or L].
        half : dict
            ``{name: half width}`` of the tolerance box.

        Returns
        -------
        k1, k2 : float or ndarray
            The bounds [L].
        """
        return 0.0, 0.0
