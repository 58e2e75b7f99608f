"""Values with units on the command line: ``0.5m/s``, ``500mm/s``, ``2Nm``, ``20um``.

A requirement's option (:class:`mechopt.requirements.base.Option`) names the kind of
quantity it takes (:data:`KINDS`); :func:`parse` reads the command-line text into a
:class:`Quantity` (a number and the unit written after it, or no unit) and
:func:`to_base` converts it into the unit the option is stated in: the task's length
unit for lengths and speeds, N for forces, N m (cranks) or N (sliders) for actuator
efforts, rad/s (cranks) or the task's unit per second (sliders) for actuator rates. A
bare number is already in that unit. Conversions are exact decimal factors (SI).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

from mechopt.core import validation as _v

__all__ = ["Quantity", "KINDS", "parse", "to_base", "base_unit"]

#: length units in micrometres (integers: a conversion between two of them is one
#: multiplication and one division of exact numbers, ``0.5 m -> 500 mm`` exactly)
LENGTH = {"m": 1_000_000, "cm": 10_000, "mm": 1_000, "um": 1, "µm": 1, "in": 25_400}

#: kind -> {unit: factor to the kind's unit: um, um/s, N, N m, rad/s}
KINDS = {
    "length": dict(LENGTH),
    "speed": {f"{u}/s": f for u, f in LENGTH.items()},
    "force": {"N": 1.0, "kN": 1e3, "mN": 1e-3},
    "torque": {"Nm": 1.0, "N.m": 1.0, "N*m": 1.0, "Nmm": 1e-3, "mNm": 1e-3, "kNm": 1e3},
    "angular_speed": {"rad/s": 1.0, "rpm": 2.0 * math.pi / 60.0, "deg/s": math.pi / 180.0},
}

_NUMBER = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


@dataclass(frozen=True)
class Quantity:
    """A number with the unit written after it (``unit`` empty for a bare number).

    Parameters
    ----------
    value : float
        The number.
    unit : str
        The unit as written (empty: none).
    """

    value: float
    unit: str = ""

    def __str__(self):
        return f"{self.value:g}{self.unit}"


def parse(text, what) -> Quantity:
    """``"0.5m/s"`` -> ``Quantity(0.5, "m/s")``; spaces inside the unit are dropped
    (``"2 N m"`` is ``"2Nm"``). ``what`` names the option in the error.

    Parameters
    ----------
    text : str
        A number with an optional unit (``"0.5m/s"``).
    what : str
        The option's name, for the message.

    Returns
    -------
    Quantity
        The number and its unit.

    Raises
    ------
    ValueError
        One line, for text that is not a number with an optional unit.
    """
    m = _NUMBER.fullmatch(str(text))
    if not m:
        raise ValueError(f"{what} must be a number with an optional unit (e.g. 0.5m/s), got {text!r}")
    value = _v.finite_number(what, float(m.group(1)))
    return Quantity(value, m.group(2).replace(" ", ""))


def base_unit(kind, task_unit, angular) -> str:
    """The unit an option of ``kind`` is stated in, for a task in ``task_unit``.

    Parameters
    ----------
    kind : str
        ``"length"``, ``"speed"``, ``"force"``, ``"effort"`` or ``"rate"``.
    task_unit : str
        The task's length unit.
    angular : bool
        Whether the actuators are cranks (efforts in N m, rates in rad/s) or sliders.

    Returns
    -------
    str
        The unit (``"mm/s"``, ``"N m"``, ...).
    """
    return {"length": task_unit, "speed": f"{task_unit}/s", "force": "N",
            "effort": "N m" if angular else "N",
            "rate": "rad/s" if angular else f"{task_unit}/s"}[kind]


def to_base(q, kind, task_unit, angular, what) -> float:
    """``q`` (a :class:`Quantity` or a number) in :func:`base_unit` of ``kind``.

    Parameters
    ----------
    q : Quantity or float
        The value (a bare number is already in the base unit).
    kind : str
        ``"length"``, ``"speed"``, ``"force"``, ``"effort"`` or ``"rate"``.
    task_unit : str
        The task's length unit.
    angular : bool
        Whether the actuators are cranks (efforts in N m, rates in rad/s) or sliders.
    what : str
        The option's name, for the message.

    Returns
    -------
    float
        The value in :func:`base_unit`.

    Raises
    ------
    ValueError
        One line, for a unit that is not one of the kind's.
    """
    if not isinstance(q, Quantity):
        return q
    if not q.unit:
        return q.value
    # an actuator's effort is a torque on a crank, a force on a slider; its rate an
    # angular speed or a speed
    table = {"effort": "torque" if angular else "force", "rate": "angular_speed" if angular else "speed"}.get(kind, kind)
    units = KINDS[table]
    if q.unit not in units:
        raise ValueError(f"{what}: unknown unit {q.unit!r} for a {table.replace('_', ' ')}; use one of "
                         f"{', '.join(units)}")
    value = q.value * units[q.unit]
    # lengths and speeds back from micrometres to the task's unit
    return value / LENGTH[task_unit] if table in ("length", "speed") else value
