"""One place for input validation, limits and tolerances, shared by the Python API and the CLI.

Limits (:data:`LENGTH_MIN`, :data:`LENGTH_MAX`, :data:`POINT_MAX`, :data:`MAX_WEIGHTS`)
bound what a user may ask for; the three relative tolerances (:data:`ROUNDING`,
:data:`RESOLUTION`, :data:`STEP_FLOOR`) are the package's only ones: every module
compares derived values with them, scaled by the quantity's own magnitude.

Every check raises :class:`ValueError` with a one-line message that names the
parameter, the value given and what is allowed; the CLI turns it into exit status 2.
"""
from __future__ import annotations

import math
import numbers
from typing import Iterable, Sequence

__all__ = [
    "LENGTH_MIN",
    "LENGTH_MAX",
    "POINT_MAX",
    "positive_length",
    "positive_size",
    "position",
    "nonnegative_length",
    "coordinate",
    "choice",
    "open_unit_interval",
    "finite_number",
    "finite_numbers",
    "integer",
    "real_array_dtype",
    "show",
    "step",
    "stroke",
    "weights",
    "MAX_WEIGHTS", "POINTS_MAX", "POINTS_FILE_BYTES", "POLYGON_VERTICES_MAX",
    "ROUNDING",
    "RESOLUTION",
    "STEP_FLOOR",
]

#: admissible magnitudes of a length, in any unit: the kinematics square and
#: multiply lengths (and their ratios), which overflows or underflows in double
#: precision for lengths far outside this range
LENGTH_MIN = 1e-12
LENGTH_MAX = 1e12
#: no workspace of an admissible design reaches farther from the origin than this
#: (a sum of a few lengths of at most LENGTH_MAX); a point beyond is out of reach
POINT_MAX = 1e3 * LENGTH_MAX

#: relative rounding tolerance: a value derived from the lengths by a few dozen
#: operations carries a relative error of some hundred ulps (2.2e-16 each) at most,
#: so it is compared with a limit it may touch exactly (a stroke end, the reach
#: boundary ``h^2 >= 0``, a tie between candidates) within ``ROUNDING`` times its scale
ROUNDING = 1e-12
#: relative resolution of values known to fewer digits than rounding: the result of
#: an iterative search or a bracketing (converged to ~1e-10 and better), a grid
#: coordinate made from a step, the smallest MIC radius told apart from none;
#: ``RESOLUTION`` times the scale separates "equal" from "different" there
RESOLUTION = 1e-9
#: relative step at which an iterative search stops: a few ulps of the scale, below
#: which a step no longer changes the iterate
STEP_FLOOR = 1e-15


def show(value, width: int = 80) -> str:
    """``repr(value)`` on one line, shortened to ``width`` characters (for messages).

    Parameters
    ----------
    value : object
        Any value.
    width : int
        The largest length.

    Returns
    -------
    str
        The text.
    """
    text = " ".join(repr(value).split())
    return text if len(text) <= width else text[: width - 3] + "..."


def _refuse_non_real(name: str, value):
    """Booleans, complex numbers and other non-real objects are not numbers here:
    ``True`` is no length of 1 and ``1+1j`` would lose its imaginary part."""
    if isinstance(value, bool) or type(value).__name__ in ("bool", "bool_"):
        raise ValueError(f"{name} must be a real number, got the boolean {show(value)}")
    if isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a real number, got the complex {show(value)}")


def real_array_dtype(name: str, array) -> None:
    """Refuse arrays of booleans, complex numbers or objects (one line naming ``name``).

    Parameters
    ----------
    name : str
        The value's name, for the message.
    array : ndarray
        The array.

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, for booleans, complex numbers or objects.
    """
    kind = getattr(getattr(array, "dtype", None), "kind", None)
    if kind in ("b", "c"):
        what = "booleans" if kind == "b" else "complex numbers"
        raise ValueError(f"{name} must hold real numbers, got an array of {what}")


def _as_float(name: str, value) -> float:
    _refuse_non_real(name, value)
    try:
        out = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be a number, got {show(value)}") from None
    return out


def finite_number(name: str, value) -> float:
    """Return ``value`` as a float, or raise if it is NaN or infinite.

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The value.

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is not a finite real number.
    """
    out = _as_float(name, value)
    if not math.isfinite(out):
        raise ValueError(f"{name} must be finite, got {show(value)}")
    return out


