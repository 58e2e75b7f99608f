"""Stan, Maties, Balan (2008): workspace W and transmission quality T of the
Bipod (RPRPR) and the Biglide (PRRRP).

Bipod (sec. 5.1, eq. 11-13): design variable ``u = q1_min/b`` in ``(0.52, 1.35)``,
``q1_min = q2_min = u b``, ``q_max = 1.6 q_min``, ``b = 1`` (the problem is
scale-free: W scales as b^2 and T not at all); the workspace is the half ``y > 0``.

Biglide (sec. 5.2): design variable ``L2`` in ``(1, 1.2)``. The paper gives neither
the guide half-distance ``L1`` nor the slider strokes; we use ``L1 = 1`` and
strokes ``q in [0, 1]`` (constructor arguments), mode ``"--"``. The links must be
longer than ``L1`` (:class:`~mechopt.mechanisms.biglide.Biglide`), so with ``L1 > 1``
the range is Stan's scaled by ``L1``: ``L2 in (L1, 1.2 L1)``
(:func:`biglide_l2_bounds`).

Objectives (both maximised): ``W`` (exact workspace area, Stan eq. 8) and ``T``
(area mean of the TQI of Stan eq. 9 over that workspace).

Normalisation of W in ``Z = W1 T + W2 W`` (Tables 2-3) is not stated by the
paper. We use ``W_n = W / W_ref`` with ``W_ref`` the area at the upper bound of
the design variable (the largest workspace of the design range, W grows
monotonically with it), so that both terms lie in [0, 1].
"""
from __future__ import annotations

import numpy as np

from mechopt.core import geometry as _g
from mechopt.mechanisms.biglide import Biglide
from mechopt.core.quadrature import gauss_legendre
from mechopt.mechanisms.sliders import GAUSS_ORDER_TQI
from mechopt.mechanisms.bipod import Bipod, bipod_tqi_integral, bipod_workspace_area

from mechopt.run.problem import MechoptProblem, Objective

__all__ = ["StanBipod", "StanBiglide", "BIPOD_BOUNDS", "BIGLIDE_BOUNDS", "biglide_indices",
           "biglide_l2_bounds"]

#: Stan eq. (12)
BIPOD_BOUNDS = (0.52, 1.35)
#: Stan eq. (13)
Q_MAX_OVER_Q_MIN = 1.6
#: Stan sec. 5.2
BIGLIDE_BOUNDS = (1.0, 1.2)


def biglide_l2_bounds(l1: float) -> tuple[float, float]:
    """The range of ``L2`` [L] for guides ``2 L1`` apart: Stan's ``(1, 1.2)`` (sec. 5.2)
    when ``L1 <= 1``; ``(L1, 1.2 L1)`` for a larger ``L1`` (Stan's range scaled by
    ``L1``), since a Biglide needs ``L2 > L1``. The lower end is open (``L2 = L1``
    leaves no workspace): the returned lower bound is ``1e-6 max(1, L1)`` above it.

    Parameters
    ----------
    l1 : float
        Half the distance of the guides [L], > 0.

    Returns
    -------
    tuple of float
        ``(lower, upper)`` bounds of ``L2`` [L].
    """
    s = max(1.0, float(l1))
    return BIGLIDE_BOUNDS[0] * s + 1e-6 * s, BIGLIDE_BOUNDS[1] * s


