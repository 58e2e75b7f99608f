"""Contract suite run on every mechanism of tests/mechanism_cases.py.

The idea of scikit-learn's ``estimator_checks``: one set of checks that every
implementation of :class:`mechopt.core.protocol.PlanarMechanism` must pass, for
every working mode. Mechanism-specific properties live in their own test files.
"""
from __future__ import annotations

import sys
import zlib

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from mechanism_cases import CASES, sample_away_from_singularities
from mechopt.core.protocol import PlanarMechanism
from mechopt.mechanisms.five_bar.model import FiveBar

IDS = [c[0] for c in CASES]
HYP = settings(
    max_examples=15,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.filter_too_much],
    derandomize=True,
)


@pytest.fixture(params=CASES, ids=IDS)
def case(request):
    cid, factory, sampler = request.param
    return cid, factory(), sampler


def _rng(cid, salt=0):
    return np.random.default_rng([zlib.crc32(cid.encode()), salt])


def _assembly_modes(mech):
    """Assembly modes of the forward problem: ``mech.assembly_modes`` or the
    module-level ``ASSEMBLY_MODES`` of the mechanism's module."""
    modes = getattr(mech, "assembly_modes", None)
    if modes is None:
        modes = getattr(sys.modules[type(mech).__module__], "ASSEMBLY_MODES", None)
    assert modes, (
        f"{type(mech).__name__} must expose its forward-kinematics assembly modes as "
        "an attribute `assembly_modes` or a module constant `ASSEMBLY_MODES`"
    )
    return tuple(modes)


def _wrap(d):
    """Wrap angle differences to (-pi, pi]."""
    return np.angle(np.exp(1j * d))


def _joint_diff(mech, a, b):
    d = np.asarray(a) - np.asarray(b)
    return _wrap(d) if mech.angular_joints else d


# --- protocol -----------------------------------------------------------------
def test_is_a_planar_mechanism(case):
    cid, mech, _ = case
    assert isinstance(mech, PlanarMechanism)
    if hasattr(mech, "mode"):
        assert mech.mode in mech.modes
    assert np.isfinite(mech.length_scale) and mech.length_scale > 0
    xmin, xmax, ymin, ymax = mech.bounding_box()
    assert xmin < xmax and ymin < ymax
    assert len(mech.joint_names) == 2


def test_sampler_gives_what_it_promises(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid), 64)
    assert x.shape == y.shape == (64,)
    assert np.all(mech.reachable(x, y))
    assert np.all(mech.lci(x, y) > 0)
    assert np.all(mech.serial_clearance(x, y) > 0)


def test_bounding_box_encloses_the_reachable_set(case):
    cid, mech, _ = case
    xmin, xmax, ymin, ymax = mech.bounding_box()
    w, h = xmax - xmin, ymax - ymin
    rng = _rng(cid, 1)
    x = rng.uniform(xmin - w, xmax + w, 20000)
    y = rng.uniform(ymin - h, ymax + h, 20000)
    outside = (x < xmin) | (x > xmax) | (y < ymin) | (y > ymax)
    assert not np.any(mech.reachable(x, y) & outside)


def test_serial_clearance_sign_matches_reachable(case):
    cid, mech, _ = case
    xmin, xmax, ymin, ymax = mech.bounding_box()
    rng = _rng(cid, 2)
    x = rng.uniform(xmin, xmax, 20000)
    y = rng.uniform(ymin, ymax, 20000)
    c = mech.serial_clearance(x, y)
    ok = mech.reachable(x, y)
    margin = 1e-9 * mech.length_scale
    assert np.all(ok[c > margin])
    assert not np.any(ok[c < -margin])


# --- inverse / forward kinematics ----------------------------------------------
def _fk_round_trip_errors(mech, x, y):
    """Per-point distance between (x, y) and fk(ik(x, y)) in the matching assembly."""
    q1, q2, ok = mech.ik(x, y)
    assert np.all(ok)
    if isinstance(mech, FiveBar):
        # the assembly of each pose is known: it must be the one that matches
        asm = mech.assembly_of(x, y)
        err = np.full(x.shape, np.inf)
        for a in _assembly_modes(mech):
            xf, yf, valid = mech.fk(q1, q2, a)
            assert np.all(valid[asm == a])
            sel = asm == a
            err[sel] = np.hypot(xf - x, yf - y)[sel]
        return err
    # generic: try every assembly mode, accept the best, but one must match
    errs = []
    for a in _assembly_modes(mech):
        xf, yf, valid = mech.fk(q1, q2, a)
        e = np.hypot(xf - x, yf - y)
        errs.append(np.where(valid, e, np.inf))
    return np.min(errs, axis=0)


