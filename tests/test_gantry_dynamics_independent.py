"""Independent check of the Wu 2008 gantry dynamics (``mechopt.mechanisms.gantry_dynamics.GantryDynamics``).

What is derived here, with sympy, from the geometry alone (no use of
``GantryDynamics.links``, ``.bodies``, ``._coef``, ``._tan`` or any private helper;
only the public gantry parameters ``d1``, ``l``, ``l2`` and the public fields of
``GantryInertia``):

* Kinematics (Wu 2008 eq. 1-2): sliders ``B1 = (-d1, q1)``, ``B2 = (d1, q2)``;
  platform reference point ``O' = (x, y)``; the "--" branch
  ``q_i = y - l2/2 - sqrt(l^2 - (x - x_Bi)^2)``, so ``sin th_i = (x - x_Bi)/l`` and
  ``cos th_i = (y - l2/2 - q_i)/l > 0``, ``th_i = asin((x - x_Bi)/l)``. The actuator
  Jacobian ``J = dq/dp`` (``q_dot = J p_dot``) is obtained by differentiating this IK.
* Bodies, each as a mass-centre position (a sympy expression of ``p = (x, y)``), a
  central moment of inertia and a rotation angle:

  - slider i: mass ``m_i1`` at ``(x_Bi, q_i)``, translating;
  - counterweight i: mass ``m_i3`` at ``(x_Bi, -q_i)`` (velocity ``-q_dot_i``, Wu eq. 23;
    the height ``-q_i`` is the assumption of a rope over a pulley at height 0, it
    only matters for gravity, and only up to a constant);
  - link ``A_iB_i``: mass ``m_i2``, centre at ``B_i + s_i2 (sin th_i, cos th_i)``
    (ASSUMPTION: the mass centre is on the segment ``B_iA_i`` at distance ``s`` from
    ``B_i``; ``s = l/2`` when not given, Table 2 prints no offsets), rotating by ``th_i``,
    central inertia ``I_i2 - m_i2 s_i2^2`` (``I_i2`` is about ``B_i``, Wu sec. 5.2);
  - link ``A3B3`` (parallelogram ``A1B1B3A3``, Wu eq. 24, 36-37): the same motion as
    ``A1B1`` shifted up by ``l2``: centre ``B1 + (0, l2) + s4 (sin th_1, cos th_1)``,
    angle ``th_1``, mass ``m4``, inertia about ``B3`` ``I4`` (``I4``/``s4`` default to
    ``I12``/``s12``);
  - link ``A4B4`` (only the symmetric variant of Wu sec. 6.3; ABSENT when ``m5 = 0``,
    the built machine): like ``A2B2`` shifted up by ``l2``, mass ``m5``, ``I5``, ``s5``;
  - platform: mass ``mN`` at ``(x, y)``, translating (no rotation).

* ``T = sum 1/2 m |v_c|^2 + 1/2 I_c omega^2`` with ``v_c = (d r_c/d p) p_dot`` and
  ``omega = (d th/d p) p_dot``; ``M(p)`` = Hessian of ``T`` in ``p_dot`` (Wu eq. 41's
  ``M``, re-derived); ``V = g sum m y_c``; ``G = dV/dp``; Lagrange's equations
  ``Q = d/dt dT/dp_dot - dT/dp + dV/dp = M p_ddot + C(p, p_dot) p_dot + G`` (expanded
  symbolically, ``d/dt`` by the chain rule) and the slider forces along ``+q``:
  ``tau = J^-T Q`` (virtual work: ``tau . q_dot = Q . p_dot``; solved numerically).
* ``kappa_D`` = condition number ``sigma_max/sigma_min`` of ``(J^T)^-1 M`` (Wu eq. 42-43)
  and ``eta_D`` its area mean over the task rectangle (eq. 44), here by a 48 x 48
  Gauss-Legendre rule built with ``numpy.polynomial.legendre.leggauss``.

Everything is compared with the implementation to a relative tolerance of 1e-9, on
the Table 2 machine, on its symmetric variant and on random inertias (explicit
offsets, ``I >= m s^2``). Reference figures: ``M_xx(0, 0.5) = 1063.0 kg`` (an older
version gave 1107.8 kg by counting the inertia of the absent link ``A4B4``) and
``eta_D = 1.5585``.
"""
from __future__ import annotations

