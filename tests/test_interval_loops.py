"""The compiled loops of mechopt.core.interval (``+ - * /``, ``sqr``, ``sqrt`` of arrays
of at least ``_FEW`` elements) give the NumPy paths' endpoints bit for bit.

The proven bounds run the loops once the compiled twins run and the NumPy paths before;
a difference would make a certificate's bounds depend on how long the process had run.
Every endpoint is compared byte for byte on intervals whose ends are floats of every
magnitude, the powers of two and their neighbours (``[2^-1022, 2^-1020]``, where the
rounding of many elements is not ``np.nextafter``'s), subnormals, signed zeros, the
largest doubles, infinities and NaN, in every broadcast the loops take (a constant, a
one-element operand, arrays of other dimensions); the loop run as plain Python (no
numba) too, and a loop with ``np.nextafter``'s rounding is caught.
"""
from __future__ import annotations

import numpy as np
import pytest

from mechopt.core import interval as iv
from mechopt.core import jit

MAX = np.finfo(float).max
TINY = np.finfo(float).tiny  # 2^-1022
SPECIAL = np.array([0.0, -0.0, MAX, -MAX, TINY, -TINY, 2 * TINY, 4 * TINY, 5e-324, -5e-324, np.inf, -np.inf,
                    np.nan, 1.0, -1.0, 0.5])


def _ends(rng, n):
    """``n`` floats: every magnitude, powers of two and their neighbours, the special ones."""
    k = rng.integers(0, 5, n)
    mag = rng.standard_normal(n) * 10.0 ** rng.integers(-320, 308, n)
    p2 = 2.0 ** rng.integers(-1074, 1024, n).astype(float) * rng.choice([-1.0, 1.0], n)
    near = p2 * rng.choice([1.0, 1.0 - 2.0 ** -52, 1.0 + 2.0 ** -52], n)
    tiny = rng.uniform(-4, 4, n) * TINY
    special = rng.choice(SPECIAL, n)
    with np.errstate(over="ignore"):
        return np.choose(k, [mag, near, tiny, special, rng.standard_normal(n)])


def _interval(rng, shape, ordered=True):
    """Intervals of the given shape (ordered ends, or any two floats)."""
    n = int(np.prod(shape))
    a, b = _ends(rng, n), _ends(rng, n)
    if ordered:
        with np.errstate(invalid="ignore"):
            a, b = np.fmin(a, b), np.fmax(a, b)
    return iv._make(a.reshape(shape), b.reshape(shape))


def _same(u, v):
    """Both intervals' endpoints equal byte for byte (shape and dtype included)."""
    for x, y in ((u.lo, v.lo), (u.hi, v.hi)):
        x, y = np.asarray(x), np.asarray(y)
        if x.shape != y.shape or x.dtype != y.dtype or x.tobytes() != y.tobytes():
            return False
    return True


