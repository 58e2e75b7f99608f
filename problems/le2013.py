"""Le, Kang, Doan (2013): the largest square inside the MIC of a five-bar.

Le 2013 sec. III, eq. (23)-(26): with ``l1 = 1`` and ``rho = l2/l1``, find the
largest square ``W_o(rho)`` centred at the MIC centre, inside the MIC, on which
``1/kappa >= gamma`` (23) and the actuated angles stay within their limits
(25)-(26); the half base ``l0`` is tied by the closed-form optimum (24),
``l0 = sqrt(2)/2 (l2 - l1)``. The paper's example: ``gamma = 0.5``, limits
``[-pi/3, 4 pi/3]`` for both actuators, ``rho in [1.2, 4]``; it reports
``rho* = 1.9721`` and ``a_MAX = 1.3142``.
"""
from __future__ import annotations

import numpy as np

from mechopt.core import validation as _v
from mechopt import FiveBar
from mechopt.analysis.workspace import largest_square_at, mic

from mechopt.run.problem import MechoptProblem, Objective

__all__ = ["square_side", "tied_half_base", "LeSquare", "LeSquareRelaxed", "LeSquareGamma", "LeSquareGammaRelaxed",
           "THETA_LIMITS", "GAMMA", "RHO_BOUNDS", "L0_BOUNDS"]

#: Le 2013 sec. IV: theta_a{1,2} in [-pi/3, 4 pi/3]
THETA_LIMITS = (-np.pi / 3, 4 * np.pi / 3)
#: Le 2013 sec. IV: gamma = 0.5
GAMMA = 0.5
RHO_BOUNDS = (1.2, 4.0)
#: range of the half base ``l0`` where it is a variable (eq. 24 dropped)
L0_BOUNDS = (0.0, 2.0)
#: a design without a feasible square (no MIC, or LCI/joint limits failing at the
#: MIC centre) violates this constraint; its a_max = 0 no feasible design is below
SQUARE_CONSTRAINT = ("square_exists",)
#: range of the square side (hypervolume normalisation): the square lies in the MIC,
#: so a <= sqrt(2) r_MIC (inscribed square); the MIC lies in each arm's annulus
#: |l2 - l1| <= r <= l1 + l2, of width 2 min(l1, l2), so r_MIC <= l1 = 1; a >= 0
A_MAX_BOUNDS = (0.0, np.sqrt(2.0))
#: range of gamma, objective and variable of the two-objective problems: its bounds
GAMMA_BOUNDS = (0.05, 0.95)


def tied_half_base(rho: float, l1: float = 1.0) -> float:
    """Le eq. (24): ``l0 = sqrt(2)/2 (l2 - l1)`` with ``l2 = rho l1``.

    Parameters
    ----------
    rho : float
        The ratio ``l2 / l1``.
    l1 : float
        The crank [L].

    Returns
    -------
    float
        ``l0`` [L].
    """
    return np.sqrt(2.0) / 2.0 * (rho - 1.0) * l1


def square_side(l1, l2, l0, gamma=GAMMA, theta_limits=THETA_LIMITS) -> dict:
    """``a_MAX`` of Le Fig. 4 for one design (``l0`` is the half base, our ``r3``).

    Returns ``a_max``, ``r_mic``, ``mic_center_y``, the LCI range inside the square
    and ``violation``: ``-a_max / a_in`` (< 0, ``a_in = sqrt(2) r_MIC`` the inscribed
    square) when a square exists; otherwise how far the design is from having one:
    1 without a MIC, else the larger of ``(gamma - LCI) / gamma`` and the joint-limit
    excess over pi at the MIC centre (> 0). ``a_max = 0`` when no square exists.

    Parameters
    ----------
    l1 : float
        Crank [L].
    l2 : float
        Distal link [L].
    l0 : float
        Half base [L].
    gamma : float
        The LCI level of eq. (25).
    theta_limits : tuple of float
        Crank limits ``(lo, hi)`` [rad] of eq. (26).

    Returns
    -------
    dict
        ``a_max`` [L], ``r_mic``, ``mic_center_y`` [L], the LCI range and ``violation``
        (dimensionless).
    """
    try:
        fb = FiveBar(l1, l2, l0)
        m = mic(fb)
    except ValueError:
        return dict(a_max=0.0, r_mic=0.0, mic_center_y=np.nan, lci_min=np.nan, lci_max=np.nan,
                    violation=1.0)
    lo, hi = theta_limits
    # the square inscribed in the MIC has half side r_MIC / sqrt(2) (Le sec. III)
    a = largest_square_at(_SquareTest(fb, gamma, lo, hi), m.center_y, m.radius / np.sqrt(2.0))
    s = np.linspace(-a / 2, a / 2, 81)
    X, Y = np.meshgrid(s, m.center_y + s)
    L = fb.lci(X, Y)
    if a > 0:
        violation = -a / (np.sqrt(2.0) * m.radius)
    else:
        t1, t2, _ = fb.ik(0.0, m.center_y)
        excess = max(lo - float(t1), float(t1) - hi, lo - float(t2), float(t2) - hi) / np.pi
        violation = max((gamma - float(fb.lci(0.0, m.center_y))) / gamma, excess, _v.RESOLUTION)
    return dict(a_max=a, r_mic=m.radius, mic_center_y=m.center_y,
                lci_min=float(L.min()) if a > 0 else np.nan, lci_max=float(L.max()) if a > 0 else np.nan,
                violation=violation)