def test_ik_fk_round_trip(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 3), 500)
    err = _fk_round_trip_errors(mech, x, y)
    assert np.max(err) <= 1e-9 * mech.length_scale, f"worst round-trip error {np.max(err)}"


def test_ik_fk_round_trip_hypothesis(case):
    cid, mech, _ = case
    xmin, xmax, ymin, ymax = mech.bounding_box()

    @HYP
    @given(st.floats(0.0, 1.0), st.floats(0.0, 1.0))
    def check(u, v):
        x = np.float64(xmin + u * (xmax - xmin))
        y = np.float64(ymin + v * (ymax - ymin))
        assume(mech.reachable(x, y))
        assume(mech.serial_clearance(x, y) > 1e-3 * mech.length_scale)
        assume(abs(mech.type2_function(x, y)) > 1e-3)
        err = _fk_round_trip_errors(mech, np.atleast_1d(x), np.atleast_1d(y))
        assert err[0] <= 1e-8 * mech.length_scale

    check()


def test_fk_of_ik_is_in_the_working_mode(case):
    """fk -> ik: angles from fk of a working-mode pose map back to the same angles."""
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 4), 200)
    q1, q2, _ = mech.ik(x, y)
    for a in _assembly_modes(mech):
        xf, yf, valid = mech.fk(q1, q2, a)
        # keep the poses of this assembly that are the original ones
        same = valid & (np.hypot(xf - x, yf - y) <= 1e-9 * mech.length_scale)
        p1, p2, ok = mech.ik(xf[same], yf[same])
        assert np.all(ok)
        assert np.max(np.abs(_joint_diff(mech, p1, q1[same])), initial=0) < 1e-9
        assert np.max(np.abs(_joint_diff(mech, p2, q2[same])), initial=0) < 1e-9


def test_ik_nan_where_unreachable(case):
    cid, mech, _ = case
    xmin, xmax, ymin, ymax = mech.bounding_box()
    rng = _rng(cid, 5)
    x = rng.uniform(xmin - 1, xmax + 1, 5000)
    y = rng.uniform(ymin - 1, ymax + 1, 5000)
    q1, q2, ok = mech.ik(x, y)
    assert np.array_equal(ok, mech.reachable(x, y))
    assert np.all(np.isnan(q1[~ok])) and np.all(np.isnan(q2[~ok]))
    assert np.all(np.isfinite(q1[ok])) and np.all(np.isfinite(q2[ok]))


# --- Jacobian -----------------------------------------------------------------
def _fd_jacobian(mech, x, y, h):
    cols = []
    for dx, dy in ((h, 0.0), (0.0, h)):
        qp1, qp2, _ = mech.ik(x + dx, y + dy)
        qm1, qm2, _ = mech.ik(x - dx, y - dy)
        cols.append(
            np.stack([_joint_diff(mech, qp1, qm1), _joint_diff(mech, qp2, qm2)], -1) / (2 * h)
        )
    return np.stack(cols, -1)  # (..., i = joint, j = coordinate)


def test_jacobian_matches_finite_differences_of_ik(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 6), 400)
    J = mech.jacobian(x, y)
    assert J.shape == (400, 2, 2)
    Jfd = _fd_jacobian(mech, x, y, 1e-5 * mech.length_scale)
    scale = np.linalg.norm(J, axis=(-2, -1))
    rel = np.linalg.norm(J - Jfd, axis=(-2, -1)) / scale
    assert np.max(rel) < 1e-6, f"worst relative error {np.max(rel):.3g}"


def test_jacobian_is_b_inverse_a(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 7), 100)
    A, b, ok = mech.closure(x, y)
    assert A.shape == (100, 2, 2) and b.shape == (100, 2) and np.all(ok)
    J = mech.jacobian(x, y)
    np.testing.assert_allclose(b[:, :, None] * J, A, rtol=1e-12, atol=1e-12 * np.abs(A).max())


