"""One place for input validation, shared by the Python API and the CLI.

Every check raises :class:`ValueError` with a one-line message that names the
parameter, the value given and what is allowed; the CLI turns it into exit status 2.
"""
from __future__ import annotations

import math
from typing import Iterable, Sequence

__all__ = [
    "positive_length",
    "nonnegative_length",
    "choice",
    "open_unit_interval",
    "finite_number",
]


def _as_float(name: str, value) -> float:
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    return out


def finite_number(name: str, value) -> float:
    """Return ``value`` as a float, or raise if it is NaN or infinite."""
    out = _as_float(name, value)
    if not math.isfinite(out):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return out


def positive_length(name: str, value) -> float:
    """A link length: finite and strictly positive."""
    out = finite_number(name, value)
    if out <= 0.0:
        raise ValueError(f"{name} must be a positive finite length, got {value!r}")
    return out


def nonnegative_length(name: str, value) -> float:
    """A length that may vanish (e.g. the half base distance r3 of a five-bar)."""
    out = finite_number(name, value)
    if out < 0.0:
        raise ValueError(f"{name} must be a non-negative finite length, got {value!r}")
    return out


def choice(name: str, value, allowed: Sequence[str] | Iterable[str]) -> str:
    """A string that must be one of ``allowed``."""
    allowed = tuple(allowed)
    if value not in allowed:
        raise ValueError(
            f"{name} must be one of {', '.join(repr(a) for a in allowed)}, got {value!r}"
        )
    return value


def open_unit_interval(name: str, value) -> float:
    """A threshold strictly between 0 and 1 (e.g. the LCI level gamma)."""
    out = finite_number(name, value)
    if not 0.0 < out < 1.0:
        raise ValueError(f"{name} must lie in the open interval (0, 1), got {value!r}")
    return out