def _cases(rng, n=1500):
    """(name, left, right) operand pairs in every broadcast the loops take."""
    full = lambda shape=(n,): _interval(rng, shape)  # noqa: E731
    c = rng.choice(SPECIAL[np.isfinite(SPECIAL)])
    return [
        ("full", full(), full()),
        ("unordered", _interval(rng, (n,), False), _interval(rng, (n,), False)),
        ("constant", full(), iv.as_interval(float(_ends(rng, 1)[0]))),
        ("special constant", full(), iv.as_interval(c)),
        ("one element", full(), _interval(rng, (1,))),
        ("left one element", _interval(rng, (1,)), full()),
        ("mixed", iv._make(_ends(rng, n), np.asarray(3.0)), full()),
        ("2-d", full((n // 3, 3)), full((n // 3, 3))),
        ("2-d constant", full((n // 3, 3)), iv.as_interval(np.array([[0.25]]))),
        ("smallest", full((iv._FEW,)), full((iv._FEW,))),
        ("strided", _interval(rng, (2 * n,))[::2], iv._make(*np.stack([full().lo, full().hi], 1).T)),
    ]


UNARY = {"sqr": lambda x: x.sqr(), "sqrt": lambda x: x.sqrt()[0]}
BINARY = {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": lambda a, b: a / b}


def _differences(monkeypatch, seed):
    """The operations and operands on which the loops' endpoints differ from the NumPy
    paths' (also checks that the loops ran)."""
    rng = np.random.default_rng(seed)
    calls = []
    for name in ("_BINARY_TWIN", "_UNARY_TWIN"):
        twin = getattr(iv, name)
        monkeypatch.setattr(iv, name, lambda *a, _t=twin: calls.append(1) or _t(*a))
    bad = []
    for case, a, b in _cases(rng):
        ops = [(k, lambda f=f: f(a, b), True) for k, f in BINARY.items()]
        # one interval: the loop takes ends of one shape, of _FEW elements or more
        ops += [(k, lambda f=f: f(a), np.shape(a.lo) == np.shape(a.hi) and np.size(a.lo) >= iv._FEW)
                for k, f in UNARY.items()]
        for k, f, loop in ops:
            with np.errstate(all="ignore"):
                monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: False))
                ref = f()
                monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: True))
                n = len(calls)
                got = f()
            assert len(calls) == n + loop, (case, k)  # the loop ran
            if not _same(ref, got):
                bad.append((case, k))
    return bad


needs_numba = pytest.mark.skipif(not jit.HAVE_NUMBA, reason="the compiled loops need numba (the fast extra)")


@needs_numba
@pytest.mark.parametrize("seed", range(4))
def test_compiled_loops_bit_for_bit(monkeypatch, seed):
    assert _differences(monkeypatch, seed) == []


@pytest.fixture
def python_loops(monkeypatch):
    """The loops run as plain Python (what numba compiles)."""
    for name, loop in (("_BINARY_TWIN", iv._binary_loop), ("_UNARY_TWIN", iv._unary_loop)):
        monkeypatch.setattr(iv, name, loop)


def test_python_loops_bit_for_bit(monkeypatch, python_loops):
    assert _differences(monkeypatch, 11) == []


def test_a_loop_rounding_as_nextafter_is_caught(monkeypatch, python_loops):
    """``np.nextafter`` (the rounding of few elements) differs from the rounding of many
    in ``[2^-1022, 2^-1020]``: a loop that used it would differ from the NumPy path."""
    monkeypatch.setattr(iv, "_round_down", lambda v: v if v == -np.inf else np.nextafter(v, -np.inf))
    monkeypatch.setattr(iv, "_round_up", lambda v: v if v == np.inf else np.nextafter(v, np.inf))
    bad = _differences(monkeypatch, 11)
    assert ("full", "*") in bad and ("full", "+") in bad


def test_a_loop_without_the_nan_rule_is_caught(monkeypatch, python_loops):
    """A product ``0 * inf`` (NaN) gives an unbounded interval on both paths; a loop
    taking the smallest of the finite products instead would differ."""
    def loop(op, alo, ahi, blo, bhi, lo, hi):
        iv._binary_loop(op, alo, ahi, blo, bhi, lo, hi)
        if op == iv._MUL:
            with np.errstate(invalid="ignore"):
                p = np.stack(np.broadcast_arrays(alo * blo, alo * bhi, ahi * blo, ahi * bhi))
            nan = np.isnan(p).any(0) & ~np.isnan(p).all(0)
            lo[nan] = np.nanmin(p[:, nan], 0)
    monkeypatch.setattr(iv, "_BINARY_TWIN", loop)
    rng = np.random.default_rng(5)
    a = _interval(rng, (iv._FEW,))
    a.lo[:8], a.hi[:8] = 0.0, 1.0
    b = iv._make(np.full(iv._FEW, 2.0), np.full(iv._FEW, np.inf))
    monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: False))
    with np.errstate(all="ignore"):
        ref = a * b
    monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: True))
    with np.errstate(all="ignore"):
        got = a * b
    assert ref.lo[0] == -np.inf and not _same(ref, got)


def test_few_elements_and_other_layouts_take_the_numpy_path(monkeypatch):
    """Fewer than ``_FEW`` elements (``np.nextafter``'s rounding), a broadcast of two
    full arrays: the loops are not called."""
    monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: True))
    monkeypatch.setattr(iv, "_BINARY_TWIN", lambda *a: pytest.fail("the loop ran"))
    monkeypatch.setattr(iv, "_UNARY_TWIN", lambda *a: pytest.fail("the loop ran"))
    rng = np.random.default_rng(0)
    few = _interval(rng, (iv._FEW - 1,))
    wide = _interval(rng, (iv._FEW, 2))
    for a, b in ((few, few), (wide, _interval(rng, (iv._FEW, 1)))):
        with np.errstate(all="ignore"):
            a * b, a + b, a - b, a / b
            if a is not wide:  # (its own ends: the loop's)
                a.sqr(), a.sqrt()


# ------------------------------------------------------------------ fused expressions
FUSED = {  # expression: (operands, operation by operation)
    iv._F_MULADD: (4, lambda a, v, w, b: a * v + w * b),
    iv._F_SCALE: (3, lambda c, v, d: c * (v * d)),
    iv._F_SUBMULDIV: (4, lambda a, q, b, v: (a - q * b) / v),
    iv._F_NEGMULDIV: (3, lambda q, d, v: -(q * d) / v),
}