import numpy as np
import pytest
import sympy as sp  # in the ``test`` extra: a missing sympy must fail, not skip

from mechopt.mechanisms.gantry_dynamics import GantryDynamics, GantryInertia, wu2008_driving_forces
from mechopt.mechanisms.gantry import wu2008_gantry

RTOL = 1e-9
TASK = (-0.25, 0.25, 0.3, 0.7)  # task rectangle [m] (x_min, x_max, y_min, y_max)

#: order of the numeric parameters passed to the lambdified functions
PARAMS = ("d1", "l", "l2", "g", "m11", "m21", "m12", "m22", "m13", "m23", "m4", "m5", "mN",
          "I12", "I22", "I4", "I5", "s12", "s22", "s4", "s5")


# --- the independent symbolic model ----------------------------------------------------
class Model:
    """Lambdified ``M(p)``, ``Q(p, p_dot, p_ddot)``, ``G(p)`` and ``J(p)``."""

    def __init__(self):
        x, y, xd, yd, xdd, ydd = sp.symbols("x y xd yd xdd ydd", real=True)
        S = dict(zip(PARAMS, sp.symbols(PARAMS, positive=True)))
        d1, l, l2, g = S["d1"], S["l"], S["l2"], S["g"]
        p, pd, pdd = (x, y), sp.Matrix([xd, yd]), sp.Matrix([xdd, ydd])

        x_B = (-d1, d1)
        q = [y - l2 / 2 - sp.sqrt(l**2 - (x - xb) ** 2) for xb in x_B]  # eq. 2, '-' branch
        sin_t = [(x - xb) / l for xb in x_B]  # eq. 1
        cos_t = [(y - l2 / 2 - qi) / l for qi in q]  # eq. 1 (= sqrt(...)/l > 0)
        th = [sp.asin(s) for s in sin_t]

        links = (  # (slider index, shift of the joint B above the slider, m, I about B, s)
            (0, 0, S["m12"], S["I12"], S["s12"]),  # A1B1
            (0, l2, S["m4"], S["I4"], S["s4"]),  # A3B3, parallelogram
            (1, 0, S["m22"], S["I22"], S["s22"]),  # A2B2
            (1, l2, S["m5"], S["I5"], S["s5"]),  # A4B4, zero when absent
        )
        bodies = []  # (m, I_c, (cx, cy), angle)
        for i, (ms, mc) in enumerate(((S["m11"], S["m13"]), (S["m21"], S["m23"]))):
            bodies.append((ms, 0, (x_B[i], q[i]), 0))  # slider
            bodies.append((mc, 0, (x_B[i], -q[i]), 0))  # counterweight, -q_dot (eq. 23)
        for i, shift, m, I_B, s in links:
            c = (x_B[i] + s * sin_t[i], q[i] + shift + s * cos_t[i])
            bodies.append((m, I_B - m * s**2, c, th[i]))
        bodies.append((S["mN"], 0, (x, y), 0))  # platform, translating

        T = 0
        V = 0
        for m, Ic, (cx, cy), ang in bodies:
            v = sp.Matrix([cx, cy]).jacobian(p) * pd
            w = (sp.Matrix([ang]).jacobian(p) * pd)[0] if ang != 0 else 0
            T += sp.Rational(1, 2) * m * (v.T * v)[0] + sp.Rational(1, 2) * Ic * w**2
            V += g * m * cy
        M = sp.hessian(T, (xd, yd))
        dT_dpd = [sp.diff(T, v) for v in (xd, yd)]
        ddt = [sum(sp.diff(e, pj) * vj for pj, vj in zip(p, pd))
               + sum(sp.diff(e, vj) * aj for vj, aj in zip((xd, yd), pdd)) for e in dT_dpd]
        G = [sp.diff(V, pj) for pj in p]
        Q = [ddt[k] - sp.diff(T, p[k]) + G[k] for k in range(2)]
        J = sp.Matrix(q).jacobian(p)  # q_dot = J p_dot

        syms = tuple(S[k] for k in PARAMS)
        state = (x, y, xd, yd, xdd, ydd)
        self._M = _lamb((x, y) + syms, [M[0, 0], M[0, 1], M[1, 1]])
        self._G = _lamb((x, y) + syms, G)
        self._Q = _lamb(state + syms, Q)
        self._J = _lamb((x, y) + syms, [J[0, 0], J[0, 1], J[1, 0], J[1, 1]])
        # T must be a quadratic form in p_dot: every third derivative in (xd, yd) is
        # identically 0 (a polynomial of degree <= 2, by Taylor's theorem), and T and its
        # gradient vanish at p_dot = 0 (no constant and no linear part). The same test as
        # sympy.Poly(T, xd, yd) homogeneous of total degree 2, without expanding T over
        # all 21 parameters into a polynomial (25 of this fixture's 29 s)
        zero = {xd: 0, yd: 0}
        third = [sp.diff(T, *w) for w in ((xd, xd, xd), (xd, xd, yd), (xd, yd, yd), (yd, yd, yd))]
        self.T_is_quadratic_form = (all(d == 0 for d in third) and T.subs(zero) == 0
                                    and all(sp.diff(T, v).subs(zero) == 0 for v in (xd, yd))
                                    and any(sp.diff(T, v, 2) != 0 for v in (xd, yd)))
        self._T = _lamb(state[:4] + syms, [T])

    def mass_matrix(self, par, x, y):
        a, b, c = self._M(x, y, *par)
        return np.stack([np.stack([a, b], -1), np.stack([b, c], -1)], -2)

    def jacobian(self, par, x, y):
        a, b, c, d = self._J(x, y, *par)
        return np.stack([np.stack([a, b], -1), np.stack([c, d], -1)], -2)

    def gravity(self, par, x, y):
        return np.stack(self._G(x, y, *par), -1)

    def Q(self, par, x, y, xd, yd, xdd, ydd):
        return np.stack(self._Q(x, y, xd, yd, xdd, ydd, *par), -1)

    def forces(self, par, *state):
        """``tau = J^-T Q`` [N], shape ``(..., 2)``."""
        J = self.jacobian(par, state[0], state[1])
        Q = self.Q(par, *state)
        return np.linalg.solve(np.swapaxes(J, -1, -2), Q[..., None])[..., 0]

    def kappa_d(self, par, x, y):
        J = self.jacobian(par, x, y)
        L = np.linalg.inv(np.swapaxes(J, -1, -2)) @ self.mass_matrix(par, x, y)
        s = np.linalg.svd(L, compute_uv=False)
        return s[..., 0] / s[..., -1]