class _StanProblem(MechoptProblem):
    #: T is a mean of the TQI, 2 LCI / (1 + LCI^2) in [0, 1]; W >= 0 and it grows with
    #: the design variable (module docstring), so its largest value is :attr:`w_ref`
    #: (the instance's bounds of W are set in ``__init__``)
    objectives = (Objective("W", -1, "L^2"), Objective("T", -1, "-", (0.0, 1.0)))
    #: one variable: converged by generation 3, the front's spread is the population
    #: (HV ratio 0.981 with 60 designs, 0.990 with 100; benchmarks/bench_fronts.py)
    default_algorithm = "nsga2"
    default_pop = 100
    default_gen = 20

    #: the rule of the mechanism's ``gtqi`` for T (the Bipod's closed form, the Biglide's
    #: fixed Gauss rule)
    gtqi_method = "exact"

    def __init__(self, xl, xu, **kwargs):
        self._w_ref = None
        super().__init__(xl, xu, **kwargs)
        self.objectives = (self.objectives[0].with_bounds(0.0, self.w_ref), *self.objectives[1:])

    def _mechanism(self, v):
        raise NotImplementedError

    def _indices(self, values):
        """``(W, T)`` of the designs ``values``: per design ``m.workspace_area()`` and
        ``m.gtqi()`` (the Biglide's with ``method="gauss"``) of ``m = _mechanism(v)``;
        a subclass may compute them for the whole population at once, with the same
        operations (so bit for bit the same numbers, ``tests/test_experiment_stan2008.py``)."""
        W = np.empty(len(values))
        T = np.empty(len(values))
        for i, v in enumerate(values):
            m = self._mechanism(v)
            W[i] = m.workspace_area()
            T[i] = m.gtqi(method=self.gtqi_method)
        return W, T

    @property
    def w_ref(self) -> float:
        """Area at the upper bound of the design variable (normalisation of W)."""
        if getattr(self, "_w_ref", None) is None:  # computed once: it is asked for every evaluation
            self._w_ref = float(self._mechanism(self.xu[0]).workspace_area())
        return self._w_ref

    def evaluate_designs(self, X):
        W, T = self._indices(X[:, 0])
        return {"F": np.column_stack([-W, -T]), "extra": {"W_n": W / self.w_ref}}

    def weighted_sum(self, F, w):
        """Stan's ``Z = W1 T + W2 W_n`` with ``W1 = 1 - w``, ``W2 = w`` (w weighs W,
        the first objective), returned negated for minimisation.

        Parameters
        ----------
        F : ndarray
            Objectives in minimisation form, ``(n, 2)``.
        w : float
            The weight of W, in [0, 1].

        Returns
        -------
        ndarray
            ``-Z`` per row (minimised).
        """
        return -((1.0 - w) * (-F[:, 1]) + w * (-F[:, 0]) / self.w_ref)