class _SquareTest:
    """The constraints (23), (25)-(26) at a square's sample points for
    :func:`mechopt.analysis.workspace.largest_square_at`, which only asks whether *all* of them
    hold: ``ok & (LCI >= gamma) & (theta_i in [lo, hi])`` point by point, with the
    same kinematics calls (``fb.lci``, ``fb.ik``) on the same points, so the bisection
    takes the same steps and returns the same side bit for bit. Only the order of the
    work differs: a square fails as soon as one point fails, so the cheap LCI is
    checked at every point first (it binds on Le's squares), and the inverse
    kinematics (two arccos and two arctan2 per point) is computed only for a square
    whose LCI holds everywhere, at the point that failed the joint limits last time
    alone first (the evaluators are element-wise: a point gives the same values alone
    as among all)."""

    def __init__(self, fb, gamma, lo, hi):
        self.fb, self.gamma, self.lo, self.hi = fb, gamma, lo, hi
        self.last = None  # index of the point that failed the joint limits last

    def _holds(self, x, y, lci):
        t1, t2, ok = self.fb.ik(x, y)
        lo, hi = self.lo, self.hi
        with np.errstate(invalid="ignore"):
            return ok & (lci >= self.gamma) & (t1 >= lo) & (t1 <= hi) & (t2 >= lo) & (t2 <= hi)

    def __call__(self, x, y):
        """Element-wise truth of the constraints, or ``[False]`` once one point fails."""
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        lci = self.fb.lci(x, y)
        with np.errstate(invalid="ignore"):
            if not np.all(lci >= self.gamma):
                return _FAILS
        i = self.last
        if i is not None and not self._holds(x[i:i + 1], y[i:i + 1], lci[i:i + 1])[0]:
            return _FAILS
        out = self._holds(x, y, lci)
        if not out.all():
            self.last = int(np.argmin(out))
        return out


_FAILS = np.zeros(1, dtype=bool)


def _evaluate(rows, gamma_col=None, l0_col=None, tied=True):
    out = {k: [] for k in ("a_max", "r_mic", "mic_center_y", "lci_min", "lci_max", "violation", "l0")}
    for row in rows:
        rho = row[0]
        l0 = tied_half_base(rho) if tied else row[l0_col]
        gamma = GAMMA if gamma_col is None else row[gamma_col]
        res = square_side(1.0, rho, l0, gamma)
        for k, v in res.items():
            out[k].append(v)
        out["l0"].append(l0)
    return {k: np.asarray(v, float) for k, v in out.items()}