def _lamb(args, exprs):
    fns = [sp.lambdify(args, e, modules="numpy", cse=True) for e in exprs]

    def f(*vals):
        shape = np.broadcast_shapes(*(np.shape(v) for v in vals))
        return [np.broadcast_to(np.asarray(fn(*vals), float), shape) for fn in fns]

    return f


def params(gantry, p: GantryInertia):
    """Numeric parameters in :data:`PARAMS` order from the public fields.

    Defaults: ``s = l/2`` when ``None``; ``I4``/``s4`` as ``A1B1``; ``A4B4`` absent
    (no mass, no inertia) when ``m5 == 0``, otherwise ``I5``/``s5`` default to ``A2B2``.
    """
    l = gantry.l
    s12 = l / 2 if p.s12 is None else p.s12
    s22 = l / 2 if p.s22 is None else p.s22
    I4 = p.I12 if p.I4 is None else p.I4
    s4 = s12 if p.s4 is None else p.s4
    if p.m5 == 0.0:
        m5, I5, s5 = 0.0, 0.0, 0.0
    else:
        m5 = p.m5
        I5 = p.I22 if p.I5 is None else p.I5
        s5 = s22 if p.s5 is None else p.s5
    v = dict(d1=gantry.d1, l=l, l2=gantry.l2, g=p.g, m11=p.m11, m21=p.m21, m12=p.m12,
             m22=p.m22, m13=p.m13, m23=p.m23, m4=p.m4, m5=m5, mN=p.mN, I12=p.I12, I22=p.I22,
             I4=I4, I5=I5, s12=s12, s22=s22, s4=s4, s5=s5)
    return tuple(float(v[k]) for k in PARAMS)