# --- batch == point by point -----------------------------------------------------
def _mixed_points(mech, cid, n=24):
    """Well-conditioned points plus unreachable ones, to check NaN/0 handling too."""
    x, y = sample_away_from_singularities(mech, _rng(cid, 8), n - 4)
    xmin, xmax, ymin, ymax = mech.bounding_box()
    x = np.concatenate([x, [xmax + 1.0, xmin - 1.0, 0.0, 0.5 * (xmin + xmax)]])
    y = np.concatenate([y, [0.0, ymax + 2.0, ymax + 1.0, ymin - 1.0]])
    return x, y


@pytest.mark.parametrize("method", ["ik", "jacobian", "lci", "closure", "singular_values"])
def test_batch_equals_point_by_point(case, method):
    cid, mech, _ = case
    x, y = _mixed_points(mech, cid)
    f = getattr(mech, method)
    batch = f(x, y)
    batch = batch if isinstance(batch, tuple) else (batch,)
    singles = [f(xi, yi) for xi, yi in zip(x.tolist(), y.tolist())]
    singles = [s if isinstance(s, tuple) else (s,) for s in singles]
    for k, whole in enumerate(batch):
        whole = np.asarray(whole)
        assert whole.shape[:1] == x.shape
        pointwise = np.stack([np.asarray(s[k]) for s in singles])
        assert pointwise.shape == whole.shape
        if whole.dtype == bool:
            assert np.array_equal(pointwise, whole)
        else:
            np.testing.assert_allclose(pointwise, whole, rtol=1e-13, atol=0, equal_nan=True)
    # a 2-D batch gives the same values in the same layout
    batch2 = f(x.reshape(4, -1), y.reshape(4, -1))
    batch2 = batch2 if isinstance(batch2, tuple) else (batch2,)
    for whole, whole2 in zip(batch, batch2):
        whole2 = np.asarray(whole2)
        assert whole2.shape[:2] == (4, x.size // 4)
        np.testing.assert_allclose(
            whole2.reshape(np.shape(whole)), whole, rtol=1e-13, atol=0, equal_nan=True
        )


def test_scalars_give_0d_arrays(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 9), 1)
    x, y = float(x[0]), float(y[0])
    assert np.shape(mech.lci(x, y)) == ()
    q1, q2, ok = mech.ik(x, y)
    assert np.shape(q1) == np.shape(q2) == np.shape(ok) == ()
    assert mech.jacobian(x, y).shape == (2, 2)
    assert np.shape(mech.reachable(x, y)) == ()


def test_broadcasting_x_column_y_row(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 10), 6)
    grid = mech.lci(x[:, None], y[None, :])
    assert grid.shape == (6, 6)
    X, Y = np.meshgrid(x, y, indexing="ij")
    np.testing.assert_allclose(grid, mech.lci(X, Y), rtol=1e-13, atol=0)


# --- LCI range --------------------------------------------------------------------
def test_lci_in_unit_interval_and_zero_where_unreachable(case):
    cid, mech, _ = case
    xmin, xmax, ymin, ymax = mech.bounding_box()
    w, h = xmax - xmin, ymax - ymin
    rng = _rng(cid, 11)
    x = rng.uniform(xmin - 0.2 * w, xmax + 0.2 * w, 50000)
    y = rng.uniform(ymin - 0.2 * h, ymax + 0.2 * h, 50000)
    c = mech.lci(x, y)
    assert c.shape == x.shape
    assert not np.any(np.isnan(c))
    assert np.all((c >= 0) & (c <= 1))
    ok = mech.reachable(x, y)
    assert np.all(c[~ok] == 0)
    assert np.any(c[ok] > 0)
    assert mech.lci(xmax + w, ymax + h) == 0


def test_lci_equals_svd_ratio(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 12), 200)
    s = np.linalg.svd(mech.jacobian(x, y), compute_uv=False)
    np.testing.assert_allclose(mech.lci(x, y), s[:, 1] / s[:, 0], rtol=1e-12, atol=1e-15)


