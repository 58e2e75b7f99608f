"""Inverse dynamics of every mechanism against an independent sympy Lagrange derivation.

The derivation below is written from each mechanism's geometry as published (Le 2013
eq. 13-18 for the 5R, Stan 2008 eq. 5-6 for the Biglide and the Bipod, Wu 2008 eq. 1-2
for the gantry): the centres of mass and angles of the bodies as sympy expressions of
the platform point ``(x, y)``, ``T`` and ``V`` from them, Lagrange's equations in
``(x, y)`` by sympy differentiation and ``tau = (dq/dp)^-T Q``. It uses neither the
package's body frames nor its closure: only the body names (to hand the same masses to
:func:`mechopt.analysis.dynamics.mass_model`).
"""
from __future__ import annotations

import functools

import numpy as np
import pytest
import sympy as sp

from mechopt import Biglide, Bipod, FiveBar
from mechopt.analysis.dynamics import inverse_dynamics, mass_model
from mechopt.core.rigid_bodies import MassLaw
from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar
from mechopt.mechanisms.gantry import Gantry

X, Y, XD, YD, XDD, YDD = sp.symbols("x y xd yd xdd ydd", real=True)
GRAV = (0.7, -9.81)  # gravity with a component along x: any direction of the plane
def _seg(P, Q, f):
    return (P[0] + f * (Q[0] - P[0]), P[1] + f * (Q[1] - P[1]))


def _ang(P, Q):
    return sp.atan2(Q[1] - P[1], Q[0] - P[0])


#: the 5R's lengths and elbow signs as symbols: one derivation serves the symmetric and
#: the asymmetric five-bar (lambdified with their values)
FB = sp.symbols("a1 c1 a2 c2 r3 s1 s2", real=True)


def five_bar_geometry(a1, c1, a2, c2, r3, mode):
    """Le 2013 eq. (13)-(18): crank angles; bodies as (name, com, angle)."""
    values = dict(zip(FB, (a1, c1, a2, c2, r3, *(1 if ch == "+" else -1 for ch in mode))))
    a1, c1, a2, c2, r3, s1, s2 = FB
    d1 = sp.sqrt((X + r3) ** 2 + Y ** 2)
    d2 = sp.sqrt((X - r3) ** 2 + Y ** 2)
    th1 = sp.atan2(Y, X + r3) + s1 * sp.acos((a1 ** 2 + d1 ** 2 - c1 ** 2) / (2 * a1 * d1))
    th2 = sp.pi - sp.atan2(Y, r3 - X) + s2 * sp.acos((a2 ** 2 + d2 ** 2 - c2 ** 2) / (2 * a2 * d2))
    P = (X, Y)

    def bodies(mass):
        out = {}
        for i, (th, a, ax) in enumerate(((th1, a1, -r3), (th2, a2, r3)), 1):
            A = (ax, 0)
            B = (ax + a * sp.cos(th), a * sp.sin(th))
            out[f"crank{i}"] = (_seg(A, B, mass[f"crank{i}"]["com"]), th)
            out[f"distal{i}"] = (_seg(B, P, mass[f"distal{i}"]["com"]), _ang(B, P))
        out["payload"] = (P, None)
        return out
    return (th1, th2), bodies, values


def biglide_geometry(l1, l2, mode):
    """Stan 2008 eq. (5): q_i = y + s_i sqrt(L2^2 - (x - g_i)^2), g_1 = +L1."""
    s = [1 if ch == "+" else -1 for ch in mode]
    g = (l1, -l1)
    q = tuple(Y + s[i] * sp.sqrt(l2 ** 2 - (X - g[i]) ** 2) for i in range(2))

    def bodies(mass):
        out = {}
        for i in range(2):
            S = (g[i], q[i])
            out[f"carriage{i + 1}"] = (S, None)
            out[f"link{i + 1}"] = (_seg(S, (X, Y), mass[f"link{i + 1}"]["com"]), _ang(S, (X, Y)))
        out["payload"] = ((X, Y), None)
        return out
    return q, bodies, {}