class StanBipod(_StanProblem):
    """Stan 2008 Bipod: maximise the workspace W and the global TQI T (eq. 8-9) over
    ``q1_min / b`` with ``q_max = 1.6 q_min``.

    Parameters
    ----------
    **kwargs
        pymoo's :class:`~pymoo.core.problem.Problem` keywords.
    """

    name = "stan2008-bipod"
    summary = "Stan 2008 Bipod: max workspace W and global TQI T over q1_min/b in (0.52, 1.35), q_max = 1.6 q_min"
    var_names = ("q1_min_over_b",)

    def __init__(self, **kwargs):
        super().__init__([BIPOD_BOUNDS[0]], [BIPOD_BOUNDS[1]], **kwargs)

    def _mechanism(self, u):
        return Bipod(1.0, u, Q_MAX_OVER_Q_MIN * u)

    def _indices(self, values):
        # the vectorised closed forms behind Bipod.workspace_area and Bipod.gtqi
        # ("exact": tqi_integral / workspace_area, NaN for an empty workspace), for the
        # whole population in one call: the same element-wise operations as one design
        # at a time (bit for bit), without 2 x 40 NumPy calls per design
        u = np.ascontiguousarray(values, dtype=float).reshape(-1)
        if not len(u):
            return np.empty(0), np.empty(0)
        for v in (u[0], u[-1]):
            self._mechanism(v)  # the constructor's checks (every u of the bounds passes them)
        one = np.ones_like(u)
        q_max = Q_MAX_OVER_Q_MIN * u
        W = np.asarray(bipod_workspace_area(one, u, q_max, u, q_max), dtype=float).reshape(-1)
        ti = np.asarray(bipod_tqi_integral(one, u, q_max, u, q_max), dtype=float).reshape(-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            T = np.where(W > 0, ti / np.where(W > 0, W, 1.0), np.nan)
        return W, T


class StanBiglide(_StanProblem):
    """Stan 2008 Biglide: maximise the workspace W and the global TQI T (eq. 8-9) over
    the link ``L2``.

    Parameters
    ----------
    l1 : float
        Link 1 [L] (Stan does not print it; 1 by default).
    q_min, q_max : float
        The strokes of both sliders [L].
    **kwargs
        pymoo's :class:`~pymoo.core.problem.Problem` keywords.

    Raises
    ------
    ValueError
        One line, for a non-positive ``l1`` or an empty stroke.
    """

    name = "stan2008-biglide"
    summary = "Stan 2008 Biglide: max workspace W and global TQI T over L2 in (1, 1.2), L1 = 1, strokes [0, 1]"
    var_names = ("L2",)
    gtqi_method = "gauss"
    #: half the guide distance L1 and the strokes [q_min, q_max] of both sliders [L]
    options = ("l1", "q_min", "q_max")
    single_optimum = ("with L1 = 1 and strokes [0, 1] (the paper states neither) W and T both grow "
                      "with L2, so the front is the upper bound L2 = 1.2")

    def __init__(self, l1: float = 1.0, q_min: float = 0.0, q_max: float = 1.0, **kwargs):
        from mechopt.core import validation as _v

        self.l1 = _v.positive_length("l1", l1)
        self.q_min, self.q_max = _v.finite_number("q_min", q_min), _v.finite_number("q_max", q_max)
        lo, hi = biglide_l2_bounds(self.l1)
        self.summary = (f"Stan 2008 Biglide: max workspace W and global TQI T over L2 in "
                        f"({lo - 1e-6 * max(1.0, self.l1):g}, {hi:g}), L1 = {self.l1:g}, "
                        f"strokes [{self.q_min:g}, {self.q_max:g}]")
        super().__init__([lo], [hi], **kwargs)

    def _mechanism(self, l2):
        return Biglide(self.l1, l2, self.q_min, self.q_max)

    def _indices(self, values):
        l2 = np.ascontiguousarray(values, dtype=float).reshape(-1)
        if not len(l2):
            return np.empty(0), np.empty(0)
        for v in (np.min(l2), np.max(l2)):
            self._mechanism(v)  # the constructor's checks (l2 > l1, ...)
        return biglide_indices(self.l1, l2, self.q_min, self.q_max)


def biglide_indices(l1: float, l2, q_min: float, q_max: float):
    """``(W, T)`` of the Biglides ``Biglide(l1, l2[i], q_min, q_max)`` (mode ``"--"``,
    equal strokes) for an array ``l2``: ``workspace_area()`` and ``gtqi(method="gauss")``.

    The population-wide twin of those two methods (:mod:`mechopt.mechanisms.biglide`):
    the same breakpoints, the same interval formulas and the same 128-node Gauss rule,
    evaluated with the same element-wise operations and summed over the intervals in the
    same order, so that every value equals the per-design one bit for bit
    (``tests/test_experiment_stan2008.py`` checks it on random designs of every setup the
    experiment uses); about 50 times faster than a design at a time, which is what the
    GA runs of Stan 2008 spend their time on.

    Parameters
    ----------
    l1 : float
        Link 1 [L].
    l2 : array_like
        Link 2 of each design [L].
    q_min, q_max : float
        The strokes [L].

    Returns
    -------
    W : ndarray
        Workspace areas [L^2] (Stan 2008 eq. 8).
    T : ndarray
        Global TQI (dimensionless, eq. 9).
    """
    L = np.ascontiguousarray(l2, dtype=float).reshape(-1)
    n = L.size
    l1, a1, b1 = float(l1), float(q_min), float(q_max)
    a2, b2 = a1, b1
    s0, s1 = -1.0, -1.0  # mode "--"
    g0, g1 = l1, -l1
    S1, S2 = b1 - a1, b2 - a2
    xa, xb = l1 - L, L - l1
    # Biglide._breakpoints: the x range, 0 and the roots of the kinks of the chord,
    # clipped to the x range, sorted and unique
    cand = [xa, xb, np.zeros(n)]
    for k in (-S1, 0.0, S2 - S1, S2):
        K = k - (a1 - a2)
        num = K * K * (4.0 * (L * L - l1 * l1) - K * K)
        den = 4.0 * (4.0 * l1 * l1 + K * K)
        with np.errstate(invalid="ignore"):
            r = np.where(num >= 0, np.sqrt(np.where(num >= 0, num, 0.0) / den), np.nan)
        cand += [r, -r]
    P = np.sort(np.clip(np.column_stack(cand), xa[:, None], xb[:, None]), axis=1)  # NaN last
    dup = np.zeros(P.shape, dtype=bool)
    dup[:, 1:] = P[:, 1:] == P[:, :-1]
    P = np.sort(np.where(dup, np.nan, P), axis=1)  # the unique points first, in order

    def half_chords(x):
        out = []
        for g in (g0, g1):
            u = x - g
            r2 = L[:, None] * L[:, None] - u * u if x.ndim == 2 else L * L - u * u
            out.append(np.sqrt(np.maximum(r2, 0.0)))
        return out

    def d_of(x):
        h1, h2 = half_chords(x)
        return (a1 - a2) - s0 * h1 + s1 * h2

    t, w = gauss_legendre(GAUSS_ORDER_TQI)
    area = np.zeros(n)
    tqi = np.zeros(n)
    for j in range(P.shape[1] - 1):
        x0, x1 = P[:, j], P[:, j + 1]
        live = np.isfinite(x0) & np.isfinite(x1)
        dx = np.where(live, x1 - x0, 0.0)
        on = dx > 0
        if not on.any():
            continue
        # workspace_area: the chord's formula on this interval, from its midpoint
        dm = d_of(0.5 * (x0 + x1))
        pieces = np.column_stack([np.full(n, S1), np.full(n, S2), dm + S1, S2 - dm])
        k = np.argmin(pieces, axis=1)
        low = np.take_along_axis(pieces, k[:, None], axis=1)[:, 0]
        use = on & (low > 0)
        with np.errstate(invalid="ignore"):
            ih1 = np.asarray(_g.chord_integral(L, np.where(use, x0, 0.0) - g0, np.where(use, x1, 0.0) - g0))
            ih2 = np.asarray(_g.chord_integral(L, np.where(use, x0, 0.0) - g1, np.where(use, x1, 0.0) - g1))
        int_d = (a1 - a2) * dx - s0 * ih1 + s1 * ih2
        part = np.where(k < 2, low * dx, np.where(k == 2, int_d + S1 * dx, S2 * dx - int_d))
        area = area + np.where(use, part, 0.0)
        # tqi_integral(method="gauss") on the same interval
        xs = (0.5 * (x1 - x0))[:, None] * t[None, :] + (0.5 * (x0 + x1))[:, None]
        xs = np.where(on[:, None], xs, 0.0)
        h1, h2 = half_chords(xs)
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = (xs - g0) / (-s0 * h1)
            t2 = (xs - g1) / (-s1 * h2)
            tq = 2.0 * np.abs(t1 - t2) / (t1 * t1 + t2 * t2 + 2.0)
        tq = np.where(np.isfinite(tq), tq, 0.0)
        d = (a1 - a2) - s0 * h1 + s1 * h2
        g = np.maximum(0.0, np.minimum(np.minimum(np.full_like(d, S1), np.full_like(d, S2)),
                                       np.minimum(d + S1, S2 - d)))
        ch = np.where((xs >= xa[:, None]) & (xs <= xb[:, None]), g, 0.0)
        sums = np.array([np.sum(row) for row in w * tq * ch]) if n else np.zeros(0)
        tqi = tqi + np.where(on, 0.5 * (x1 - x0) * sums, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        T = np.where(area > 0, tqi / np.where(area > 0, area, 1.0), np.nan)
    return area, T