def _length_range(name: str, out: float, value) -> float:
    if not LENGTH_MIN <= out <= LENGTH_MAX:
        raise ValueError(f"{name} must lie in [{LENGTH_MIN:g}, {LENGTH_MAX:g}] (any unit; lengths "
                         f"beyond overflow the kinematics), got {show(value)}")
    return out


def positive_length(name: str, value) -> float:
    """A link length: finite, strictly positive, in [LENGTH_MIN, LENGTH_MAX].

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The length [L].

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is not a positive finite length in
        the admissible range.
    """
    out = finite_number(name, value)
    if out <= 0.0:
        raise ValueError(f"{name} must be a positive finite length, got {show(value)}")
    return _length_range(name, out, value)


def nonnegative_length(name: str, value) -> float:
    """A length that may vanish (e.g. the half base distance r3 of a five-bar),
    at most LENGTH_MAX (tiny values act as 0: such lengths are only added to others).

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The length [L].

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is negative, not finite or too
        large.
    """
    out = finite_number(name, value)
    if out < 0.0:
        raise ValueError(f"{name} must be a non-negative finite length, got {show(value)}")
    return out if out <= LENGTH_MAX else _length_range(name, out, value)


def positive_size(name: str, value) -> float:
    """A derived size (e.g. a raster step): finite and strictly positive, of any
    magnitude (a step of a design of lengths 1e-12 is smaller still; the callers
    bound the work it implies).

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The size.

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is not finite and positive.
    """
    out = finite_number(name, value)
    if not out > 0.0:
        raise ValueError(f"{name} must be a positive finite length, got {show(value)}")
    return out


def position(name: str, value) -> float:
    """A point's coordinate used by an analysis (e.g. a disk centre): finite,
    ``|value| <= POINT_MAX`` (workspaces of admissible designs reach up to a few
    LENGTH_MAX from the origin).

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The coordinate [L].

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is not finite or beyond
        ``POINT_MAX``.
    """
    out = finite_number(name, value)
    if abs(out) > POINT_MAX:
        raise ValueError(f"{name} must lie in [-{POINT_MAX:g}, {POINT_MAX:g}] (farther than any "
                         f"workspace reaches), got {show(value)}")
    return out


def coordinate(name: str, value) -> float:
    """A signed position (e.g. a stroke limit): finite, ``|value| <= LENGTH_MAX``.

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The coordinate [L].

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is not finite or beyond
        ``LENGTH_MAX``.
    """
    out = finite_number(name, value)
    if abs(out) > LENGTH_MAX:
        raise ValueError(f"{name} must lie in [-{LENGTH_MAX:g}, {LENGTH_MAX:g}], got {show(value)}")
    return out


def integer(name: str, value, minimum: int | None = None, maximum: int | None = None) -> int:
    """A whole number (``3``, ``3.0`` or ``"3"``) within ``[minimum, maximum]``.

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.
    minimum : int, optional
        The smallest allowed.
    maximum : int, optional
        The largest allowed.

    Returns
    -------
    int
        The number.

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is not a whole number in the range.
    """
    _refuse_non_real(name, value)
    if isinstance(value, numbers.Integral):
        out = int(value)
    else:
        f = finite_number(name, value)
        if f != math.floor(f):
            raise ValueError(f"{name} must be an integer, got {show(value)}")
        out = int(f)
    if (minimum is not None and out < minimum) or (maximum is not None and out > maximum):
        if maximum is None:
            allowed = f">= {minimum}"
        elif minimum is None:
            allowed = f"<= {maximum}"
        else:
            allowed = f"in [{minimum}, {maximum}]"
        raise ValueError(f"{name} must be an integer {allowed}, got {show(value)}")
    return out


def finite_numbers(name: str, value, n: int, what: str | None = None) -> tuple:
    """A sequence of exactly ``n`` finite numbers, e.g. a point or a box.

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.
    n : int
        How many numbers.
    what : str, optional
        What they are, for the message (``"a point (x, y)"``).

    Returns
    -------
    tuple of float
        The numbers.

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, when it is not a sequence of ``n`` finite
        numbers.
    """
    what = what or f"{n} numbers"
    try:
        items = list(value)
    except TypeError:
        raise ValueError(f"{name} must be {what}, got {show(value)}") from None
    if len(items) != n:
        raise ValueError(f"{name} must be {what}, got {show(value)}")
    return tuple(finite_number(name, v) for v in items)