def gantry_geometry(d1, l, l2, mode):
    """Wu 2008 eq. (1)-(2): q_i = y - l2/2 + s_i sqrt(l^2 - (x - x_Bi)^2), x_B1 = -d1."""
    s = [1 if ch == "+" else -1 for ch in mode]
    g = (-d1, d1)
    q = tuple(Y - l2 / 2 + s[i] * sp.sqrt(l ** 2 - (X - g[i]) ** 2) for i in range(2))

    def bodies(mass):
        A = (X, Y - l2 / 2)
        out = {}
        for i in range(2):
            B = (g[i], q[i])
            out[f"carriage{i + 1}"] = (B, None)
            out[f"counterweight{i + 1}"] = ((g[i], -q[i]), None)
            out[f"A{i + 1}B{i + 1}"] = (_seg(B, A, mass[f"A{i + 1}B{i + 1}"]["com"]), _ang(B, A))
        B3, A3 = (g[0], q[0] + l2), (X, Y + l2 / 2)
        out["A3B3"] = (_seg(B3, A3, mass["A3B3"]["com"]), _ang(B3, A3))
        out["platform"] = ((X, Y), None)
        return out
    return q, bodies, {}


def bipod_geometry(b, lengths):
    """Stan 2008 eq. (6): struts from A1 = (0, 0) and A2 = (b, 0); a cylinder pivoting
    at A_i, a rod fixed to P (its centre ``s`` back from P along the strut)."""
    A = ((0, 0), (b, 0))
    q = tuple(sp.sqrt((X - a[0]) ** 2 + Y ** 2) for a in A)

    def bodies(mass):
        out = {}
        for i in range(2):
            u = ((X - A[i][0]) / q[i], Y / q[i])
            ang = sp.atan2(Y, X - A[i][0])
            cl, rl = lengths[i]
            sc, sr = mass[f"cylinder{i + 1}"]["com"] * cl, mass[f"rod{i + 1}"]["com"] * rl
            out[f"cylinder{i + 1}"] = ((A[i][0] + sc * u[0], sc * u[1]), ang)
            out[f"rod{i + 1}"] = ((X - sr * u[0], Y - sr * u[1]), ang)
        out["payload"] = ((X, Y), None)
        return out
    return q, bodies, {}


def _dt(f):
    """Total time derivative along (x, y)(t)."""
    return sp.diff(f, X) * XD + sp.diff(f, Y) * YD + sp.diff(f, XD) * XDD + sp.diff(f, YD) * YDD


#: the masses, centres of mass and inertias as symbols (one derivation per geometry)
@functools.lru_cache(maxsize=None)
def _mass_symbols(names):
    return {n: {k: sp.Symbol(f"{n}_{k}", positive=True) for k in ("mass", "com", "inertia")}
            for n in names}


def lagrange(q, bodies, names):
    """(tau, qdot, (T + V, d(T + V)/dt)) as numeric functions of (x, y, xd, yd, xdd, ydd)
    and the parameters (the symbols of the geometry, of :func:`_mass_symbols` and the
    rotor's reflected inertia)."""
    mass = _mass_symbols(tuple(names))
    rotor = sp.Symbol("rotor", nonnegative=True)
    T, V = 0, 0
    for name, (c, ang) in bodies(mass).items():
        m = mass[name]["mass"]
        cd = [_dt(ci) for ci in c]
        T += sp.Rational(1, 2) * m * (cd[0] ** 2 + cd[1] ** 2)
        if ang is not None:
            T += sp.Rational(1, 2) * mass[name]["inertia"] * _dt(ang) ** 2
        V -= m * (GRAV[0] * c[0] + GRAV[1] * c[1])
    qd = [_dt(qi) for qi in q]
    T += sp.Rational(1, 2) * rotor * (qd[0] ** 2 + qd[1] ** 2)
    L = T - V
    Q = [_dt(sp.diff(L, v)) - sp.diff(L, p) for v, p in ((XD, X), (YD, Y))]
    Jm = sp.Matrix([[sp.diff(qi, X), sp.diff(qi, Y)] for qi in q])
    params = tuple(sorted((T + V).free_symbols - {X, Y, XD, YD}, key=str))
    args = (X, Y, XD, YD, XDD, YDD) + params
    fQ = sp.lambdify(args, Q, "numpy", cse=True)
    fJ = sp.lambdify(args, list(Jm), "numpy", cse=True)
    fqd = sp.lambdify(args, qd, "numpy", cse=True)
    fE = sp.lambdify(args, [T + V, _dt(T + V)], "numpy", cse=True)

    def bind(f, values):
        vals = [values[p] for p in params]
        return lambda *a: [np.broadcast_to(v, np.shape(a[0])) for v in f(*a, *vals)]

    def make(values):
        Qf, Jf, qdf, Ef = (bind(f, values) for f in (fQ, fJ, fqd, fE))

        def tau(*a):
            Qv = np.stack(Qf(*a), -1)
            Jv = np.stack(Jf(*a), -1).reshape(np.shape(a[0]) + (2, 2))
            return np.linalg.solve(np.swapaxes(Jv, -1, -2), Qv[..., None])[..., 0]
        return tau, qdf, Ef
    return make