def test_scale_invariance(case):
    """Every mechanism has ``scaled(D)``: LCI and TQI of the pose ``D p`` equal those
    of ``p``; reachability (hence every area) maps by ``p -> D p``, so areas scale as
    D^2; the Jacobian scales as 1/D for angular joints and not at all for sliders
    (q is then a length: q_dot = J p_dot is homogeneous of degree 0)."""
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 13), 200)
    xmin, xmax, ymin, ymax = mech.bounding_box()
    rng = _rng(cid, 14)
    bx, by = rng.uniform(xmin, xmax, 2000), rng.uniform(ymin, ymax, 2000)
    for D in (0.01, 3.7, 250.0):
        big = mech.scaled(D)
        assert type(big) is type(mech) and getattr(big, "mode", None) == getattr(mech, "mode", None)
        assert big.length_scale == pytest.approx(D * mech.length_scale, rel=1e-12)
        np.testing.assert_allclose(big.bounding_box(), D * np.asarray(mech.bounding_box()),
                                   rtol=1e-12, atol=1e-12 * D * mech.length_scale)
        np.testing.assert_allclose(big.lci(D * x, D * y), mech.lci(x, y), rtol=1e-10, atol=1e-14)
        np.testing.assert_allclose(big.tqi(D * x, D * y), mech.tqi(x, y), rtol=1e-10, atol=1e-14)
        k = 1.0 / D if mech.angular_joints else 1.0
        J = mech.jacobian(x, y)
        np.testing.assert_allclose(big.jacobian(D * x, D * y), J * k, rtol=1e-9,
                                   atol=1e-12 * np.abs(J).max() * k)
        # reachability maps point for point, away from the boundary's rounding band
        clear = np.abs(np.asarray(mech.serial_clearance(bx, by))) > 1e-6 * mech.length_scale
        np.testing.assert_array_equal(np.asarray(big.reachable(D * bx, D * by))[clear],
                                      np.asarray(mech.reachable(bx, by))[clear])
        if hasattr(mech, "workspace_area"):
            assert big.workspace_area() == pytest.approx(D * D * mech.workspace_area(), rel=1e-9)
    with pytest.raises(ValueError, match="factor"):
        mech.scaled(0.0)
    with pytest.raises(ValueError, match="factor"):
        mech.scaled(float("nan"))


def test_summary_is_the_declared_one(case):
    """``summary()`` returns :attr:`summary_keys` in order; where ``summary_powers`` is
    declared, every float of it has a power, and the design scaled by ``D`` gives the
    numbers times ``D**p`` (what ``mechopt.analysis.evaluate`` relies on to evaluate a design in
    units of its size)."""
    cid, mech, _ = case
    try:
        s = mech.summary()
    except ValueError:  # a gantry not made by Wu's synthesis has no summary
        assert mech.summary_powers is None
        return
    assert tuple(s) == mech.summary_keys
    if mech.summary_powers is None:
        return
    floats = {k for k, v in s.items() if isinstance(v, float)}
    assert floats <= set(mech.summary_powers), floats - set(mech.summary_powers)
    D = 2.0 ** 5  # exact: the scaled numbers equal bit for bit
    big = mech.scaled(D).summary()
    for k in floats:
        want = s[k] * D ** mech.summary_powers[k]
        assert big[k] == want or (np.isnan(want) and np.isnan(big[k])), k


# --- errors on wrong shapes ------------------------------------------------------
@pytest.mark.parametrize(
    "method",
    ["ik", "jacobian", "lci", "closure", "reachable", "serial_clearance",
     "classify_singularity", "type2_function", "local_indices"],
)
def test_value_error_when_x_and_y_do_not_broadcast(case, method):
    cid, mech, _ = case
    with pytest.raises(ValueError, match="(?i)broadcast|shape"):
        getattr(mech, method)(np.zeros(3), np.zeros(4))


def test_fk_value_error_when_angles_do_not_broadcast(case):
    cid, mech, _ = case
    a = _assembly_modes(mech)[0]
    with pytest.raises(ValueError, match="(?i)broadcast|shape"):
        mech.fk(np.zeros(3), np.zeros((2, 2)), a)


def test_fk_value_error_on_unknown_assembly(case):
    cid, mech, _ = case
    with pytest.raises(ValueError, match="assembly"):
        mech.fk(0.1, 0.2, "no-such-assembly")


# --- singularities ----------------------------------------------------------------
def test_classify_regular_points_as_none(case):
    cid, mech, sampler = case
    x, y = sampler(mech, _rng(cid, 14), 200)
    assert np.all(mech.classify_singularity(x, y) == "none")


def test_classify_unreachable(case):
    cid, mech, _ = case
    xmin, xmax, ymin, ymax = mech.bounding_box()
    out = mech.classify_singularity([xmax + 1.0, xmin - 1.0], [ymax + 1.0, 0.0])
    assert list(out) == ["unreachable", "unreachable"]


# Mechanisms whose reachable set is bounded by type-I loci only (no actuator stroke
# limits, where J stays regular): for them every boundary point is type I.
FIVE_BAR_CASES = [c for c in CASES if isinstance(c[1](), FiveBar)]
TYPE1_BOUNDARY_CASES = FIVE_BAR_CASES
TYPE1_IDS = [c[0] for c in TYPE1_BOUNDARY_CASES]