def rel_mat(A, B):
    """Max over poses of ``max|A - B| / max|B|`` (entries of each 2x2 matrix / vector)."""
    A, B = np.asarray(A), np.asarray(B)
    ax = tuple(range(A.ndim - (2 if A.shape[-2:] == (2, 2) else 1), A.ndim))
    return float(np.max(np.max(np.abs(A - B), axis=ax) / np.max(np.abs(B), axis=ax)))


def rel(a, b):
    return float(np.max(np.abs(np.asarray(a) - b) / np.abs(b)))


# --- fixtures ------------------------------------------------------------------------
@pytest.fixture(scope="module")
def model():
    return Model()


@pytest.fixture(scope="module")
def gantry():
    return wu2008_gantry(10.0, unit="m")


@pytest.fixture(scope="module")
def poses():
    """(0, 0.5) first, then a 5 x 3 grid over the closed task rectangle (corners inset
    by 1e-9 m) and 8 seeded random points: 24 poses."""
    xs = np.linspace(TASK[0] + 1e-9, TASK[1] - 1e-9, 5)
    ys = np.linspace(TASK[2] + 1e-9, TASK[3] - 1e-9, 3)
    X, Y = np.meshgrid(xs, ys)
    rng = np.random.default_rng(2008)
    x = np.concatenate([[0.0], X.ravel(), rng.uniform(TASK[0], TASK[1], 8)])
    y = np.concatenate([[0.5], Y.ravel(), rng.uniform(TASK[2], TASK[3], 8)])
    return x, y


def _random_states(rng, n):
    x = rng.uniform(TASK[0], TASK[1], n)
    y = rng.uniform(TASK[2], TASK[3], n)
    xd, yd = rng.normal(0.0, 1.0, (2, n))
    xdd, ydd = rng.normal(0.0, 7.0, (2, n))
    return x, y, xd, yd, xdd, ydd


# --- the model itself ----------------------------------------------------------------
def test_model_sanity(model, gantry, poses):
    """T is a quadratic form equal to 1/2 p_dot^T M p_dot; own J matches the gantry's
    and has the rows (tan th_i, 1) of Wu eq. 4-5; M is positive definite."""
    assert model.T_is_quadratic_form
    par = params(gantry, GantryInertia.wu2008())
    x, y = poses
    xd, yd = np.random.default_rng(5).normal(0.0, 1.0, (2, x.size))
    (T,) = model._T(x, y, xd, yd, *par)
    M = model.mass_matrix(par, x, y)
    v = np.stack([xd, yd], -1)
    assert np.allclose(T, 0.5 * np.einsum("ni,nij,nj->n", v, M, v), rtol=1e-12, atol=0)
    J = model.jacobian(par, x, y)
    assert rel_mat(J, gantry.jacobian(x, y)) < RTOL
    # rows (tan th_i, 1) of Wu eq. 4-5, from the geometry directly
    t1 = (x + gantry.d1) / np.sqrt(gantry.l**2 - (x + gantry.d1) ** 2)
    assert np.allclose(J[:, 0, 0], t1, rtol=1e-12) and np.all(J[:, :, 1] == 1.0)
    assert np.all(np.linalg.eigvalsh(M) > 0)


# --- Table 2 machine -----------------------------------------------------------------
@pytest.fixture(scope="module")
def wu(gantry):
    return GantryDynamics(gantry, GantryInertia.wu2008())


