"""The paper formulations as pymoo Problems, and their registry.

``get(name)`` returns a fresh Problem; ``available()`` lists ``(name, summary)``.
Installed as ``mechopt.problems``.
"""
from __future__ import annotations

import importlib

__all__ = ["get", "available", "names", "PYMOO_KEYWORDS"]

#: keywords of :class:`pymoo.core.problem.Problem` that every problem passes on (they
#: change how it is evaluated, not its numbers, so they are not among its settings)
PYMOO_KEYWORDS = ("callback", "elementwise_runner", "elementwise")

# name -> (module, class name, constructor kwargs)
_REGISTRY = {
    "le2013": ("le2013", "LeSquare", {}),
    "le2013-relaxed": ("le2013", "LeSquareRelaxed", {}),
    "le2013-gamma": ("le2013", "LeSquareGamma", {}),
    "le2013-gamma-relaxed": ("le2013", "LeSquareGammaRelaxed", {}),
    **{f"liu2006-{r}": ("liu2006", "LiuRegion", {"region": r})
       for r in ("w-gci", "w-gci-prime", "w-gci-gvi", "w-gci-gpi", "w-gci-gsi", "all")},
    "liu2006-many": ("liu2006", "LiuManyObjective", {}),
    "stan2008-bipod": ("stan2008", "StanBipod", {}),
    "stan2008-biglide": ("stan2008", "StanBiglide", {}),
    "wu2008": ("wu2008", "WuGantry", {}),
    "wu2008-dynamic": ("wu2008", "WuGantryDynamic", {}),
    # task-driven design (mechopt design); with no options, the five-bar for a 100 x 60 mm
    # rectangle 180 mm in front of the base, LCI >= 0.4
    "design": ("design", "DesignProblem", {}),
}


def names() -> tuple[str, ...]:
    """The registered problems' names.

    Returns
    -------
    tuple of str
        In registration order.
    """
    return tuple(_REGISTRY)


def get(name: str, **options):
    """A new instance of the registered Problem ``name``.

    ``options`` are passed to its constructor (e.g. ``quadrature="area"`` for the
    Liu problems), and pymoo's own :data:`PYMOO_KEYWORDS` to
    :class:`pymoo.core.problem.Problem` (e.g. ``elementwise_runner=
    StarmapParallelization(pool.starmap)``); an option the problem does not take is a
    ValueError.

    Parameters
    ----------
    name : str
        A registered problem (:func:`names`).
    **options : 
        The problem's options and pymoo's :data:`PYMOO_KEYWORDS`.

    Returns
    -------
    mechopt.run.problem.MechoptProblem
        A new instance.

    Raises
    ------
    ValueError
        One line, for an unknown name or an option the problem does not take.
    """
    import inspect

    from mechopt.core import validation as _v

    _v.choice("problem", name, names())
    module, cls, kw = _REGISTRY[name]
    mod = importlib.import_module(f"{__name__}.{module}")
    klass = getattr(mod, cls)
    params = inspect.signature(klass.__init__).parameters.values()
    accepted = {p.name for p in params if p.kind is p.POSITIONAL_OR_KEYWORD} - {"self"} - set(kw)
    for key in options:
        if key not in accepted and key not in PYMOO_KEYWORDS:
            takes = ", ".join(sorted(accepted)) or "none"
            raise ValueError(f"problem {name!r} takes no option {key!r} (its options: {takes})")
    return klass(**kw, **options)


def available():
    """``[(name, one-line summary)]`` of every registered problem; the summary of a
    problem whose front is a single design says so, with the reason.

    Returns
    -------
    list of tuple
        ``[(name, summary), ...]``.
    """
    rows = []
    for n in names():
        p = get(n)
        note = f" [single optimum: {p.single_optimum}]" if p.single_optimum else ""
        rows.append((n, p.summary + note))
    return rows
