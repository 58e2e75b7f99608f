"""mechopt: dimensional synthesis of 2-DOF planar parallel manipulators.

The public API is importable from here; each name is loaded on first use (PEP 562),
so that ``import mechopt`` and a command that needs one mechanism load only what
they use (scipy, numba and matplotlib stay unloaded until needed).
"""
from __future__ import annotations

import importlib

__version__ = "0.1.0"

#: public name -> module that defines it
_PUBLIC = {
    "PlanarMechanism": "mechopt.core.protocol",
    "FiveBar": "mechopt.mechanisms.five_bar.model",
    "Bipod": "mechopt.mechanisms.bipod",
    "Biglide": "mechopt.mechanisms.biglide",
    "Gantry": "mechopt.mechanisms.gantry",
    "dimensional_synthesis": "mechopt.mechanisms.gantry",
    "GantryDynamics": "mechopt.mechanisms.gantry_dynamics",
    "GantryInertia": "mechopt.mechanisms.gantry_dynamics",
    "mic": "mechopt.analysis.workspace",
    "global_indices": "mechopt.analysis.performance",
    "evaluate": "mechopt.analysis.evaluate",
    "Task": "mechopt.analysis.task",
    "Requirements": "mechopt.requirements",
    "design": "mechopt.workflows.design",
}

__all__ = ["__version__", *_PUBLIC]


def __getattr__(name):
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module 'mechopt' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__():
    return sorted(set(globals()) | set(_PUBLIC))
