"""Fused five-bar LCI: the hot loop of workspace/atlas evaluations over millions of points.

:func:`five_bar_lci` gives the same values as the generic path
``indices.lci(FiveBar.jacobian(x, y))`` (to rounding: tested to 1e-12) without its
temporaries: no elbow coordinates, no ``(..., 2, 2)`` stacks, no trigonometry.
:meth:`mechopt.mechanisms.five_bar.model.FiveBar.lci` calls it.

Derivation (the conventions of :mod:`mechopt.mechanisms.five_bar.model`; Le 2013 eq. 13-19). For leg i with base joint
``A_i = (ax_i, 0)``, ``v = P - A_i = (dx, y)``, ``w = (-y, dx)`` and ``q = |v|^2``, the
circle intersection gives the elbow ``B_i = A_i + c v + h w`` with
``c = (r1^2 - r2^2 + q) / (2 q)`` and ``h = s_i sqrt(n) / (2 q)``, where
``n = (q - (r1 - r2)^2) ((r1 + r2)^2 - q)`` (Heron's form of
``4 q r1^2 - (r1^2 - r2^2 + q)^2``, free of cancellation near the serial boundary).
Then

    a_i = P - B_i = ((q + r2^2 - r1^2) v - s_i sqrt(n) w) / (2 q) =: a~_i / (2 q)
    b_i = (B_i - A_i) x a_i = -h q = -s_i sqrt(n) / 2

so the Jacobian row ``a_i / b_i`` is ``a~_i`` divided by ``-s_i q sqrt(n)``. The LCI is
invariant under scaling J and under row order, so it is evaluated on
``M = [g1 a~2; g2 a~1]`` with ``g_i = q_i sqrt(n_i)`` (no division) by the package's
one LCI formula, :func:`mechopt.core.indices.lci_of_entries`
(``2 |det M| / (S + sqrt(P Q))``, Liu 2006 eq. 3).

Coordinates are divided by the length scale first so that nothing over- or
underflows in any unit. Unreachable points (``n < 0``), a base joint at P
(``q = 0``) and type-I poses (``n = 0``) give 0, as on the generic path.

The pure NumPy kernel is always available. The numba kernel (the ``fast`` extra,
unless ``MECHOPT_NO_NUMBA`` is set: :mod:`mechopt.core.jit`, compiled on first use)
gives the same values bit for bit (tested in
``tests/test_workspace.py``) and is 10-25x faster on large arrays, but loading it costs about
0.5 s per process (numba's start-up and its cache), more than one design's whole
evaluation spends in this function. :func:`five_bar_lci` therefore starts with the
NumPy kernel and switches to numba for good once it has spent
:data:`NUMBA_AFTER_SECONDS` in NumPy (a long run then pays the load once, at most
twice the better choice's time), or at once if the numba kernel is already loaded.
"""
from __future__ import annotations

import time

import numpy as np

from mechopt.core import jit as _jit
from mechopt.core.indices import lci_of_entries
from mechopt.core.jit import HAVE_NUMBA

__all__ = ["five_bar_lci", "five_bar_lci_numpy", "five_bar_lci_numba", "HAVE_NUMBA"]

#: points per block of the NumPy kernel: its 14 buffers stay in L2/L3 cache
CHUNK = 16384


def _consts(r1, r2, r3):
    L = (r1 + r2 + r3) / 3.0
    r1n, r2n, r3n = r1 / L, r2 / L, r3 / L
    lo2 = (r1n - r2n) ** 2
    hi2 = (r1n + r2n) ** 2
    kk = r2n * r2n - r1n * r1n
    return 1.0 / L, r3n, lo2, hi2, kk


def _signed_sum(u, a, t, b, s, out, tmp):
    """``out = u a + s t b`` for ``s = +-1`` (in place; ``tmp`` is overwritten): the
    NumPy form of the compiled loop's ``u * a + s * t * b``, the same values."""
    np.multiply(u, a, out=out)
    np.multiply(t, b, out=tmp)
    if s > 0:
        out += tmp
    else:
        out -= tmp


def five_bar_lci_numpy(x, y, r1, r2, r3, s1, s2, chunk: int = CHUNK):
    """LCI of the five-bar working mode with elbow signs ``s1, s2`` (+1/-1).

    ``x`` and ``y`` must already have a common shape (see ``base.as_points``).
    Pure NumPy, in blocks of ``chunk`` points with preallocated buffers.

    Parameters
    ----------
    x, y : array_like
        Points [L].
    r1, r2, r3 : float
        Crank, distal link and half base [L].
    s1, s2 : int
        Elbow signs, +1 or -1.
    chunk : int
        Points per block.

    Returns
    -------
    ndarray
        The LCI (dimensionless).
    """
    shape = np.shape(x)
    xf = np.ascontiguousarray(x, dtype=float).reshape(-1)
    yf = np.ascontiguousarray(y, dtype=float).reshape(-1)
    n = xf.size
    out = np.empty(n)
    inv_l, r3n, lo2, hi2, kk = _consts(r1, r2, r3)
    m = min(chunk, n) if n else 0
    buf = np.empty((14, m))
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for i0 in range(0, n, chunk):
            i1 = min(i0 + chunk, n)
            k = i1 - i0
            (xs, ys, y2, dx, q, t, u, g1, g2, m11, m12, m21, m22, tmp) = (
                b[:k] for b in buf
            )
            np.multiply(xf[i0:i1], inv_l, out=xs)
            np.multiply(yf[i0:i1], inv_l, out=ys)
            np.multiply(ys, ys, out=y2)
            # leg 1's a~ goes to (m21, m22) with g1, leg 2's to (m11, m12) with g2
            for ax, s, rx, ry, g in ((-r3n, s1, m21, m22, g1), (r3n, s2, m11, m12, g2)):
                np.subtract(xs, ax, out=dx)  # dx = x - ax
                np.multiply(dx, dx, out=q)
                q += y2  # q = |P - A_i|^2
                np.subtract(q, lo2, out=t)
                np.subtract(hi2, q, out=u)
                t *= u  # n_i
                np.sqrt(t, out=t)  # sqrt(n_i), NaN where unreachable
                np.multiply(q, t, out=g)  # g_i = q sqrt(n_i)
                np.add(q, kk, out=u)  # E = q + r2^2 - r1^2
                # a~ = E v - s sqrt(n) w  with v = (dx, y), w = (-y, dx)
                _signed_sum(u, dx, t, ys, s, rx, tmp)
                _signed_sum(u, ys, t, dx, -s, ry, tmp)
            # M = [g1 a~2; g2 a~1]: diag(g2, g1) A~ with its rows swapped, which
            # leaves the LCI unchanged
            m21 *= g2
            m22 *= g2
            m11 *= g1
            m12 *= g1
            res = out[i0:i1]
            res[...] = lci_of_entries(m11, m12, m21, m22)
            # NaN (unreachable, 0/0 at type-I or q = 0) -> 0; fmax drops NaN
            np.fmax(res, 0.0, out=res)
    return out.reshape(shape)


