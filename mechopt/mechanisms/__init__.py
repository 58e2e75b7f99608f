"""The mechanisms: one module per mechanism, each a :class:`~mechopt.core.protocol.PlanarMechanism`.

:func:`registry` finds every mechanism that declares a ``cli_name`` in the modules of
this package and in the ``__init__`` of its subpackages (``five_bar/`` exports
:class:`~mechopt.mechanisms.five_bar.FiveBar` there), so a new mechanism is one new
module (plus its case in the contract suite, ``tests/mechanism_cases.py``):
``mechopt evaluate``, ``mechopt design`` and :func:`mechopt.analysis.evaluate.evaluate`
pick it up without edits elsewhere. A subpackage's other modules (the five-bar's
compiled kernels) are not imported to list the mechanisms: building the command
line does not load numba.
"""
from __future__ import annotations

import importlib
import pkgutil
from functools import lru_cache

__all__ = ["registry", "get", "designed", "design_spec"]


@lru_cache(maxsize=1)
def registry() -> dict:
    """Every mechanism of this package.

    Returns
    -------
    dict
        ``{cli_name: class}`` sorted by name: the mechanisms defined in its modules,
        or in a subpackage and exported by its ``__init__``.

    Raises
    ------
    RuntimeError
        When two mechanisms declare the same ``cli_name``.
    """
    from mechopt.core.protocol import PlanarMechanism

    found = {}
    for info in pkgutil.iter_modules(__path__, prefix=f"{__name__}."):
        module = importlib.import_module(info.name)
        home = module.__name__ + "." if info.ispkg else None
        for obj in vars(module).values():
            if (isinstance(obj, type) and issubclass(obj, PlanarMechanism) and obj.cli_name
                    and (obj.__module__ == module.__name__
                         or (home is not None and obj.__module__.startswith(home)))):
                if obj.cli_name in found and found[obj.cli_name] is not obj:
                    raise RuntimeError(f"two mechanisms are named {obj.cli_name!r}")
                found[obj.cli_name] = obj
    return dict(sorted(found.items()))


def get(name: str):
    """The mechanism class registered as ``name``.

    Parameters
    ----------
    name : str
        A ``cli_name`` (e.g. ``"five-bar"``).

    Returns
    -------
    type
        The :class:`~mechopt.core.protocol.PlanarMechanism` subclass.

    Raises
    ------
    ValueError
        One line naming the known mechanisms, for an unknown name.
    """
    from mechopt.core import validation as _v

    return registry()[_v.choice("mechanism", name, tuple(registry()))]


def designed() -> tuple:
    """Names of the mechanisms ``mechopt design`` sizes: every mechanism of
    :func:`registry` (in its order) with a
    :attr:`~mechopt.core.protocol.PlanarMechanism.design_spec`.

    Returns
    -------
    tuple of str
        The names.
    """
    return tuple(n for n, cls in registry().items() if cls.design_spec is not None)


def design_spec(name: str):
    """The design specification of a mechanism.

    Parameters
    ----------
    name : str
        One of :func:`designed`.

    Returns
    -------
    mechopt.core.design_spec.DesignSpec
        An instance of the mechanism's spec.

    Raises
    ------
    ValueError
        One line naming the designed mechanisms, for another name.
    """
    from mechopt.core import validation as _v

    return registry()[_v.choice("mechanism", name, designed())].design_spec()
