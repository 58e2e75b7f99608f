"""Wu, Wang, Wang, Shao (2008): the gantry's smallest link angle theta_1S.

For a task rectangle ``b x h`` (Wu sec. 4.3: 500 x 400 mm) the dimensional
synthesis of eq. (10)-(16) fixes ``d, d1, l`` and the stroke from ``theta_1S``
(:func:`mechopt.mechanisms.gantry.dimensional_synthesis`). Two objectives: the
global velocity output ratio ``k_av`` (eq. 7, literal reading: the x-mean of
``|cot theta_1|``, maximised) and the machine size measured by the link length
``l`` (minimised); ``d1`` and the stroke are reported with every design. The
variant ``wu2008-dynamic`` adds the global dynamic index ``eta_D`` (eq. 44,
minimised) with the masses of Wu Table 2 carried over to each design's link length
(:meth:`mechopt.mechanisms.gantry_dynamics.GantryInertia.wu2008_scaled`: constant mass per length and
cross-section, counterweights half the moving mass).

Both objectives of ``wu2008`` improve as ``theta_1S`` decreases (Wu sec. 4.3:
a larger ``theta_1S`` gives "larger volume ... and smaller value of k_av"), so
its front is the single design at the lower bound: the paper's real trade-off is
with the singularity at ``theta_1S = 0``, which Wu settles by fixing 10 deg and
which ``wu2008-dynamic`` exposes through ``eta_D``.
"""
from __future__ import annotations

import numpy as np

from mechopt.mechanisms.gantry import Gantry, dimensional_synthesis, k_av_literal_of_design

from mechopt.run.problem import MechoptProblem, Objective

__all__ = ["WuGantry", "WuGantryDynamic", "THETA_1S_BOUNDS_DEG"]

#: design range of theta_1S [deg]; Wu sec. 4.3 chooses 10 deg, eq. (14) needs < 45
THETA_1S_BOUNDS_DEG = (5.0, 40.0)


class WuGantry(MechoptProblem):
    """Wu 2008 gantry: maximise ``k_av`` (eq. 7) and minimise the link length ``l``
    (eq. 15) over ``theta_1S`` [deg].

    Parameters
    ----------
    b, h : float
        The task rectangle [mm] (Wu's 500 x 400).
    **kwargs
        pymoo's :class:`~pymoo.core.problem.Problem` keywords.

    Raises
    ------
    ValueError
        One line, for a non-positive ``b`` or ``h``.
    """

    name = "wu2008"
    summary = "Wu 2008 gantry: max k_av (eq. 7) and min link length l over theta_1S in [5, 40] deg, task 500 x 400 mm"
    var_names = ("theta_1S_deg",)
    objectives = (Objective("k_av", -1), Objective("l", 1, "mm"))
    #: the single design at the lower bound is reached by generation 8 from seeds 1-2
    default_algorithm = "nsga2"
    default_pop = 20
    default_gen = 20
    #: the task rectangle b x h [mm]
    options = ("b", "h")
    single_optimum = ("k_av and l both improve as theta_1S falls (Wu sec. 4.3), so the front is "
                      "the lower bound; the paper trades them against the singularity at "
                      "theta_1S = 0 and fixes 10 deg (see wu2008-dynamic for a real trade-off)")

    def __init__(self, b: float = 500.0, h: float = 400.0, **kwargs):
        from mechopt.core import validation as _v

        self.b, self.h = _v.positive_length("b", b), _v.positive_length("h", h)
        if (self.b, self.h) != (500.0, 400.0):
            self.summary = self.summary.replace("task 500 x 400 mm", f"task {self.b:g} x {self.h:g} mm")
        super().__init__([THETA_1S_BOUNDS_DEG[0]], [THETA_1S_BOUNDS_DEG[1]], **kwargs)
        # ranges of the objectives (hypervolume normalisation): k_av falls and l grows
        # with theta_1S (closed forms: k_av_literal_of_design, eq. 14-15), so their
        # ranges are their values at the bounds of theta_1S
        ends = self._synthesis(np.array([[THETA_1S_BOUNDS_DEG[0]], [THETA_1S_BOUNDS_DEG[1]]]))
        k, l = ends["k_av"], ends["l"]
        self.objectives = (self.objectives[0].with_bounds(k[1], k[0]),
                           self.objectives[1].with_bounds(l[0], l[1]), *self.objectives[2:])

    def _synthesis(self, X):
        th = np.radians(X[:, 0])
        dims = np.array([dimensional_synthesis(self.b, self.h, t) for t in th])
        extra = {"d": dims[:, 0], "d1": dims[:, 1], "l": dims[:, 2], "stroke": dims[:, 3],
                 "k_av": k_av_literal_of_design(th)}
        return extra

    def evaluate_designs(self, X):
        ex = self._synthesis(X)
        return {"F": np.column_stack([-ex["k_av"], ex["l"]]), "extra": ex}


class WuGantryDynamic(WuGantry):
    name = "wu2008-dynamic"
    summary = "Wu 2008 gantry, three objectives: max k_av, min l, min eta_D (eq. 44, Table 2 masses)"
    #: eta_D is a mean of kappa_D >= 1; no upper bound follows from the formulation
    #: (kappa_D grows without bound as theta_1S -> 0): 2 is above its largest value
    #: over the design range (1.663 at theta_1S = 5 deg, on a 201-point lattice)
    objectives = WuGantry.objectives + (Objective("eta_d", 1, "-", (1.0, 2.0)),)
    #: a curve in 3 objectives: NSGA-III with 100 designs reaches IGD+ 0.007 and HV ratio
    #: 0.980, NSGA-II with 150 designs 0.0025 and 0.991 by generation 2
    #: (benchmarks/bench_fronts.py); a generation (0.3 s) runs on 2 processes
    default_algorithm = "nsga2"
    default_pop = 150
    default_gen = 20
    single_optimum = None

    def evaluate_designs(self, X):
        ex = self._synthesis(X)
        # the machine of Wu's synthesis in mm (platform of Table 1, which eta_D does not
        # depend on), its dynamics in metres with Table 2 carried over to its link length
        ex["eta_d"] = np.array([
            Gantry.from_parameters(self.b, self.h, float(t)).eta_d() for t in X[:, 0]])
        F = np.column_stack([-ex["k_av"], ex["l"], ex["eta_d"]])
        return {"F": F, "extra": ex}
