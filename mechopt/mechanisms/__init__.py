"""The mechanisms: one module per mechanism, each a :class:`~mechopt.mechanisms.base.PlanarMechanism`.

:func:`registry` finds every mechanism that declares a ``cli_name`` in the modules of
this package, so a new mechanism is one new module (plus its case in the contract
suite, ``tests/mechanism_cases.py``): ``mechopt evaluate`` and
:func:`mechopt.evaluate.evaluate` pick it up without edits elsewhere.
"""
from __future__ import annotations

import importlib
import pkgutil
from functools import lru_cache

__all__ = ["registry", "get"]


@lru_cache(maxsize=1)
def registry() -> dict:
    """``{cli_name: class}`` of every mechanism module of this package, sorted by name."""
    from .base import PlanarMechanism

    found = {}
    for info in pkgutil.iter_modules(__path__):
        if info.name == "base":
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        for obj in vars(module).values():
            if (isinstance(obj, type) and issubclass(obj, PlanarMechanism)
                    and obj.__module__ == module.__name__ and obj.cli_name):
                if obj.cli_name in found:
                    raise RuntimeError(f"two mechanisms are named {obj.cli_name!r}")
                found[obj.cli_name] = obj
    return dict(sorted(found.items()))


def get(name: str):
    """The mechanism class registered as ``name`` (e.g. ``"five-bar"``)."""
    from .. import validation as _v

    return registry()[_v.choice("mechanism", name, tuple(registry()))]