def motions(center, R, T=0.8, n=41):
    """Three motions about ``center`` (radius ``R``) in closed form: a circle, a
    Lissajous figure, a straight line with a quintic time law."""
    t = np.linspace(0.0, T, n)
    w = 2 * np.pi / T
    cx, cy = center
    out = []
    out.append(dict(x=cx + R * np.cos(w * t), y=cy + R * np.sin(w * t), xd=-R * w * np.sin(w * t),
                    yd=R * w * np.cos(w * t), xdd=-R * w * w * np.cos(w * t), ydd=-R * w * w * np.sin(w * t)))
    out.append(dict(x=cx + R * np.sin(w * t), y=cy + 0.6 * R * np.sin(2 * w * t), xd=R * w * np.cos(w * t),
                    yd=1.2 * R * w * np.cos(2 * w * t), xdd=-R * w * w * np.sin(w * t),
                    ydd=-2.4 * R * w * w * np.sin(2 * w * t)))
    s = t / T
    h, hd, hdd = 10 * s**3 - 15 * s**4 + 6 * s**5, (30 * s**2 - 60 * s**3 + 30 * s**4) / T, (60 * s - 180 * s**2 + 120 * s**3) / T**2
    ex, ey = 2 * R * 0.8, -2 * R * 0.6
    out.append(dict(x=cx - R * 0.8 + ex * h, y=cy + R * 0.6 + ey * h, xd=ex * hd, yd=ey * hd, xdd=ex * hdd, ydd=ey * hdd))
    return out


def _masses(names, seed):
    rng = np.random.default_rng(seed)
    return {n: {"mass": float(rng.uniform(0.1, 2.0)), "com": float(rng.uniform(0.2, 0.8)),
                "inertia": float(rng.uniform(1e-4, 1e-2))} for n in names}


NAMES = {"five-bar": ("crank1", "distal1", "crank2", "distal2", "payload"),
         "biglide": ("carriage1", "link1", "carriage2", "link2", "payload"),
         "bipod": ("cylinder1", "rod1", "cylinder2", "rod2", "payload"),
         "gantry": ("carriage1", "carriage2", "A1B1", "A2B2", "A3B3", "counterweight1",
                    "counterweight2", "platform")}
GEOMETRY = {"five-bar": lambda *a: five_bar_geometry(*(a or (1, 1, 1, 1, 1, "++"))),
            "biglide": biglide_geometry, "bipod": bipod_geometry, "gantry": gantry_geometry}
CASES = {
    # name: (mechanism in [L], length_unit, (geometry, its arguments in metres), centre, radius [L])
    "five-bar": (lambda: FiveBar(250.0, 350.0, 100.0, "+-"), 1e-3,
                 ("five-bar", (0.25, 0.35, 0.25, 0.35, 0.1, "+-")), (0.0, 380.0), 90.0),
    "asymmetric-five-bar": (lambda: AsymmetricFiveBar(0.3, 0.45, 0.25, 0.5, 0.12, "-+"), 1.0,
                            ("five-bar", (0.3, 0.45, 0.25, 0.5, 0.12, "-+")), (0.02, 0.45), 0.1),
    "biglide": (lambda: Biglide(0.3, 0.5, -2.0, 2.0, mode="--"), 1.0,
                ("biglide", (0.3, 0.5, "--")), (0.05, 0.2), 0.1),
    "bipod": (lambda: Bipod(0.4, 0.25, 0.7, 0.3, 0.75), 1.0,
              ("bipod", (0.4, ((0.25, 0.45), (0.3, 0.45)))), (0.2, 0.4), 0.08),
    "gantry": (lambda: Gantry(0.35, 0.6, 0.9, q_min=-0.6, l2=0.2, mode="--"), 1.0,
               ("gantry", (0.35, 0.6, 0.2, "--")), (0.0, 0.25), 0.1),
}
ROTOR = {"five-bar": (2e-5, 12.0)}  # rotor inertia [kg m^2], gear ratio: reflected 2.88e-3


@functools.lru_cache(maxsize=None)
def _derivation(kind, args):
    q, bodies, values = GEOMETRY[kind](*args)
    return lagrange(q, bodies, NAMES[kind]), values