def _fused_differences(monkeypatch, seed, n=1500):
    """The expressions (and operands) whose fused loop differs from the NumPy path's
    operations one by one; checks that the fused loop ran where it should."""
    rng = np.random.default_rng(seed)
    bad = []
    for op, (m, f) in FUSED.items():
        for shapes in ([(n,)] * m, [(n,), (1,)] + [(n,)] * (m - 2), [(1,)] * (m - 1) + [(n,)],
                       [(n // 3, 3)] * m):
            xs = [_interval(rng, s) for s in shapes]
            if op == iv._F_SCALE:
                xs[0] = iv.as_interval(rng.choice([2.0, 0.5, -3.0, 1e300]))
            with np.errstate(all="ignore"):
                monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: False))
                ref = f(*xs)
                monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: True))
                got = iv._fused(op, *xs)
            # the loop runs unless a first product has one element (its rounding: nextafter's)
            first_small = any(max(np.size(xs[j].lo), np.size(xs[j].hi)) == 1 for j in iv._F_FIRST[op][0]) and \
                all(max(np.size(xs[j].lo), np.size(xs[j].hi)) == 1 for j in iv._F_FIRST[op][0])
            assert (got is None) == first_small, (op, shapes)
            if got is not None and not _same(ref, got):
                bad.append((op, shapes[1]))
    return bad


@needs_numba
@pytest.mark.parametrize("seed", range(3))
def test_compiled_fused_expressions_bit_for_bit(monkeypatch, seed):
    assert _fused_differences(monkeypatch, seed) == []


@pytest.fixture
def python_fused(monkeypatch):
    for name, loop in (("_MULADD_TWIN", iv._muladd_loop), ("_SCALE_TWIN", iv._scale_loop),
                       ("_QUOTIENT_TWIN", iv._quotient_loop), ("_BINARY_TWIN", iv._binary_loop),
                       ("_UNARY_TWIN", iv._unary_loop)):
        monkeypatch.setattr(iv, name, loop)


def test_python_fused_expressions_bit_for_bit(monkeypatch, python_fused):
    assert _fused_differences(monkeypatch, 7, n=600) == []


def test_a_fused_loop_rounding_once_is_caught(monkeypatch, python_fused):
    """The products rounded only with the sum (one rounding instead of three): tighter,
    and not the NumPy path's endpoints."""
    def loop(alo, ahi, vlo, vhi, wlo, whi, blo, bhi, lo, hi):
        with np.errstate(all="ignore"):
            p = np.stack(np.broadcast_arrays(alo * vlo, alo * vhi, ahi * vlo, ahi * vhi))
            q = np.stack(np.broadcast_arrays(wlo * blo, wlo * bhi, whi * blo, whi * bhi))
            lo[:] = iv._down(p.min(0) + q.min(0))
            hi[:] = iv._up(p.max(0) + q.max(0))
    monkeypatch.setattr(iv, "_MULADD_TWIN", loop)
    assert (iv._F_MULADD, (600,)) in _fused_differences(monkeypatch, 7, n=600)


def _gradient_ops(rng, n):
    """Gradient expressions over ``n`` boxes (two variables; the closure's operations)."""
    x, y = (iv.Interval(*np.sort(rng.uniform(-50, 150, (2, n)), 0)) for _ in range(2))
    gx, gy = iv.Gradient.variables(x, y)
    with np.errstate(all="ignore"):
        d2 = (gx.sqr() + gy.sqr()).nonneg()
        u = 1.0 / d2
        k = 0.5 + 0.5 * ((gx * gy) * u)
        h, _ = (u * 40000.0 - k.sqr()).sqrt()
        r = iv.hypot(gx * h - gy, gy / (k + 3.0))
        return [d2, u, k, h, r, gx / gy, (gx - gy) / (h + 1.0)]


@pytest.mark.parametrize("n", [iv._FEW - 1, 700])
def test_gradient_operations_bit_for_bit(monkeypatch, python_fused, n):
    """Values and derivatives of Gradient expressions, loops (fused and not) against the
    NumPy path (fewer than _FEW boxes: the NumPy path both times)."""
    for compiled in (False, True):
        monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda c=compiled: c))
        got = _gradient_ops(np.random.default_rng(1), n)
        if not compiled:
            ref = got
    for u, v in zip(ref, got):
        assert _same(u.v, v.v) and all(_same(a, b) for a, b in zip(u.g, v.g))
