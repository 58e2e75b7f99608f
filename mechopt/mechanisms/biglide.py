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
the default. Mode ``"--"`` is always in the assembly ``"up"`` (``P`` above the line
``S2 -> S1``), ``"++"`` always ``"down"``; the mixed modes change assembly across
their type-II line ``x = 0``.

The Biglide is the two-slider topology of :mod:`mechopt.mechanisms.sliders` with the
reported point at the links' joint (no platform offset): the closure
(``J`` rows ``(tan theta_i, 1)``, Wu eq. 4), the singularities (type I on
``x = +/-(L2 - L1)``, type II on ``x = 0`` in the mixed modes), the forward kinematics,
the exact workspace area and GTQI and Wu's velocity output ratio are derived there.
The other boundaries of the workspace are stroke limits (arcs of radius ``L2``
around ``(g_i, q_i_min)`` and ``(g_i, q_i_max)``); ``J`` is regular there.
``J`` depends on ``x`` only, so every local index is constant along y (Stan Fig. 30).

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

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.protocol import Parameter, as_points
from mechopt.mechanisms.sliders import ASSEMBLY_MODES, GTQI_METHODS, GuideDesignSpec, TwoSliderMechanism

__all__ = ["Biglide", "BiglideDesignSpec", "MODES", "ASSEMBLY_MODES", "GTQI_METHODS", "SUMMARY_KEYS"]

MODES = ("--", "++", "+-", "-+")


def _stroke(name_min, q_min, name_max, q_max):
    return _v.stroke(name_min, q_min, name_max, q_max, positive=False)


class BiglideDesignSpec(GuideDesignSpec):
    """``mechopt design biglide``: the lengths ``l1`` (half the guide distance) and ``l2``
    (the links) [L], ``l2 > l1``, the modes :data:`MODES` (default ``"--"``); the
    strokes are the ranges of ``q1``, ``q2`` over the task."""

    name = "biglide"
    lengths = ("l1", "l2")
    guide, link = "l1", "l2"
    modes, default_mode = MODES, "--"

    def raw(self, v, mode):
        """The design with placeholder strokes (its inverse kinematics ignores them).

        Parameters
        ----------
        v : dict
            The design's lengths [L].
        mode : str
            A working mode.

        Returns
        -------
        Biglide
            The mechanism.
        """
        return Biglide(v["l1"], v["l2"], -1.0, 1.0, mode=mode)

    def positions(self, v, mode, x, y):
        return self.raw(v, mode).slider_positions(x, y)

    def build(self, v, mode, strokes=None, pad=0.0):
        (a1, b1), (a2, b2) = strokes
        return Biglide(v["l1"], v["l2"], a1 - pad, b1 + pad, a2 - pad, b2 + pad, mode=mode)

    def size(self, mech, derived):
        """``2 l1 + 2 l2``: the guide distance and the two links (strokes reported apart).

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
        return 2.0 * (mech.l1 + mech.l2)


class Biglide(TwoSliderMechanism):
    """Biglide (PRRRP) ``Biglide(l1, l2, q1_min, q1_max, q2_min=None, q2_max=None, mode="--")``.

    See the module docstring for the kinematics, singularities and references.

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

    Raises
    ------
    ValueError
        One line, for non-positive lengths or an invalid stroke or mode.
    """

    cli_name = "biglide"
    design_spec = BiglideDesignSpec
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
    #: the keys of :meth:`summary`, in order
    summary_keys = ("workspace_area", "gtqi", "tqi_integral", "k_av_1", "k_av_2", "quadrature")
    #: areas scale as ``D^2``, the means and ratios not at all (prismatic actuators)
    summary_powers = {"workspace_area": 2, "gtqi": 0, "tqi_integral": 2, "k_av_1": 0, "k_av_2": 0}
    _closure_via_positions = True

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
        strokes = ((self.q1_min, self.q1_max), (self.q2_min, self.q2_max))
        self._set_sliders(self.l1, self.l2, True, mode, strokes,
                          (self.q1_max - self.q1_min, self.q2_max - self.q2_min), 0.0)

    def __repr__(self):
        return (
            f"Biglide(l1={self.l1!r}, l2={self.l2!r}, q1_min={self.q1_min!r}, "
            f"q1_max={self.q1_max!r}, q2_min={self.q2_min!r}, q2_max={self.q2_max!r}, "
            f"mode={self.mode!r})"
        )

    def with_mode(self, mode: str) -> "Biglide":
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
        return Biglide(self.l1, self.l2, self.q1_min, self.q1_max, self.q2_min, self.q2_max, mode)

    def scaled(self, factor: float) -> "Biglide":
        """Every length (``l1``, ``l2``, the stroke limits) multiplied by ``factor``
        (the Jacobian of these prismatic actuators is unchanged).

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
        return Biglide(self.l1 * f, self.l2 * f, self.q1_min * f, self.q1_max * f,
                       self.q2_min * f, self.q2_max * f, self.mode)

    def summary(self) -> dict:
        """Floats of :attr:`summary_keys` for ``mechopt evaluate biglide``.

        ``workspace_area`` [L^2] exact (Stan eq. 8, mode of the design); ``gtqi`` the
        area mean of the TQI (Stan eq. 9, 1-D quadrature, rel. error ~1e-10);
        ``tqi_integral`` [L^2] its numerator; ``k_av_1``, ``k_av_2`` Wu's eq. (7) over
        the whole x range (``inf`` when it contains that leg's guide, i.e. ``l2 >= 2 l1``);
        ``quadrature`` names the rule of the GTQI: ``"adaptive-1d"`` (exact area, adaptive
        1-D quadrature of the TQI's column integrals, relative tolerance 1e-10).

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
        w = self.workspace_area()
        ti = self.tqi_integral()
        return {
            "workspace_area": w,
            "gtqi": ti / w if w > 0 else float("nan"),
            "tqi_integral": ti,
            "k_av_1": self.k_av(leg=1),
            "k_av_2": self.k_av(leg=2),
            "quadrature": "adaptive-1d",
        }

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
        L = self.l2
        q1, q2 = self.slider_positions(x, y)
        inside_terms, viol_terms = [], []
        for g, s, q, (qmin, qmax) in zip(self._g, self._s, (q1, q2), self.joint_limits):
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


#: the keys of :meth:`Biglide.summary`
SUMMARY_KEYS = Biglide.summary_keys