def test_mass_matrix_reference_value(model, gantry, wu):
    par = params(gantry, GantryInertia.wu2008())
    M_own = model.mass_matrix(par, 0.0, 0.5)
    assert M_own[0, 0] == pytest.approx(1063.0, abs=0.05)  # not 1107.8 (phantom A4B4)
    assert M_own[1, 1] == pytest.approx(1848.0, rel=1e-12)  # sum of all masses, incl. counterweights
    M_imp = np.asarray(wu.mass_matrix(0.0, 0.5))
    assert M_imp.shape == (2, 2)
    assert M_imp[0, 0] == pytest.approx(1063.0, abs=0.05)
    assert rel_mat(M_imp, M_own) < RTOL


def test_mass_matrix_matches(model, gantry, wu, poses):
    x, y = poses
    par = params(gantry, GantryInertia.wu2008())
    M_imp = wu.mass_matrix(x, y)
    assert M_imp.shape == (x.size, 2, 2)
    err = rel_mat(M_imp, model.mass_matrix(par, x, y))
    print(f"max rel diff M: {err:.2e}")
    assert err < RTOL


def test_kappa_d_matches(model, gantry, wu, poses):
    x, y = poses
    par = params(gantry, GantryInertia.wu2008())
    k_own = model.kappa_d(par, x, y)
    assert np.all(k_own >= 1.0) and np.all(np.isfinite(k_own))
    err = rel(wu.kappa_d(x, y), k_own)
    print(f"max rel diff kappa_D: {err:.2e}")
    assert err < RTOL


def test_eta_d_matches(model, gantry, wu):
    n = 48
    u, w = np.polynomial.legendre.leggauss(n)
    xs = 0.5 * (TASK[1] - TASK[0]) * u + 0.5 * (TASK[1] + TASK[0])
    ys = 0.5 * (TASK[3] - TASK[2]) * u + 0.5 * (TASK[3] + TASK[2])
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    W = np.outer(w, w) / 4.0  # weights of the area mean (sum 1)
    par = params(gantry, GantryInertia.wu2008())
    eta_own = float(np.sum(W * model.kappa_d(par, X, Y)))
    assert eta_own == pytest.approx(1.5585, abs=5e-5)
    eta_imp = wu.eta_d()
    err = abs(eta_imp - eta_own) / eta_own
    print(f"eta_D own {eta_own:.10f} impl {eta_imp:.10f} rel diff {err:.2e}")
    assert err < RTOL


def test_gravity_and_bias_match(model, gantry, wu):
    rng = np.random.default_rng(41)
    x, y, xd, yd, _, _ = _random_states(rng, 20)
    par = params(gantry, GantryInertia.wu2008())
    G_own = model.gravity(par, x, y)
    # Table 2 counterweights are half the moving mass each: no vertical gravity load
    assert np.max(np.abs(G_own[:, 1])) < 1e-9 * np.max(np.abs(G_own[:, 0]))
    G_imp = wu.gravity(x, y)
    assert np.max(np.abs(G_imp - G_own)) <= RTOL * np.max(np.abs(G_own))
    z = np.zeros_like(x)
    par0 = par[:3] + (0.0,) + par[4:]  # g = 0: Q(p, p_dot, 0) = C(p, p_dot) p_dot
    C_own = model.Q(par0, x, y, xd, yd, z, z)
    assert rel_mat(wu.bias(x, y, xd, yd), C_own) < RTOL


def test_driving_forces_along_the_wu_trajectory(model, gantry):
    tr = wu2008_driving_forces(wu2008_gantry(10.0, unit="m"), n=61)
    state = [np.asarray(tr[k], float) for k in ("x", "y", "xd", "yd", "xdd", "ydd")]
    par = params(gantry, GantryInertia.wu2008())
    tau = model.forces(par, *state)
    F = np.stack([tr["F1"], tr["F2"]], -1)
    assert F.shape == tau.shape == (61, 2)
    peak = np.max(np.abs(tau))
    assert peak > 100.0  # forces are not trivially zero
    err = float(np.max(np.abs(F - tau)) / peak)
    print(f"max diff F / peak |F|: {err:.2e} (peak {peak:.3f} N)")
    assert err < RTOL
    # virtual work: tau . q_dot = Q . p_dot
    qd = (model.jacobian(par, state[0], state[1]) @ np.stack(state[2:4], -1)[..., None])[..., 0]
    Q = model.Q(par, *state)
    assert np.allclose(np.sum(tau * qd, -1), np.sum(Q * np.stack(state[2:4], -1), -1),
                       rtol=1e-12, atol=1e-9 * peak)


