"""The mechanisms: one module per mechanism, each a :class:`~mechopt.core.protocol.PlanarMechanism`.

:func:`registry` finds every mechanism that declares a ``cli_name`` in the modules of
this package and its subpackages (``five_bar/``), so a new mechanism is one new module (plus its case in the contract
suite, ``tests/mechanism_cases.py``): ``mechopt evaluate`` and
:func:`mechopt.analysis.evaluate.evaluate` pick it up without edits elsewhere.
"""
from __future__ import annotations

import importlib
import pkgutil
from functools import lru_cache

__all__ = ["registry", "get"]


@lru_cache(maxsize=1)
def registry() -> dict:
    """``{cli_name: class}`` of every mechanism module of this package, sorted by name."""
    from mechopt.core.protocol import PlanarMechanism

    found = {}
    for info in pkgutil.walk_packages(__path__, prefix=f"{__name__}."):
        module = importlib.import_module(info.name)
        for obj in vars(module).values():
            if (isinstance(obj, type) and issubclass(obj, PlanarMechanism)
                    and obj.__module__ == module.__name__ and obj.cli_name):
                if obj.cli_name in found:
                    raise RuntimeError(f"two mechanisms are named {obj.cli_name!r}")
                found[obj.cli_name] = obj
    return dict(sorted(found.items()))


def get(name: str):
    """The mechanism class registered as ``name`` (e.g. ``"five-bar"``)."""
    from mechopt.core import validation as _v

    return registry()[_v.choice("mechanism", name, tuple(registry()))]