def _boundary_points_by_bisection(mech, cid, n=12):
    """Reachable points within a few ulps of the boundary of the reachable set,
    found by bisection on ``reachable`` along rays from well-conditioned points."""
    x0, y0 = sample_away_from_singularities(mech, _rng(cid, 15), n)
    ang = _rng(cid, 16).uniform(0, 2 * np.pi, n)
    ux, uy = np.cos(ang), np.sin(ang)
    xmin, xmax, ymin, ymax = mech.bounding_box()
    lo = np.zeros(n)
    hi = np.full(n, 2.0 * np.hypot(xmax - xmin, ymax - ymin))
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        ok = mech.reachable(x0 + mid * ux, y0 + mid * uy)
        lo = np.where(ok, mid, lo)
        hi = np.where(ok, hi, mid)
    x, y = x0 + lo * ux, y0 + lo * uy
    assert np.all(mech.reachable(x, y))
    return x, y


@pytest.mark.parametrize("cid,factory,sampler", TYPE1_BOUNDARY_CASES, ids=TYPE1_IDS)
def test_type1_on_reachable_boundary_loose_tol(cid, factory, sampler):
    """On the boundary of the reachable set a leg is stretched or folded (type I).

    The measure ``|B_ii|`` grows like the square root of the distance to the
    boundary, so a point within rounding of the boundary has ``|B_ii|`` of order
    sqrt(eps) ~ 1e-8: the tolerance here is above that.
    """
    mech = factory()
    x, y = _boundary_points_by_bisection(mech, cid)
    out = mech.classify_singularity(x, y, tol=1e-6)
    assert np.all(np.isin(out, ["type-I", "both"])), out


@pytest.mark.parametrize("cid,factory,sampler", TYPE1_BOUNDARY_CASES, ids=TYPE1_IDS)
def test_type1_on_reachable_boundary_default_tol(cid, factory, sampler):
    mech = factory()
    x, y = _boundary_points_by_bisection(mech, cid)
    out = mech.classify_singularity(x, y)
    assert np.all(np.isin(out, ["type-I", "both"])), out


# --- five-bar: constructed singular poses -------------------------------------------


def _five_bar_type2_candidates(r1, r2, r3):
    """Type-II poses built from the geometry, as ``(x, y, b1, b2)``.

    (a) distal links aligned: for theta1 on a grid, B1 on the crank circle of A1,
    B2 on the crank circle of A2 at distance 2 r2 from B1, P the midpoint (a1 = -a2);
    (b) coincident elbows: B1 = B2 at an intersection of the two crank circles and
    P anywhere on the circle of radius r2 around it (a1 = a2).
    """
    out = []
    a2 = np.array([r3, 0.0])
    for t1 in np.linspace(-np.pi, np.pi, 37)[:-1]:
        b1 = np.array([-r3 + r1 * np.cos(t1), r1 * np.sin(t1)])
        dv = a2 - b1
        d = np.hypot(*dv)
        R = 2 * r2
        if d == 0 or d > R + r1 or d < abs(R - r1):
            continue
        along = (R * R - r1 * r1 + d * d) / (2 * d)
        h = np.sqrt(max(R * R - along * along, 0.0))
        e = dv / d
        for sgn in (1.0, -1.0):
            b2 = b1 + along * e + sgn * h * np.array([-e[1], e[0]])
            p = 0.5 * (b1 + b2)
            out.append((p[0], p[1], b1, b2))
    if r3 < r1:
        for sy in (1.0, -1.0):
            b = np.array([0.0, sy * np.sqrt(r1 * r1 - r3 * r3)])
            for psi in np.linspace(-np.pi, np.pi, 13)[:-1]:
                p = b + r2 * np.array([np.cos(psi), np.sin(psi)])
                out.append((p[0], p[1], b, b))
    return out


def _five_bar_type2_poses(mech):
    """The constructed type-II poses whose elbows are those of ``mech``'s working mode
    (and that are not type-I as well)."""
    found = []
    L = mech.length_scale
    for x, y, b1, b2 in _five_bar_type2_candidates(mech.r1, mech.r2, mech.r3):
        b1x, b1y, b2x, b2y, ok = mech.elbows(x, y)
        if not ok or mech.serial_clearance(x, y) < 1e-3 * L:
            continue
        if np.hypot(b1x - b1[0], b1y - b1[1]) < 1e-9 * L and np.hypot(
            b2x - b2[0], b2y - b2[1]
        ) < 1e-9 * L:
            found.append((x, y, b1, b2))
    return found