class LeSquare(MechoptProblem):
    """Le eq. (23)-(26): maximise the square side over ``rho`` with ``l0`` tied by eq. (24).

    Parameters
    ----------
    **kwargs : 
        pymoo's :class:`~pymoo.core.problem.Problem` keywords (``elementwise_runner``,
        ``callback``).
    """

    name = "le2013"
    summary = "Le 2013: max square in the MIC of a 5R, LCI >= 0.5, joint limits, l0 tied (eq. 24); rho in [1.2, 4]"
    var_names = ("rho",)
    objectives = (Objective("a_max", -1, "l1", A_MAX_BOUNDS),)
    constr_names = SQUARE_CONSTRAINT
    #: ``l0`` follows eq. (24); False: it is the second variable, in :data:`L0_BOUNDS`
    tied = True
    #: DE reaches the brute-force optimum 1.332245 by generation 18 from seeds 1-5
    #: (GA 16 x 20: 1.33221; benchmarks/bench_fronts.py)
    default_algorithm = "de"
    default_pop = 10
    default_gen = 40

    def __init__(self, **kwargs):
        bounds = [RHO_BOUNDS] + ([] if self.tied else [L0_BOUNDS])
        super().__init__([b[0] for b in bounds], [b[1] for b in bounds], **kwargs)

    def evaluate_designs(self, X):
        ex = _evaluate(X, l0_col=1, tied=self.tied)
        return {"F": -ex["a_max"][:, None], "G": ex["violation"][:, None], "extra": ex}


class LeSquareRelaxed(LeSquare):
    """As :class:`LeSquare` with the half base ``l0`` free in [0, 2] (eq. 24 dropped)."""

    name = "le2013-relaxed"
    summary = "Le 2013 relaxed: as le2013 with the half base l0 free in [0, 2] (eq. 24 dropped)"
    var_names = ("rho", "l0")
    tied = False
    #: the optimum lies on a narrow ridge along the cliff l0 ~ eq. (24) (beyond it the
    #: square collapses): GA 40 x 80 stops below the tied optimum (1.33205 < 1.33221),
    #: DE best/1/bin, whose difference vectors follow the ridge, reaches the
    #: brute-force optimum 1.332249 (>= le2013's 1.332245) by generation 38 from seeds 1-5
    default_algorithm = "de"
    default_pop = 30
    default_gen = 80


class LeSquareGamma(MechoptProblem):
    """Two objectives: the square side and the LCI level gamma it guarantees.

    With ``tied=True`` the half base follows eq. (24); with ``tied=False`` it is a
    variable, so the gap between the two fronts is what eq. (24) costs.

    Parameters
    ----------
    tied : bool
        Whether the half base follows eq. (24).
    **kwargs : 
        pymoo's :class:`~pymoo.core.problem.Problem` keywords (``elementwise_runner``,
        ``callback``).
    """

    name = "le2013-gamma"
    summary = "Le 2013 two-objective: max square side and max gamma over (rho, gamma), l0 tied by eq. (24)"
    objectives = (Objective("a_max", -1, "l1", A_MAX_BOUNDS), Objective("gamma", -1, "-", GAMMA_BOUNDS))
    constr_names = SQUARE_CONSTRAINT
    #: 60 designs for the front's spread (HV ratio 0.98 needs about 50 on a 2-D
    #: front); converged by generation 6 from seeds 1-2 (benchmarks/bench_fronts.py)
    default_algorithm = "nsga2"
    default_pop = 60
    default_gen = 30
    options = ("tied",)

    def __init__(self, tied: bool = True, **kwargs):
        self.tied = bool(tied)
        if self.tied:
            self.var_names = ("rho", "gamma")
            super().__init__([RHO_BOUNDS[0], GAMMA_BOUNDS[0]], [RHO_BOUNDS[1], GAMMA_BOUNDS[1]], **kwargs)
        else:
            self.var_names = ("rho", "gamma", "l0")
            super().__init__([RHO_BOUNDS[0], GAMMA_BOUNDS[0], L0_BOUNDS[0]],
                             [RHO_BOUNDS[1], GAMMA_BOUNDS[1], L0_BOUNDS[1]], **kwargs)

    def evaluate_designs(self, X):
        ex = _evaluate(X, gamma_col=1, l0_col=2, tied=self.tied)
        F = np.column_stack([-ex["a_max"], -X[:, 1]])
        return {"F": F, "G": ex["violation"][:, None], "extra": ex}


class LeSquareGammaRelaxed(LeSquareGamma):
    """As :class:`LeSquareGamma` with the half base ``l0`` free in [0, 2] (``tied=False``).

    Parameters
    ----------
    **kwargs
        pymoo's :class:`~pymoo.core.problem.Problem` keywords.
    """

    name = "le2013-gamma-relaxed"
    summary = "Le 2013 two-objective with l0 free in [0, 2]: the front eq. (24) is measured against"

    def __init__(self, **kwargs):
        super().__init__(tied=False, **kwargs)
