"""What a run will cost, known before it starts: memory and time estimates.

A pymoo generation compares every design with every other (non-dominated sorting,
the duplicate elimination's distance matrix), so its memory and time grow with the
square of the population; the problem's evaluations grow with their number. The
constants below were measured with pymoo 0.6.2 (NSGA-II and GA, three generations,
populations 1000 to 16000: about 17 bytes and 4e-8 s per pair of designs and
generation); they make an estimate, not a promise, and err on the large side.

:func:`check` refuses (one-line ValueError giving the estimate) a run that cannot fit
in the memory available, or that would take longer than :data:`REFUSE_SECONDS`;
it returns a line to print for a run estimated above :data:`WARN_SECONDS`.
"""
from __future__ import annotations

import os
import time
from dataclasses import dataclass

import numpy as np

__all__ = ["Estimate", "estimate", "check", "available_memory", "WARN_SECONDS", "REFUSE_SECONDS"]

#: bytes of working memory per pair of designs in a generation (measured, see above)
BYTES_PER_PAIR = 17.0
#: seconds of pymoo's own work per pair of designs and generation (measured)
SECONDS_PER_PAIR = 4e-8
#: bytes per design held by pymoo (an Individual and its arrays)
BYTES_PER_DESIGN = 4096
#: the interpreter, numpy, pandas, pymoo and mechopt loaded
BASE_BYTES = 300 * 2**20
#: a run estimated above this many seconds says so before it starts
WARN_SECONDS = 3600.0
#: a run estimated above this many seconds is refused (30 days)
REFUSE_SECONDS = 30 * 86400.0
#: runs of at most this many evaluations are not timed (they cannot take an hour
#: unless one evaluation takes 18 s)
_UNTIMED = 200


@dataclass(frozen=True)
class Estimate:
    """What a run will take (:func:`estimate`).

    Parameters
    ----------
    memory_bytes : float
        Peak memory [bytes].
    seconds : float
        Wall time [s].
    evaluations : int
        Design evaluations.
    seconds_per_evaluation : float or None
        Measured time per evaluation [s] (None when no design was evaluated).
    """

    memory_bytes: float
    seconds: float
    evaluations: int
    seconds_per_evaluation: float | None

    def describe(self) -> str:
        """The estimate in words (for messages).

        Returns
        -------
        str
            ``"about 1.2 GB of memory and 3 min ..."``.
        """
        per = ("" if self.seconds_per_evaluation is None
               else f", {self.seconds_per_evaluation * 1e3:.3g} ms per evaluation")
        return (f"about {_bytes(self.memory_bytes)} of memory and {_duration(self.seconds)} "
                f"({self.evaluations:,} evaluations{per})")


def _bytes(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if n < 1000 or unit == "TB":
            return f"{n:.3g} {unit}"
        n /= 1000.0
    return f"{n:.3g} TB"  # pragma: no cover


def _duration(s: float) -> str:
    for limit, div, unit in ((120, 1, "s"), (7200, 60, "min"), (172800, 3600, "h"),
                             (365.25 * 86400, 86400, "days")):
        if s < limit:
            return f"{s / div:.3g} {unit}"
    return f"{s / (365.25 * 86400):.3g} years"


def available_memory() -> float:
    """Bytes of memory this run may take: ``MemAvailable`` of /proc/meminfo where the
    OS has it, else the physical memory.

    Returns
    -------
    float
        [bytes].
    """
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):  # pragma: no cover - not POSIX
        return float("inf")


def _seconds_per_evaluation(problem) -> float:
    """A short timed sample: one design (compiles and loads what the problem needs),
    then four, drawn in the bounds with a generator of its own (the run's random
    state is not touched)."""
    rng = np.random.default_rng(0)
    xl, xu = np.asarray(problem.xl, float), np.asarray(problem.xu, float)
    problem.evaluate(xl + rng.random((1, problem.n_var)) * (xu - xl))
    X = xl + rng.random((4, problem.n_var)) * (xu - xl)
    t0 = time.perf_counter()
    problem.evaluate(X)
    return (time.perf_counter() - t0) / len(X)


def estimate(problem, pop: int, n_offsprings: int, max_gen: int, max_evaluations: int | None = None,
             sample: bool = True) -> Estimate:
    """Memory and time of ``max_gen`` generations of ``pop`` designs (``n_offsprings``
    new ones each) on ``problem``; ``max_evaluations`` caps the evaluations. Without
    ``sample`` no design is evaluated and the time counts pymoo's own work only.

    Parameters
    ----------
    problem : mechopt.run.problem.MechoptProblem
        The problem.
    pop : int
        Population size.
    n_offsprings : int
        New designs per generation.
    max_gen : int
        Generations.
    max_evaluations : int, optional
        A cap on the evaluations.
    sample : bool
        Time a few evaluations of the problem.

    Returns
    -------
    Estimate
        The estimate.
    """
    evaluations = pop + max(max_gen - 1, 0) * n_offsprings
    if max_evaluations is not None:
        evaluations = min(evaluations, max_evaluations)
    pairs = float(pop + n_offsprings) ** 2
    memory = BASE_BYTES + BYTES_PER_PAIR * pairs + BYTES_PER_DESIGN * (pop + n_offsprings)
    per = None if evaluations <= _UNTIMED or not sample else _seconds_per_evaluation(problem)
    gens = max_gen if max_evaluations is None else min(max_gen, max(1, max_evaluations // max(n_offsprings, 1)))
    seconds = (per or 0.0) * evaluations + SECONDS_PER_PAIR * pairs * gens
    return Estimate(memory, seconds, int(evaluations), per)


def check(est: Estimate, memory: float | None = None) -> str | None:
    """Refuse what cannot run (ValueError); a line to print for a run above an hour.

    Parameters
    ----------
    est : Estimate
        The estimate.
    memory : float, optional
        Memory available [bytes] (default: :func:`available_memory`).

    Returns
    -------
    str or None
        A line for a run above an hour, else None.

    Raises
    ------
    ValueError
        One line, for a run that cannot fit in memory or would take more than 30 days.
    """
    memory = available_memory() if memory is None else memory
    if est.memory_bytes > memory:
        raise ValueError(f"this run needs {est.describe()}, more than the {_bytes(memory)} of memory "
                         f"available; lower --pop")
    if est.seconds > REFUSE_SECONDS:
        raise ValueError(f"this run would take {est.describe()}; lower --pop or --gen")
    if est.seconds > WARN_SECONDS:
        return f"mechopt: this run is estimated at {est.describe()}"
    return None