FIVE_BAR_LENGTH_SETS = sorted({(m.r1, m.r2, m.r3) for m in (c[1]() for c in FIVE_BAR_CASES)})


@pytest.mark.parametrize("lengths", FIVE_BAR_LENGTH_SETS, ids=str)
def test_five_bar_constructed_type2_pose(lengths):
    found_any = 0
    for mode in FiveBar.modes:
        mech = FiveBar(*lengths, mode)
        poses = _five_bar_type2_poses(mech)
        if not poses:
            continue
        found_any += len(poses)
        x = np.array([p[0] for p in poses])
        y = np.array([p[1] for p in poses])
        A, b, ok = mech.closure(x, y)
        assert np.all(ok)
        det = np.linalg.det(A)
        assert np.max(np.abs(det)) < 1e-12 * mech.r2**2, (mode, det)
        assert np.all(np.abs(mech.type2_function(x, y)) < 1e-12)
        assert np.all(mech.classify_singularity(x, y) == "type-II"), mode
        assert np.max(mech.lci(x, y)) < 1e-10
    assert found_any >= 2, f"no type-II pose constructed for lengths {lengths}"


def _five_bar_boundary_points(mech, which):
    """Points on the circles of Le eq. (19) (to rounding, on the reachable side)
    that are reachable by the other leg with margin."""
    r1, r2, r3 = mech.r1, mech.r2, mech.r3
    rad = r1 + r2 if which == "outer" else abs(r1 - r2)
    phi = np.linspace(-np.pi, np.pi, 73)[:-1]
    pts = []
    for ax in (-r3, r3):
        x = ax + rad * np.cos(phi)
        y = rad * np.sin(phi)
        other = np.hypot(x + ax, y)  # distance to the other base joint (-ax, 0)
        keep = (other > abs(r1 - r2) + 0.05 * mech.length_scale) & (
            other < r1 + r2 - 0.05 * mech.length_scale
        )
        pts.append((x[keep], y[keep]))
    x = np.concatenate([p[0] for p in pts])
    y = np.concatenate([p[1] for p in pts])
    # rounding puts some of them just outside: keep those on the reachable side
    keep = mech.reachable(x, y)
    assert keep.sum() >= x.size // 4
    return x[keep], y[keep]


@pytest.mark.parametrize("which", ["outer", "inner"])
@pytest.mark.parametrize("cid,factory,sampler", FIVE_BAR_CASES, ids=[c[0] for c in FIVE_BAR_CASES])
def test_five_bar_type1_on_le19_circles_loose_tol(cid, factory, sampler, which):
    mech = factory()
    x, y = _five_bar_boundary_points(mech, which)
    if x.size == 0:
        # no point of this circle is inside the other leg's annulus with margin: with
        # r3 = 0 both legs share the circle, so take its points as they are (both legs
        # fold there: type-I twice)
        r1, r2 = mech.r1, mech.r2
        assert mech.r3 == 0.0, (cid, which)
        rad = r1 + r2 if which == "outer" else abs(r1 - r2)
        phi = np.linspace(-np.pi, np.pi, 73)[:-1]
        f = 1 - 1e-15 if which == "outer" else 1 + 1e-15  # rounding-level, reachable side
        x, y = f * rad * np.cos(phi), f * rad * np.sin(phi)
        keep = mech.reachable(x, y)
        assert keep.sum() >= 36
        x, y = x[keep], y[keep]
    assert np.all(np.abs(mech.serial_clearance(x, y)) < 1e-12 * mech.length_scale)
    out = mech.classify_singularity(x, y, tol=1e-6)
    assert np.all(np.isin(out, ["type-I", "both"])), out
    np.testing.assert_array_less(mech.lci(x, y), 1e-6)


@pytest.mark.parametrize("cid,factory,sampler", FIVE_BAR_CASES[:1], ids=[FIVE_BAR_CASES[0][0]])
def test_five_bar_type1_on_le19_circles_default_tol(cid, factory, sampler):
    mech = factory()
    x, y = _five_bar_boundary_points(mech, "outer")
    out = mech.classify_singularity(x, y)
    assert np.all(np.isin(out, ["type-I", "both"])), out