@functools.lru_cache(maxsize=None)
def _case(name):
    make, unit, (kind, args), center, R = CASES[name]
    mech = make()
    mass = _masses(NAMES[kind], seed=len(name))
    ri, gear = ROTOR.get(name, (0.0, 1.0))
    model = mass_model(mech, MassLaw(rotor_inertia=ri, gear_ratio=gear), mass, length_unit=unit)
    assert set(NAMES[kind]) <= {b.name for b in model.bodies}
    derive, values = _derivation(kind, () if kind == "five-bar" else args)
    if kind == "five-bar":
        values = five_bar_geometry(*args)[2]
    values = dict(values)
    for n, d in _mass_symbols(tuple(NAMES[kind])).items():
        for k, sym in d.items():
            values[sym] = mass[n][k]
    values[sp.Symbol("rotor", nonnegative=True)] = ri * gear ** 2
    return mech, unit, model, derive(values), center, R


#: the five-bar family's and the bipod's derivations take 20 s of sympy: behind ``slow``; the
#: fast test below checks their power balance against an energy computed in numpy
SLOW = {"five-bar", "asymmetric-five-bar", "bipod"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n
                                  for n in CASES])
def test_efforts_match_the_sympy_lagrange_derivation(name):
    mech, unit, model, (tau_ref, qd_ref, E_ref), center, R = _case(name)
    for m in motions(center, R):
        si = {k: v * unit for k, v in m.items()}
        out = inverse_dynamics(mech, m, model, gravity=GRAV, length_unit=unit)
        args = tuple(si[k] for k in ("x", "y", "xd", "yd", "xdd", "ydd"))
        tau = tau_ref(*args)
        assert np.all(np.isfinite(out["tau"]))
        peak = np.max(np.abs(tau))
        assert np.max(np.abs(out["tau"] - tau)) <= 1e-6 * peak, name
        # the power balance: sum tau_i qd_i = d(T + V)/dt of the independent energy
        qd = np.stack(qd_ref(*args), -1)
        np.testing.assert_allclose(out["qd"], qd, rtol=0, atol=1e-9 * np.max(np.abs(qd)))
        power = np.sum(out["tau"] * out["qd"], -1)
        _, dE = E_ref(*args)
        assert np.max(np.abs(power - dE)) <= 1e-6 * np.max(np.abs(power)), name
        # the same energy up to a constant (the motors on the frame are in the package's V)
        E = E_ref(*args)[0] - (out["T"] + out["V"])
        assert np.ptp(E) <= 1e-9 * np.max(np.abs(out["T"] + out["V"]))


def test_gravity_off_and_the_static_balance():
    mech, unit, model, _, center, _ = _case("biglide")
    still = dict(x=np.array([0.05]), y=np.array([0.2]), xd=0.0, yd=0.0, xdd=0.0, ydd=0.0)
    assert np.all(inverse_dynamics(mech, still, model, gravity="off")["tau"] == 0.0)
    # at rest the sliders carry the weight: the sum of the vertical slider forces
    tau = inverse_dynamics(mech, still, model, gravity=(0.0, -9.81))["tau"]
    weight = 9.81 * sum(b.mass for b in model.bodies)
    assert np.sum(tau) == pytest.approx(weight, rel=1e-12)


def test_mass_model_input_checks():
    mech = FiveBar(0.25, 0.35, 0.1)
    for bad, match in (({"crank1": {"mass": -1.0}}, "mass of body crank1 must be >= 0"),
                       ({"elbow": {"mass": 1.0}}, "unknown body 'elbow'"),
                       ({"crank1": {"weight": 1.0}}, "body 'crank1' takes the keys")):
        with pytest.raises(ValueError, match=match):
            mass_model(mech, bodies=bad)
    with pytest.raises(ValueError, match="material must be one of"):
        MassLaw(material="unobtainium")
    with pytest.raises(ValueError, match="wall must be at most"):
        MassLaw(outer=0.01, wall=0.006)


def test_default_law_numbers():
    # 20 x 20 x 2 mm aluminium: 0.3888 kg/m; I_c = m (L^2/12 + I_s/A)
    model = mass_model(FiveBar(0.25, 0.35, 0.1))
    crank = {b.name: b for b in model.bodies}["crank1"]
    assert crank.mass == pytest.approx(2700 * (0.02**2 - 0.016**2) * 0.25, rel=1e-14)
    Is = (0.02**4 - 0.016**4) / 12
    assert crank.inertia == pytest.approx(crank.mass * (0.25**2 / 12 + Is / 1.44e-4), rel=1e-12)
    assert crank.com == (0.125, 0.0)


def _wrap(d):
    return (d + np.pi) % (2 * np.pi) - np.pi


