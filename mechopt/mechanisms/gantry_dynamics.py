"""Rigid-body dynamics of the Wu 2008 gantry: inertia matrices, kappa_D, eta_D, driving forces.

The motion profiles (:func:`trapezoidal_profile`, :func:`wu2008_trajectory`) live in
:mod:`mechopt.core.motion` and Wu's printed numbers (Table 2 inertias, Table 3 motion) in
``mechopt/data/wu2008.csv`` (:func:`mechopt.data.published_values`); both names stay
importable from here.

Model (Wu 2008 sec. 5, Table 2). Moving bodies of :class:`mechopt.Gantry`:

=====================  ===========  =====================================================
body                   parameters   motion
=====================  ===========  =====================================================
slider i (i = 1, 2)    m_i1         translates with ``(0, q_dot_i)``
link A_iB_i            m_i2, I_i2,  rotates by ``theta_i`` about ``B_i``; mass centre at
                       s_i2         ``B_i + s_i2 (sin theta_i, cos theta_i)``
counterweight i        m_i3         translates with ``(0, -q_dot_i)`` (eq. 23)
link A3B3              m4, I4, s4   parallelogram: moves with slider 1 and ``theta_1``
                                    (eq. 24), ``B3 = B1 + (0, l2)``
link A4B4 (optional)   m5, I5, s5   the extra link of the symmetric variant (sec. 6.3)
platform               mN           translates with ``(x_dot, y_dot)``
=====================  ===========  =====================================================

``I`` are moments of inertia about the slider joint ``B`` (Wu sec. 5.2), ``s`` the
distance from ``B`` to the mass centre. Table 2 prints no ``s_i2``: mechopt takes the
mass centre at mid-link, ``s = l/2`` (an assumption, stated in every output).

Inertia matrix. The printed matrix ``M`` of Wu eq. (41) is garbled in the available
text (signs, a non-symmetric last term), so mechopt derives it afresh from Lagrange's
equations with the platform coordinates ``p = (x, y)`` as generalized coordinates.
With ``t_i = tan theta_i``, ``q_dot_i = t_i x_dot + y_dot`` (eq. 4) and
``theta_dot_i = x_dot / (l cos theta_i)`` (eq. 3), a link about its slider joint has

    T = 1/2 m q_dot^2 - m s sin(theta) q_dot theta_dot + 1/2 I theta_dot^2,

so the kinetic energy is ``T = 1/2 p_dot^T M(p) p_dot`` with

    M = mN 1 + sum_i [ (a_i - 2 b_i) t_i^2 + g_i (1 + t_i^2)    (a_i - b_i) t_i ]
                     [ (a_i - b_i) t_i                           a_i             ]

    a_i = m_i1 + m_i3 + sum_links m,   b_i = sum_links m s / l,   g_i = sum_links I / l^2,

the sums running over the links carried by slider i (A1B1 and A3B3 on slider 1,
A2B2 and A4B4 on slider 2). This agrees term by term with the printed eq. (41) read
with consistent signs (``(1 - s/l) tan^2`` and ``(m s l sin^2 + I)/(l^2 cos^2)``
combine into ``(a - 2 b) t^2 + g (1 + t^2)``). ``M`` depends on ``x`` only. The
equations of motion are

    J^T tau = M p_ddot + x_dot (dM/dx) p_dot - 1/2 (p_dot^T (dM/dx) p_dot) e_x + G(p),

    G = g ( sum_i [ (w_i - b_i) t_i,  w_i ] + [0, mN] ),   w_i = m_i1 - m_i3 + sum_links m,

(gravity ``g = 9.8 m/s^2`` downward, Wu sec. 5.2), i.e. Wu eq. (41)
``tau = (J^T)^-1 M a + N``. With Table 2 the counterweights (half the moving mass
each) cancel the vertical gravity load exactly: ``G_y = 0``.

Dynamic manipulability (Wu sec. 6). The "inertia matrix" of eq. (42) is
``Lambda = (J^T)^-1 M`` (driving forces per unit platform acceleration, [kg]);
``kappa_D = sigma_2 / sigma_1`` (eq. 43) is its condition number and ``eta_D`` (eq. 44)
the area mean of ``kappa_D`` over the task workspace ``W_t``. ``kappa_D`` depends on
``x`` only.

Units: SI. The gantry must be given in metres (:func:`mechopt.mechanisms.gantry.wu2008_gantry`
with ``unit="m"``, or :meth:`Gantry.scaled`), masses in kg, inertias in kg m^2.

References
----------
Wu J, Wang J, Wang L, Shao H (2008), Proc. IMechE Part C 222,
doi:10.1243/09544062JMES830, sec. 5-6, eq. (3)-(4), (41)-(45), Tables 2-3.
Asada H (1983), J. Dyn. Syst. Meas. Control 105:131-135 (generalized inertia ellipsoid).
"""
from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core import validation as _v
from mechopt.data import published_values
from mechopt.core.protocol import as_points
from mechopt.core.quadrature import gauss_legendre
from mechopt.core.motion import trapezoidal_profile, wu2008_trajectory  # noqa: F401 (importable from here too)