def choice(name: str, value, allowed: Sequence[str] | Iterable[str]) -> str:
    """A string that must be one of ``allowed``.

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.
    allowed : iterable of str
        The allowed strings.

    Returns
    -------
    str
        The value.

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, listing the allowed strings, for another
        value.
    """
    allowed = tuple(allowed)
    try:
        ok = bool(value in allowed)
    except (TypeError, ValueError):  # e.g. an array: no single truth value
        ok = False
    if not ok:
        raise ValueError(
            f"{name} must be one of {', '.join(repr(a) for a in allowed)}, got {show(value)}"
        )
    return value


def open_unit_interval(name: str, value) -> float:
    """A threshold strictly between 0 and 1 (e.g. the LCI level gamma).

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The value, in (0, 1).

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, outside (0, 1).
    """
    out = finite_number(name, value)
    if not 0.0 < out < 1.0:
        raise ValueError(f"{name} must lie in the open interval (0, 1), got {show(value)}")
    return out


def step(name: str, value, upper: float) -> float:
    """A lattice step in ``(0, upper]``.

    Parameters
    ----------
    name : str
        The value's name, for the message.
    value : object
        The value to check.
    upper : float
        The largest step.

    Returns
    -------
    float
        The step.

    Raises
    ------
    ValueError
        One line naming ``name`` and the value, outside (0, upper].
    """
    out = finite_number(name, value)
    if not 0.0 < out <= upper:
        raise ValueError(f"{name} must lie in (0, {upper}], got {value!r}")
    return out


#: most weights of one sweep (each is a full optimisation run)
MAX_WEIGHTS = 10_001

#: the most points a ``points:``/``path:`` task file may hold, and its largest size [bytes]
#: (200 000 lines of two numbers; the design's samples are a few thousand points)
POINTS_MAX = 200_000
POINTS_FILE_BYTES = 16 * 1024 * 1024

#: the most vertices of a polygon task (the simplicity test is vectorised over pairs of
#: edges: 5000 vertices are 12.5 million pairs, about a second)
POLYGON_VERTICES_MAX = 5_000


def weights(text: str):
    """Weights of a sweep: ``"0:1:0.1"`` (start:stop:step, inclusive) or ``"0,0.25,1"``;
    each in [0, 1]. Returns a NumPy array.

    Parameters
    ----------
    text : str
        The weights' text.

    Returns
    -------
    ndarray
        The weights, each in [0, 1].

    Raises
    ------
    ValueError
        One line, for a malformed text or a weight outside [0, 1].
    """
    import numpy as np

    try:
        if ":" in text:
            a, b, s = (float(v) for v in text.split(":"))
            if not s > 0 or b < a:
                raise ValueError
            n = int(np.floor((b - a) / s + RESOLUTION)) + 1
            if n > MAX_WEIGHTS:
                raise ValueError(f"weights {text!r} give {n} weights, more than {MAX_WEIGHTS}")
            w = a + s * np.arange(n)
        else:
            items = text.split(",")
            if len(items) > MAX_WEIGHTS:
                raise ValueError(f"weights {text[:20]!r}... give {len(items)} weights, more than {MAX_WEIGHTS}")
            w = np.array([float(v) for v in items])
    except (ValueError, TypeError, AttributeError, OverflowError) as exc:
        if str(exc).startswith("weights "):
            raise
        raise ValueError(f"weights must be start:stop:step or a comma list, got {show(text)}") from None
    if w.size == 0 or not np.all(np.isfinite(w)) or w.min() < 0 or w.max() > 1:
        raise ValueError(f"weights must lie in [0, 1], got {text!r}")
    return np.round(w, 12)


def stroke(name_min: str, q_min, name_max: str, q_max, positive: bool = True):
    """An actuator range ``(lo, hi)`` with ``lo < hi``: strut lengths (``positive``)
    or slider positions (any sign, as :func:`coordinate`).

    Parameters
    ----------
    name_min : str
        The lower limit's name.
    q_min : object
        The lower limit [L].
    name_max : str
        The upper limit's name.
    q_max : object
        The upper limit [L].
    positive : bool
        Strut lengths (positive) or slider positions (any sign).

    Returns
    -------
    lo, hi : float
        The range [L].

    Raises
    ------
    ValueError
        One line, for invalid limits or ``lo >= hi``.
    """
    check = positive_length if positive else coordinate
    lo, hi = check(name_min, q_min), check(name_max, q_max)
    if not hi > lo:
        raise ValueError(f"{name_max} must be greater than {name_min} = {lo!r}, got {q_max!r}")
    return lo, hi