def _five_bar_bodies_np(t, center, R, T, geom, mass):
    """Centres of mass and angles of the 5R's bodies (Le 2013 eq. 13-18, numpy) with
    ``P`` on a circle: ``{name: (c, angle or None)}``."""
    a1, c1, a2, c2, r3, mode = geom
    s1, s2 = (1 if ch == "+" else -1 for ch in mode)
    w = 2 * np.pi / T
    x, y = center[0] + R * np.cos(w * t), center[1] + R * np.sin(w * t)
    d1, d2 = np.hypot(x + r3, y), np.hypot(x - r3, y)
    th1 = np.arctan2(y, x + r3) + s1 * np.arccos((a1**2 + d1**2 - c1**2) / (2 * a1 * d1))
    th2 = np.pi - np.arctan2(y, r3 - x) + s2 * np.arccos((a2**2 + d2**2 - c2**2) / (2 * a2 * d2))
    out = {}
    for i, (th, a, ax) in enumerate(((th1, a1, -r3), (th2, a2, r3)), 1):
        bx, by = ax + a * np.cos(th), a * np.sin(th)
        f, g = mass[f"crank{i}"]["com"], mass[f"distal{i}"]["com"]
        out[f"crank{i}"] = (np.stack([ax + f * (bx - ax), f * by], -1), th)
        out[f"distal{i}"] = (np.stack([bx + g * (x - bx), by + g * (y - by)], -1),
                             np.arctan2(y - by, x - bx))
    out["payload"] = (np.stack([x, y], -1), None)
    return out, (th1, th2)


@pytest.mark.parametrize("name", ["five-bar", "asymmetric-five-bar"])
def test_power_balance_against_a_numpy_energy(name):
    """sum tau_i qd_i of the package = d(T + V)/dt of an energy computed here from Le's
    formulas, velocities and the time derivative by 4th-order central differences of
    closed-form positions (truncation ~h^4, far below the 1e-6 asked)."""
    make, unit, (_, geom), center, R = CASES[name]
    mech = make()
    names = NAMES["five-bar"]
    mass = _masses(names, seed=len(name))
    model = mass_model(mech, MassLaw(motor=0.0), mass, length_unit=unit)
    T_period = 0.8
    t = np.linspace(0.0, T_period, 41)
    w = 2 * np.pi / T_period
    cx, cy = (c * unit for c in center)
    Rm = R * unit

    def energy(tt):
        bodies, _ = _five_bar_bodies_np(tt, (cx, cy), Rm, T_period, geom, mass)
        h = 1e-4
        shifted = {k: _five_bar_bodies_np(tt + k * h, (cx, cy), Rm, T_period, geom, mass)[0]
                   for k in (-2, -1, 1, 2)}
        E = np.zeros(np.shape(tt))
        for n, (c, ang) in bodies.items():
            m = mass[n]["mass"]
            v = (8 * (shifted[1][n][0] - shifted[-1][n][0]) - (shifted[2][n][0] - shifted[-2][n][0])) / (12 * h)
            E += 0.5 * m * np.sum(v * v, -1) - m * (c @ np.asarray(GRAV))
            if ang is not None:
                om = (8 * _wrap(shifted[1][n][1] - shifted[-1][n][1])
                      - _wrap(shifted[2][n][1] - shifted[-2][n][1])) / (12 * h)
                E += 0.5 * mass[n]["inertia"] * om * om
        return E

    H = 1e-3
    dE = (8 * (energy(t + H) - energy(t - H)) - (energy(t + 2 * H) - energy(t - 2 * H))) / (12 * H)
    m = dict(x=(cx + Rm * np.cos(w * t)) / unit, y=(cy + Rm * np.sin(w * t)) / unit,
             xd=-Rm * w * np.sin(w * t) / unit, yd=Rm * w * np.cos(w * t) / unit,
             xdd=-Rm * w * w * np.cos(w * t) / unit, ydd=-Rm * w * w * np.sin(w * t) / unit)
    out = inverse_dynamics(mech, m, model, gravity=GRAV, length_unit=unit)
    power = np.sum(out["tau"] * out["qd"], -1)
    assert np.max(np.abs(power - dE)) <= 1e-6 * np.max(np.abs(power))
    # and the crank rates of the package are the derivatives of Le's angles
    _, (a, b) = _five_bar_bodies_np(t, (cx, cy), Rm, T_period, geom, mass)
    _, (a1, b1) = _five_bar_bodies_np(t + 1e-6, (cx, cy), Rm, T_period, geom, mass)
    _, (a0, b0) = _five_bar_bodies_np(t - 1e-6, (cx, cy), Rm, T_period, geom, mass)
    np.testing.assert_allclose(out["qd"][:, 0], (a1 - a0) / 2e-6, rtol=1e-6)
    np.testing.assert_allclose(out["qd"][:, 1], (b1 - b0) / 2e-6, rtol=1e-6)