__all__ = [
    "GantryInertia",
    "GantryDynamics",
    "ELLIPSE_KINDS",
    "rectangle_rule",
    "trapezoidal_profile",
    "wu2008_published",
    "wu2008_trajectory",
    "wu2008_driving_forces",
    "G_WU2008",
]

#: gravitational acceleration of Wu sec. 5.2 [m/s^2] (``mechopt/data/wu2008.csv``)
G_WU2008 = published_values("wu2008")[("table2", "g")][0]
ELLIPSE_KINDS = ("acceleration", "kinetic")


def wu2008_published() -> dict:
    """Rows of ``mechopt/data/wu2008.csv`` as ``{(design, quantity): (value, unit, digits, source)}``
    (:func:`mechopt.data.published_values`).

    Returns
    -------
    dict
        ``{(design, quantity): (value, unit, digits, source)}``.
    """
    return published_values("wu2008")


def _mass(name, value, unit="kg"):
    out = _v.finite_number(name, value)
    if out < 0.0:
        raise ValueError(f"{name} must be a non-negative finite value [{unit}], got {value!r}")
    return out


@dataclass(frozen=True)
class GantryInertia:
    """Masses [kg], inertias about the slider joints [kg m^2] and mass-centre offsets [m].

    Names follow Wu 2008 sec. 5.2 and Table 2: ``m_i1`` sliders, ``m_i2`` links
    ``A_iB_i``, ``m_i3`` counterweights, ``m4`` link ``A3B3``, ``mN`` platform,
    ``I_i2`` link inertias about ``B_i``, ``s_i2`` distance from ``B_i`` to the link's
    mass centre. ``I4``/``s4`` (link ``A3B3``) default to ``I12``/``s12`` (Wu eq. 36-37:
    it moves, and is taken to load the machine, like ``A1B1``). ``m5``, ``I5``, ``s5``
    describe the extra link ``A4B4`` of the symmetric variant (sec. 6.3), absent by
    default (``m5 = 0``; ``I5 = None`` then means no inertia, and ``I22`` when
    ``m5 > 0``). ``None`` offsets mean mid-link, ``l/2``. ``g`` [m/s^2] is the gravity.

    Assumptions where the paper is silent: each link's mass centre lies on the
    segment ``B_i A_i`` at ``s`` from ``B_i`` (the direction of eq. 1; the printed
    eq. 32-33 carry ``E [sin, -cos]``, a sign that contradicts eq. 1 and is not
    followed); ``A3B3`` loads slider 1 with ``A1B1``'s mass and inertia (eq. 36-37);
    counterweights hang at ``-q_i`` (eq. 23). The independent sympy derivation of
    ``tests/test_gantry_dynamics_independent.py`` checks ``M``, ``kappa_D``,
    ``eta_D`` and the Table 3 forces under these assumptions to 1e-9.

    Parameters
    ----------
    m11, m21 : float
        Slider masses [kg].
    m12, m22 : float
        Masses of the links ``A_iB_i`` [kg].
    m13, m23 : float
        Counterweight masses [kg].
    m4 : float
        Mass of the link ``A3B3`` [kg].
    mN : float
        Platform mass [kg].
    I12, I22 : float
        Link inertias about ``B_i`` [kg m^2].
    s12, s22 : float, optional
        Distances from ``B_i`` to the links' mass centres [m] (None: mid-link).
    I4, s4 : float, optional
        The same of ``A3B3`` (default: ``I12``, ``s12``).
    m5 : float
        Mass of the extra link ``A4B4`` of the symmetric variant [kg] (0: absent).
    I5, s5 : float, optional
        Its inertia [kg m^2] and offset [m].
    g : float
        Gravity [m/s^2].
    """

    m11: float
    m21: float
    m12: float
    m22: float
    m13: float
    m23: float
    m4: float
    mN: float
    I12: float
    I22: float
    s12: float | None = None
    s22: float | None = None
    I4: float | None = None
    s4: float | None = None
    m5: float = 0.0
    I5: float | None = None
    s5: float | None = None
    g: float = G_WU2008

    def __post_init__(self):
        units = {"I": "kg m^2", "s": "m", "g": "m/s^2"}
        for f in fields(self):
            v = getattr(self, f.name)
            if v is None and f.default is None:  # optional: derived from the others
                continue
            object.__setattr__(self, f.name, _mass(f.name, v, units.get(f.name[0], "kg")))

    @classmethod
    def wu2008(cls) -> "GantryInertia":
        """Wu 2008 Table 2 (from ``mechopt/data/wu2008.csv``); offsets at mid-link.

        Returns
        -------
        GantryInertia
            Table 2.
        """
        pub = published_values("wu2008")
        names = ("m11", "m21", "m12", "m22", "m13", "m23", "m4", "mN", "I12", "I22")
        kw = {k: pub[("table2", k)][0] for k in names}
        return cls(**kw, g=pub[("table2", "g")][0])

    @classmethod
    def wu2008_scaled(cls, l: float, l0: float) -> "GantryInertia":
        """Table 2 carried over to a machine whose links have length ``l`` [m]; ``l0`` [m]
        is the link length of the Table 1 design that Table 2 belongs to (eq. 15 at
        ``theta_1S = 10`` deg: ``1e-3 * dimensional_synthesis(500, 400, radians(10))[2]``).

        Table 2 belongs to the Table 1 design (``theta_1S = 10`` deg, ``l = l_0 =
        616.40`` mm); another ``theta_1S`` gives another ``l`` (eq. 14-15), for which
        Table 2's 11.3 kg m^2 can be below ``m (l/2)^2``, which no rigid body has. The
        law used here (an assumption, the paper has no other machine):

        * each link is a uniform plate of Table 2's mass per length: ``m(l) = m_0 l / l_0``
          (``m_0 = 80`` kg for ``A1B1``, ``A2B2``, ``A3B3``), mass centre at mid-link;
        * of the same cross-section, i.e. a plate of fixed width ``w``, central
          inertia ``m (l^2 + w^2) / 12``, with ``w`` fixed by Table 2 at ``l_0``:
          ``w^2 = 12 I_0 / m_0 - 4 l_0^2`` (``w = 0.419`` m), so that about the slider
          joint ``I(l) = m(l) (l^2 / 3 + w^2 / 12)`` and ``I(l_0) = I_0 = 11.3`` kg m^2;
        * sliders and platform do not depend on ``l`` (Table 2 values);
        * each counterweight is half the mass of all moving parts (Wu sec. 6.2),
          462 kg at ``l_0``.

        At ``l = l_0`` this is Table 2 (to rounding).

        Parameters
        ----------
        l : float
            The machine's link length [m].
        l0 : float
            The Table 1 design's link length [m].

        Returns
        -------
        GantryInertia
            The inertias.
        """
        l = _v.positive_length("l", l)
        l0 = _v.positive_length("l0", l0)
        base = cls.wu2008()
        k = l / l0
        w2 = {name: 12.0 * I0 / m0 - 4.0 * l0 * l0
              for name, m0, I0 in (("1", base.m12, base.I12), ("2", base.m22, base.I22))}
        m12, m22, m4 = base.m12 * k, base.m22 * k, base.m4 * k
        I12 = m12 * (l * l / 3.0 + w2["1"] / 12.0)
        I22 = m22 * (l * l / 3.0 + w2["2"] / 12.0)
        out = replace(base, m12=m12, m22=m22, m4=m4, I12=I12, I22=I22)
        half = 0.5 * out.moving_mass
        return replace(out, m13=half, m23=half)

    @property
    def moving_mass(self) -> float:
        """Mass of all moving parts except the counterweights [kg]."""
        return self.m11 + self.m21 + self.m12 + self.m22 + self.m4 + self.m5 + self.mN

    def symmetric_variant(self) -> "GantryInertia":
        """The symmetric machine of Wu sec. 6.3: a link ``A4B4`` makes the right chain a
        parallelogram too.

        Assumptions (the paper gives no numbers for it): the right slider, link and
        extra link copy the left ones (``m21 = m11``, ``m22 = m12``, ``I22 = I12``,
        ``s22 = s12``, ``m5 = m4``, ``I5 = I4``, ``s5 = s4``) and each counterweight is
        again half of all moving parts (the rule of sec. 6.2).

        Returns
        -------
        GantryInertia
            The variant's inertias.
        """
        sym = replace(self, m21=self.m11, m22=self.m12, I22=self.I12, s22=self.s12,
                      m5=self.m4, I5=self.I4 if self.I4 is not None else self.I12,
                      s5=self.s4 if self.s4 is not None else self.s12)
        half = 0.5 * sym.moving_mass
        return replace(sym, m13=half, m23=half)