# --- symmetric variant (Wu sec. 6.3) -------------------------------------------------
def test_symmetric_variant(model, gantry, poses):
    inertia = GantryInertia.wu2008().symmetric_variant()
    assert inertia.m5 > 0.0
    dyn = GantryDynamics(gantry, inertia)
    par = params(gantry, inertia)
    x, y = poses
    assert rel_mat(dyn.mass_matrix(x, y), model.mass_matrix(par, x, y)) < RTOL
    k_own = model.kappa_d(par, x, y)
    assert rel(dyn.kappa_d(x, y), k_own) < RTOL
    # mirror symmetry x -> -x
    assert rel(model.kappa_d(par, -x, y), k_own) < RTOL
    assert rel(dyn.kappa_d(-x, y), dyn.kappa_d(x, y)) < RTOL
    # the extra link changes the machine: kappa_D differs from the built one off-centre
    k_built = model.kappa_d(params(gantry, GantryInertia.wu2008()), x, y)
    assert np.max(np.abs(k_built - k_own)) > 1e-3
    rng = np.random.default_rng(63)
    st = _random_states(rng, 20)
    F1, F2 = dyn.driving_forces(*st)
    tau = model.forces(par, *st)
    assert np.max(np.abs(np.stack([F1, F2], -1) - tau)) <= RTOL * np.max(np.abs(tau))


# --- random inertias ------------------------------------------------------------------
def _random_inertia(rng, l, with_a4b4):
    def link():
        m = rng.uniform(5.0, 150.0)
        s = rng.uniform(0.05, 0.95) * l
        I = m * s * s + rng.uniform(0.0, 1.0) * m * l * l / 12.0  # I_B = I_c + m s^2
        return m, I, s

    (m12, I12, s12), (m22, I22, s22), (m4, I4, s4), (m5, I5, s5) = (link() for _ in range(4))
    kw = dict(m11=rng.uniform(20, 400), m21=rng.uniform(20, 400), m12=m12, m22=m22,
              m13=rng.uniform(0, 600), m23=rng.uniform(0, 600), m4=m4, mN=rng.uniform(20, 400),
              I12=I12, I22=I22, s12=s12, s22=s22, I4=I4, s4=s4, g=rng.uniform(0.0, 12.0))
    if with_a4b4:
        kw.update(m5=m5, I5=I5, s5=s5)
    return GantryInertia(**kw)


@pytest.mark.parametrize("case", range(6))
def test_random_inertias(model, case):
    rng = np.random.default_rng(1000 + case)
    g = wu2008_gantry(15.0 if case % 3 == 2 else 10.0, unit="m")
    inertia = _random_inertia(rng, g.l, with_a4b4=case % 2 == 1)
    dyn = GantryDynamics(g, inertia)
    par = params(g, inertia)
    st = _random_states(rng, 25)
    x, y = st[0], st[1]
    assert rel_mat(dyn.mass_matrix(x, y), model.mass_matrix(par, x, y)) < RTOL
    assert rel(dyn.kappa_d(x, y), model.kappa_d(par, x, y)) < RTOL
    G_own = model.gravity(par, x, y)
    assert np.max(np.abs(dyn.gravity(x, y) - G_own)) <= RTOL * max(np.max(np.abs(G_own)), 1.0)
    F1, F2 = dyn.driving_forces(*st)
    tau = model.forces(par, *st)
    assert np.max(np.abs(np.stack([F1, F2], -1) - tau)) <= RTOL * np.max(np.abs(tau))