def _five_bar_lci_loop(xf, yf, inv_l, r3n, lo2, hi2, kk, s1, s2, out):
    for i in range(xf.size):
        xs = xf[i] * inv_l
        ys = yf[i] * inv_l
        y2 = ys * ys
        dx = xs + r3n
        q = dx * dx + y2
        nn = (q - lo2) * (hi2 - q)
        dx2 = xs - r3n
        q2 = dx2 * dx2 + y2
        nn2 = (q2 - lo2) * (hi2 - q2)
        if not (nn > 0.0 and nn2 > 0.0):
            out[i] = 0.0  # unreachable, type I, or P on a base joint
            continue
        t = np.sqrt(nn)
        e = q + kk
        a1x = e * dx + s1 * t * ys
        a1y = e * ys - s1 * t * dx
        g1 = q * t
        t2 = np.sqrt(nn2)
        e2 = q2 + kk
        a2x = e2 * dx2 + s2 * t2 * ys
        a2y = e2 * ys - s2 * t2 * dx2
        g2 = q2 * t2
        m11 = g1 * a2x
        m12 = g1 * a2y
        m21 = g2 * a1x
        m22 = g2 * a1y
        v = lci_of_entries(m11, m12, m21, m22)
        out[i] = v if v >= 0.0 else 0.0  # NaN -> 0


#: the compiled loop, once made (numba is imported then, not with this module)
_loop_jit = None


def _get_loop_jit():
    global _loop_jit
    if _loop_jit is None:
        _loop_jit = _jit.njit(_five_bar_lci_loop,
                              signature="void(f8[::1], f8[::1], f8, f8, f8, f8, f8, f8, f8, f8[::1])")
    return _loop_jit


def five_bar_lci_numba(x, y, r1, r2, r3, s1, s2):
    """The same LCI as :func:`five_bar_lci_numpy`, by the numba-compiled loop.

    Parameters
    ----------
    x, y : array_like
        Points [L].
    r1, r2, r3 : float
        Crank, distal link and half base [L].
    s1, s2 : int
        Elbow signs, +1 or -1.

    Returns
    -------
    ndarray
        The LCI (dimensionless).

    Raises
    ------
    RuntimeError
        When numba is not available.
    """
    if not HAVE_NUMBA:
        raise RuntimeError("numba is not available (install the 'fast' extra)")
    shape = np.shape(x)
    # the compiled signature takes writable arrays: read-only inputs are copied
    xf = np.require(np.ascontiguousarray(x, dtype=float).reshape(-1), requirements=["W"])
    yf = np.require(np.ascontiguousarray(y, dtype=float).reshape(-1), requirements=["W"])
    out = np.empty(xf.size)
    inv_l, r3n, lo2, hi2, kk = _consts(r1, r2, r3)
    _get_loop_jit()(xf, yf, inv_l, r3n, lo2, hi2, kk, float(s1), float(s2), out)
    return out.reshape(shape)


#: seconds spent in the NumPy kernel after which :func:`five_bar_lci` loads numba
NUMBA_AFTER_SECONDS = 0.5
_numpy_seconds = 0.0


def five_bar_lci(x, y, r1, r2, r3, s1, s2):
    """Five-bar LCI by the kernel that is cheaper for this process (the same values
    either way): numba once loaded or once :data:`NUMBA_AFTER_SECONDS` of NumPy work
    have been spent, NumPy before (see the module docstring).

    Parameters
    ----------
    x, y : array_like
        Points [L].
    r1, r2, r3 : float
        Crank, distal link and half base [L].
    s1, s2 : int
        Elbow signs, +1 or -1.

    Returns
    -------
    ndarray
        The LCI (dimensionless), 0 where unreachable or singular.
    """
    global _numpy_seconds
    if HAVE_NUMBA and (_loop_jit is not None or _numpy_seconds >= NUMBA_AFTER_SECONDS):
        return five_bar_lci_numba(x, y, r1, r2, r3, s1, s2)
    t0 = time.perf_counter()
    out = five_bar_lci_numpy(x, y, r1, r2, r3, s1, s2)
    _numpy_seconds += time.perf_counter() - t0
    return out