def rectangle_rule(box, n: int = 48):
    """Tensor Gauss-Legendre nodes ``(x, y)`` and weights (sum 1) on ``box = (xmin, xmax, ymin, ymax)``.

    ``sum(w * f(x, y))`` is the area mean of ``f`` over the rectangle; exact for
    polynomials of degree ``2n - 1`` in each variable.

    Parameters
    ----------
    box : tuple of float
        ``(xmin, xmax, ymin, ymax)``.
    n : int
        Nodes per side.

    Returns
    -------
    x, y : ndarray
        The nodes.
    w : ndarray
        Weights summing to 1.
    """
    n = _v.integer("n", n, 1)
    xmin, xmax, ymin, ymax = _v.finite_numbers("box", box, 4, "(xmin, xmax, ymin, ymax)")
    g, gw = gauss_legendre(n)
    xs = 0.5 * (xmax - xmin) * g + 0.5 * (xmax + xmin)
    ys = 0.5 * (ymax - ymin) * g + 0.5 * (ymax + ymin)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    W = np.outer(gw, gw) / 4.0
    return X.ravel(), Y.ravel(), W.ravel()


class GantryDynamics:
    """Dynamics of a :class:`~mechopt.Gantry` (in metres) with :class:`GantryInertia`.

    See the module docstring for the model and the derivation of ``M``. All methods
    broadcast over arrays of platform positions; results are NaN where unreachable.

    Parameters
    ----------
    gantry : Gantry
        The machine, lengths in metres.
    inertia : GantryInertia
        Its masses and inertias.

    Raises
    ------
    ValueError
        One line, when ``gantry`` is not a :class:`~mechopt.Gantry` or ``inertia`` not a
        :class:`GantryInertia`.
    """

    def __init__(self, gantry, inertia: GantryInertia):
        if not (hasattr(gantry, "link_tangents") and hasattr(gantry, "column_x")):  # a mechopt.Gantry
            raise ValueError(f"gantry must be a mechopt.Gantry, got {type(gantry).__name__}")
        if not isinstance(inertia, GantryInertia):
            raise ValueError(
                f"inertia must be a mechopt.mechanisms.gantry_dynamics.GantryInertia, got {type(inertia).__name__}")
        self.gantry = gantry
        self.inertia = p = inertia
        l = gantry.l
        half = l / 2.0
        s12 = half if p.s12 is None else p.s12
        s22 = half if p.s22 is None else p.s22
        I4 = p.I12 if p.I4 is None else p.I4
        s4 = s12 if p.s4 is None else p.s4
        # A4B4 exists only in the symmetric variant (m5 > 0); absent, it has no inertia.
        # (Defaulting I5 to I22 for an absent link once put a phantom 11.3 kg m^2 on
        # slider 2 of the built machine: M_xx 1107.8 instead of 1063.0 kg at (0, 0.5) m.)
        I5 = (p.I22 if p.m5 > 0.0 else 0.0) if p.I5 is None else p.I5
        s5 = s22 if p.s5 is None else p.s5
        #: links per slider: (name, m, I about B, s)
        self.links = (
            (("A1B1", p.m12, p.I12, s12), ("A3B3", p.m4, I4, s4)),
            (("A2B2", p.m22, p.I22, s22), ("A4B4", p.m5, I5, s5)),
        )
        for leg in self.links:
            for name, m, I, s in leg:
                if s > l:
                    raise ValueError(f"mass-centre offset of link {name} must be <= l = {l!r}, got {s!r}")
                if m == 0.0 and I > 0.0:
                    raise ValueError(
                        f"inertia of link {name} must be 0 when its mass is 0 (a massless "
                        f"body has no inertia), got {I!r} kg m^2")
                if I < m * s * s * (1.0 - _v.ROUNDING):
                    raise ValueError(
                        f"inertia of link {name} about its slider joint must be >= m s^2 = "
                        f"{m * s * s!r} kg m^2 (non-negative central inertia), got {I!r}")
        self._coef = []
        for i, leg in enumerate(self.links):
            m_slider = (p.m11, p.m21)[i]
            m_cw = (p.m13, p.m23)[i]
            ml = sum(m for _, m, _, _ in leg)
            a = m_slider + m_cw + ml
            b = sum(m * s for _, m, _, s in leg) / l
            g = sum(I for _, _, I, _ in leg) / (l * l)
            w = m_slider - m_cw + ml
            self._coef.append((a, b, g, w))

    def __repr__(self):
        return f"GantryDynamics({self.gantry!r}, {self.inertia!r})"

    # --- kinematic helpers ---------------------------------------------------------
    def _tan(self, x, y):
        """``(t1, t2, c1, c2, ok)``: tan and ``l cos`` of the link angles, NaN where
        unreachable (:meth:`mechopt.Gantry.link_tangents`)."""
        return self.gantry.link_tangents(x, y)

    # --- inertia matrices --------------------------------------------------------------
    def mass_matrix(self, x, y):
        """Task-space inertia matrix ``M(p)`` [kg], shape ``(..., 2, 2)``: ``T = 1/2 p_dot^T M p_dot``.

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].

        Returns
        -------
        ndarray
            ``M`` [kg].
        """
        t1, t2, _, _, _ = self._tan(x, y)
        mN = self.inertia.mN
        Mxx = np.full(t1.shape, mN)
        Mxy = np.zeros(t1.shape)
        Myy = np.full(t1.shape, mN)
        for t, (a, b, g, _) in zip((t1, t2), self._coef):
            tt = t * t
            Mxx = Mxx + (a - 2.0 * b) * tt + g * (1.0 + tt)
            Mxy = Mxy + (a - b) * t
            Myy = Myy + a
        Myy = np.where(np.isnan(t1), np.nan, Myy)
        return np.stack([np.stack([Mxx, Mxy], -1), np.stack([Mxy, Myy], -1)], -2)

    def mass_matrix_dx(self, x, y):
        """``dM/dx`` [kg/m] (``M`` does not depend on ``y``), using ``d tan(theta)/dx = 1/(l cos^3 theta)``.

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].

        Returns
        -------
        ndarray
            ``dM/dx`` [kg/m].
        """
        t1, t2, c1, c2, _ = self._tan(x, y)
        l = self.gantry.l
        dxx = np.zeros(t1.shape)
        dxy = np.zeros(t1.shape)
        for t, c, (a, b, g, _) in zip((t1, t2), (c1, c2), self._coef):
            tx = l * l / (c * c * c)  # 1/(l cos^3) with c = l cos
            dxx = dxx + 2.0 * t * tx * (a - 2.0 * b + g)
            dxy = dxy + (a - b) * tx
        dyy = np.where(np.isnan(t1), np.nan, 0.0)
        return np.stack([np.stack([dxx, dxy], -1), np.stack([dxy, dyy], -1)], -2)

    def inertia_matrix(self, x, y):
        """``Lambda = (J^T)^-1 M`` of Wu eq. (42) [kg]: ``tau ~ Lambda a``.

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].

        Returns
        -------
        ndarray
            ``Lambda`` [kg], shape ``(..., 2, 2)``.
        """
        J = self.gantry.jacobian(x, y)
        M = self.mass_matrix(x, y)
        return _inv_t(J) @ M

    def kinetic_energy(self, x, y, xd, yd):
        """``1/2 p_dot^T M p_dot`` [J].

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].
        xd, yd : array_like
            Platform velocities [m/s].

        Returns
        -------
        ndarray
            [J].
        """
        M = self.mass_matrix(x, y)
        xd, yd = np.asarray(xd, float), np.asarray(yd, float)
        return 0.5 * (M[..., 0, 0] * xd * xd + 2 * M[..., 0, 1] * xd * yd + M[..., 1, 1] * yd * yd)

    # --- indices ----------------------------------------------------------------------
    def kappa_d(self, x, y):
        """``kappa_D = sigma_2 / sigma_1`` of ``(J^T)^-1 M`` (Wu eq. 43), >= 1; NaN where unreachable.

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].

        Returns
        -------
        ndarray
            ``kappa_D`` (dimensionless).
        """
        s_max, s_min = _ix.singular_values(self.inertia_matrix(x, y))
        with np.errstate(divide="ignore", invalid="ignore"):
            return s_max / s_min

    def kappa_d_map(self, region=None, n: int = 101):
        """``(X, Y, kappa_D)`` on an ``n x n`` grid of cell centres over ``region``
        (default the task workspace), for atlases such as Wu Fig. 6-7.

        Parameters
        ----------
        region : tuple of float, optional
            ``(xmin, xmax, ymin, ymax)`` [m] (default: the task workspace).
        n : int
            Cells per side.

        Returns
        -------
        X, Y : ndarray
            Cell centres [m].
        kappa_D : ndarray
            The index (dimensionless).
        """
        box = self._region(region)
        n = _v.integer("n", n, 1)
        xmin, xmax, ymin, ymax = box
        xs = xmin + (np.arange(n) + 0.5) * (xmax - xmin) / n
        ys = ymin + (np.arange(n) + 0.5) * (ymax - ymin) / n
        X, Y = np.meshgrid(xs, ys)
        return X, Y, self.kappa_d(X, Y)

    def eta_d(self, region=None, n: int = 48) -> float:
        """``eta_D`` of Wu eq. (44): area mean of ``kappa_D`` over ``region``
        (default the task workspace ``W_t``), by an ``n x n`` Gauss-Legendre rule.

        Parameters
        ----------
        region : tuple of float, optional
            ``(xmin, xmax, ymin, ymax)`` [m] (default: the task workspace).
        n : int
            Gauss-Legendre nodes per side.

        Returns
        -------
        float
            ``eta_D`` (dimensionless).

        Raises
        ------
        ValueError
            For an invalid region or node count.
        """
        x, y, w = rectangle_rule(self._region(region), n)
        k = self.kappa_d(x, y)
        if not np.all(np.isfinite(k)):
            raise ValueError("region must lie inside the reachable, non-singular set for eta_D")
        return float(np.sum(w * k))

    def eta_d_std(self, region=None, n: int = 48) -> float:
        """Area standard deviation of ``kappa_D`` over ``region``: mechopt's reading of
        the second global index the abstract announces (its formula is not printed).

        Parameters
        ----------
        region : tuple of float, optional
            ``(xmin, xmax, ymin, ymax)`` [m] (default: the task workspace).
        n : int
            Gauss-Legendre nodes per side.

        Returns
        -------
        float
            The standard deviation (dimensionless).

        Raises
        ------
        ValueError
            For an invalid region or node count.
        """
        x, y, w = rectangle_rule(self._region(region), n)
        k = self.kappa_d(x, y)
        if not np.all(np.isfinite(k)):
            raise ValueError("region must lie inside the reachable, non-singular set for eta_D")
        mean = np.sum(w * k)
        return float(np.sqrt(np.sum(w * (k - mean) ** 2)))

    def _region(self, region):
        if region is None:
            if self.gantry.task_workspace is None:
                raise ValueError("region must be given when the gantry has no task_workspace, got None")
            return self.gantry.task_workspace
        box = _v.finite_numbers("region", region, 4, "(xmin, xmax, ymin, ymax)")
        if not (box[0] < box[1] and box[2] < box[3]):
            raise ValueError(
                f"region must be (xmin, xmax, ymin, ymax) with xmin < xmax, ymin < ymax, got {_v.show(region)}")
        return box

    def inertia_ellipse(self, x, y, kind: str = "acceleration"):
        """Generalized inertia ellipse at each pose: ``(major, minor, angle)``.

        ``kind="acceleration"`` (Wu sec. 6.2, Fig. 5): the platform accelerations
        reachable with unit driving force, ``{a : |(J^T)^-1 M a| <= 1}``; semi-axes
        ``1/sigma_1`` (major, the direction easiest to accelerate) and ``1/sigma_2``
        [m/s^2 per N], so ``major/minor = kappa_D``. ``kind="kinetic"``: Asada's GIE
        ``{p_dot : p_dot^T M p_dot <= 1}``, semi-axes ``1/sqrt(eig M)`` [m/s per sqrt(J)].
        ``angle`` [rad] is the direction of the major axis from the x axis, in (-pi/2, pi/2].

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].
        kind : str
            ``"acceleration"`` or ``"kinetic"``.

        Returns
        -------
        major, minor : ndarray
            Semi-axes [m/s^2 per N, or m/s per sqrt(J)].
        angle : ndarray
            Direction of the major axis [rad].
        """
        kind = _v.choice("kind", kind, ELLIPSE_KINDS)
        if kind == "acceleration":
            L = self.inertia_matrix(x, y)
            S = np.swapaxes(L, -1, -2) @ L  # |L a|^2 = a^T S a
        else:
            S = self.mass_matrix(x, y)
        a, b, c = S[..., 0, 0], S[..., 0, 1], S[..., 1, 1]
        half_tr = 0.5 * (a + c)
        r = np.hypot(0.5 * (a - c), b)
        lam_max, lam_min = half_tr + r, half_tr - r
        # eigenvector of lam_max at 0.5 atan2(2b, a - c); the major axis is the other one
        phi = 0.5 * np.arctan2(2.0 * b, a - c) + 0.5 * np.pi
        phi = np.where(phi > 0.5 * np.pi, phi - np.pi, phi)
        with np.errstate(divide="ignore", invalid="ignore"):
            return 1.0 / np.sqrt(lam_min), 1.0 / np.sqrt(lam_max), phi

    # --- forces -----------------------------------------------------------------------
    def gravity(self, x, y):
        """Generalized gravity force ``G = dV/dp`` [N], shape ``(..., 2)``.

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].

        Returns
        -------
        ndarray
            ``G`` [N].
        """
        t1, t2, _, _, _ = self._tan(x, y)
        g = self.inertia.g
        Gx = np.zeros(t1.shape)
        Gy = np.full(t1.shape, self.inertia.mN)
        for t, (a, b, gg, w) in zip((t1, t2), self._coef):
            Gx = Gx + (w - b) * t
            Gy = Gy + w
        Gy = np.where(np.isnan(t1), np.nan, Gy)
        return g * np.stack([Gx, Gy], -1)

    def bias(self, x, y, xd, yd):
        """Centrifugal and Coriolis terms ``x_dot M_x p_dot - 1/2 (p_dot^T M_x p_dot) e_x`` [N].

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].
        xd, yd : array_like
            Platform velocities [m/s].

        Returns
        -------
        ndarray
            [N], shape ``(..., 2)``.
        """
        Mx = self.mass_matrix_dx(x, y)
        xd, yd = np.asarray(xd, float), np.asarray(yd, float)
        v = np.stack(np.broadcast_arrays(xd, yd), -1)
        Mv = (Mx @ v[..., None])[..., 0]
        quad = np.sum(v * Mv, axis=-1)
        out = xd[..., None] * Mv
        out[..., 0] -= 0.5 * quad
        return out

    def driving_forces(self, x, y, xd, yd, xdd, ydd, gravity: bool = True):
        """Slider forces ``tau = (F1, F2)`` [N] along ``+q`` (Wu eq. 41): ``J^-T (M a + h + G)``.

        ``gravity=False`` drops ``G`` (the paper includes it, eq. 30-38).

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].
        xd, yd : array_like
            Platform velocities [m/s].
        xdd, ydd : array_like
            Platform accelerations [m/s^2].
        gravity : bool
            Include gravity.

        Returns
        -------
        ndarray
            ``(F1, F2)`` [N], shape ``(..., 2)``.
        """
        x, y = as_points(x, y)
        M = self.mass_matrix(x, y)
        a = np.stack(np.broadcast_arrays(np.asarray(xdd, float), np.asarray(ydd, float)), -1)
        Q = (M @ a[..., None])[..., 0] + self.bias(x, y, xd, yd)
        if gravity:
            Q = Q + self.gravity(x, y)
        J = self.gantry.jacobian(x, y)
        tau = (_inv_t(J) @ Q[..., None])[..., 0]
        return tau[..., 0], tau[..., 1]

    # --- bodies (for checks and drawings) ------------------------------------------------
    def bodies(self, x, y):
        """Mass-centre positions and orientations of every body, from the geometry alone.

        Returns ``{name: (m, I_c, cx, cy, phi)}`` with ``I_c`` the central moment of
        inertia [kg m^2] and ``phi`` the rotation angle [rad] (``theta_i`` for links,
        0 for translating bodies). Counterweights hang at ``-q_i`` (a rope over a pulley
        at height 0). Used by the tests to check ``T`` and the power balance
        independently of :meth:`mass_matrix`.

        Parameters
        ----------
        x, y : array_like
            Platform positions [m].

        Returns
        -------
        dict
            ``{name: (m, I_c, cx, cy, phi)}`` [kg, kg m^2, m, m, rad].
        """
        x, y = as_points(x, y)
        g = self.gantry
        p = self.inertia
        q1, q2, ok = g.ik(x, y)
        th1, th2 = g.link_angles(x, y)
        ay = y - g.l2 / 2.0
        out = {}
        zero = np.zeros(x.shape)
        for i, (xb, q, th) in enumerate(zip(g.column_x, (q1, q2), (th1, th2))):
            ux, uy = (x - xb) / g.l, (ay - q) / g.l  # unit vector B_i -> A_i
            out[f"slider{i + 1}"] = ((p.m11, p.m21)[i], 0.0, np.full(x.shape, xb), q, zero)
            out[f"counterweight{i + 1}"] = ((p.m13, p.m23)[i], 0.0, np.full(x.shape, xb), -q, zero)
            for k, (name, m, I, s) in enumerate(self.links[i]):
                by = q + (g.l2 if k == 1 else 0.0)  # B3 (B4) is l2 above B1 (B2)
                out[name] = (m, I - m * s * s, xb + s * ux, by + s * uy, th)
        out["platform"] = (p.mN, 0.0, x, y, zero)
        return out


def _inv_t(J):
    """``(J^T)^-1`` of 2x2 matrices, NaN/inf where singular."""
    a, b, c, d = J[..., 0, 0], J[..., 0, 1], J[..., 1, 0], J[..., 1, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        det = a * d - b * c
        return np.stack([np.stack([d, -c], -1), np.stack([-b, a], -1)], -2) / det[..., None, None]


def wu2008_driving_forces(gantry, n: int = 651, inertia: GantryInertia | None = None) -> dict:
    """Driving forces of Wu Fig. 4 along :func:`wu2008_trajectory` (gravity included),
    for ``gantry`` in metres (Wu's: ``wu2008_gantry(10.0, unit="m")``) with Table 2
    inertias by default (links' mass centres at mid-link). Returns the trajectory dict
    plus ``F1``, ``F2`` [N].

    Parameters
    ----------
    gantry : Gantry
        The machine in metres.
    n : int
        Time samples.
    inertia : GantryInertia, optional
        Default: Table 2.

    Returns
    -------
    dict
        The trajectory (:func:`mechopt.core.motion.wu2008_trajectory`) with ``F1``, ``F2``
        [N].
    """
    dyn = GantryDynamics(gantry, GantryInertia.wu2008() if inertia is None else inertia)
    tr = wu2008_trajectory(n)
    F1, F2 = dyn.driving_forces(tr["x"], tr["y"], tr["xd"], tr["yd"], tr["xdd"], tr["ydd"])
    tr.update(F1=F1, F2=F2)
    return tr
