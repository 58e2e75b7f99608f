"""Requirements and objectives of ``mechopt design``, one module each.

Each module declares its members on the protocol of :mod:`mechopt.requirements.base`
(:class:`~mechopt.requirements.base.Requirement`,
:class:`~mechopt.requirements.base.Objective`, their
:class:`~mechopt.requirements.base.Option` declarations) in a tuple ``MEMBERS``;
:data:`MODULES` lists the modules in the order of the constraint columns, and
:func:`registry` collects them. The design evaluator, the problem and the command
line read the registry alone: a new requirement is one new module added to
:data:`MODULES` (or, in a test, to a monkeypatched copy of it).

- ``reach``: requirement reach (always)
- ``singular``: requirement singular (always; ``singularity_margin``)
- ``lci``: requirement lci (``--min-lci``); objectives min-lci, mean-lci
- ``joints``: requirement joints (``--joint-limits``, cranks)
- ``link_angle``: requirement link_angle (``--link-angle``)
- ``stroke``: requirement stroke (``--max-stroke``, sliders)
- ``lengths``: requirement lengths (bipod struts, always)
- ``speed``: requirement speed (``--min-speed``, ``--actuator-speed``, ``--actuator-norm``); objective speed
- ``force``: requirement force (``--min-force``, ``--actuator-torque``); objective force
- ``torque``: objective torque (``--payload``)
- ``accuracy``: requirement error (``--max-error``); objective error
- ``size``: objectives size, footprint
- ``collisions``: requirements clearance (``--min-clearance``), joint_angle (``--min-joint-angle``),
  keep_out (``--keep-out``), base (``--min-base``, ``--motor-diameter``); objective clearance
- ``motion``: requirements peak_torque (``--max-torque``, ``--cycle-time``), rms_torque
  (``--max-rms-torque``); objectives peak-torque, rms-torque, moving-mass

:class:`Requirements` holds the values of every declared option (a requirement is
off while its first option is None).
"""
from __future__ import annotations

import importlib

from mechopt.requirements.base import Objective, Requirement

__all__ = ["MODULES", "Requirements", "registry", "requirements", "objectives", "options", "objective"]

#: the member modules, in the order of the constraint columns (``g_<name>``, ``margin_<name>``)
MODULES = tuple(f"mechopt.requirements.{m}" for m in (
    "reach", "singular", "lci", "joints", "link_angle", "stroke", "lengths", "speed", "force", "torque", "accuracy",
    "size", "collisions", "motion"))


def registry() -> tuple:
    """Every declared member (requirements and objectives).

    Returns
    -------
    tuple
        The ``MEMBERS`` of each module of :data:`MODULES`, in that order.
    """
    members = []
    for name in MODULES:
        members.extend(importlib.import_module(name).MEMBERS)
    return tuple(members)


def requirements() -> tuple:
    """The declared requirements.

    Returns
    -------
    tuple of mechopt.requirements.base.Requirement
        In constraint order (the columns ``g_<name>``).
    """
    return tuple(m for m in registry() if isinstance(m, Requirement))


def objectives() -> dict:
    """The declared objectives.

    Returns
    -------
    dict
        ``{name: Objective}`` in registry order.
    """
    return {m.name: m for m in registry() if isinstance(m, Objective)}


def objective(name) -> Objective:
    """The declared objective ``name``.

    Parameters
    ----------
    name : str
        An objective's name (``"size"``, ``"min-lci"``, ...).

    Returns
    -------
    mechopt.requirements.base.Objective
        The objective.

    Raises
    ------
    ValueError
        One line naming the known objectives, for an unknown name.
    """
    from mechopt.core import validation as _v

    known = objectives()
    return known[_v.choice("objective", name, tuple(known))]


def options() -> dict:
    """Every declared option and the member that declares it.

    Returns
    -------
    dict
        ``{name: (Option, member)}`` in registry order.

    Raises
    ------
    ValueError
        When two members declare an option of the same name.
    """
    out = {}
    for m in registry():
        for o in m.options:
            if o.name in out:
                raise ValueError(f"option {o.name!r} is declared twice ({out[o.name][1]!r} and {m!r})")
            out[o.name] = (o, m)
    return out


class Requirements:
    """What must hold over the whole task: one keyword per declared option
    (:func:`options`; lengths in the task's unit, angles in rad, speeds in [L]/s or
    rad/s, forces in N, torques in N m or N). ``None`` switches a requirement off;
    reachability in one working mode without crossing a type-II singularity is always
    required. Immutable and hashable.

    The built-in keywords: ``min_lci`` (LCI >= gamma over the task, gamma in (0, 1)),
    ``joint_limits`` (``((lo1, hi1), (lo2, hi2))`` or one ``(lo, hi)`` [rad], the
    cranks as :meth:`FiveBar.ik <mechopt.mechanisms.five_bar.model.FiveBar.ik>` returns
    them), ``link_angle`` (``(lo, hi)`` [rad] of each link from the slider direction,
    Wu 2008 eq. 1, 13), ``max_stroke`` [L], ``min_speed`` [L/s] with ``actuator_speed``
    [rad/s or L/s], ``min_force`` [N] with ``actuator_torque`` [N m or N], ``payload``
    [N] (the ``torque`` objective) and ``singularity_margin`` (smallest ``|sine of the
    angle between the legs|``, default 1e-3).

    Parameters
    ----------
    **values
        One keyword per declared option (:func:`options`), in the units above; an
        option not given takes its declared default.

    Raises
    ------
    ValueError
        One line naming an unknown keyword and the known ones.
    """

    __slots__ = ("_values",)

    def __init__(self, **values):
        declared = options()
        unknown = sorted(set(values) - set(declared))
        if unknown:
            raise ValueError(f"unknown requirement {unknown[0]!r}; known: {', '.join(declared)}")
        object.__setattr__(self, "_values",
                           {n: values.get(n, o.default) for n, (o, _) in declared.items()})

    def __getattr__(self, name):
        try:
            return object.__getattribute__(self, "_values")[name]
        except KeyError:
            raise AttributeError(f"Requirements has no option {name!r}") from None

    def __setattr__(self, name, value):
        raise AttributeError("Requirements is immutable: use replace()")

    def __reduce__(self):
        return (_rebuild, (dict(self._values),))

    def __eq__(self, other):
        return isinstance(other, Requirements) and self._values == other._values

    def __hash__(self):
        return hash(repr(self))

    def __repr__(self):
        return "Requirements(" + ", ".join(f"{k}={v!r}" for k, v in self._values.items()) + ")"

    def asdict(self) -> dict:
        """The values of every declared option.

        Returns
        -------
        dict
            ``{option: value}`` (None: off).
        """
        return dict(self._values)

    def replace(self, **changes) -> "Requirements":
        """A copy with some values changed.

        Parameters
        ----------
        **changes
            ``option=value`` pairs.

        Returns
        -------
        Requirements
            The new requirements (this one is immutable).
        """
        return Requirements(**{**self._values, **changes})

    def checked(self, spec, unit="mm") -> "Requirements":
        """The requirements validated for the mechanism of design spec ``spec`` and a task
        in ``unit`` (each option's check, values with units converted; an option of a
        requirement that does not apply to it, or a requirement missing the options it
        needs, is refused with one line). A member's ``implied(values, spec, unit)``
        fills options left None from others (``--actuator``'s datasheet gives the
        actuators' limits).

        Parameters
        ----------
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.
        unit : str
            The task's length unit.

        Returns
        -------
        Requirements
            The checked values, with units converted and implied options filled in.

        Raises
        ------
        ValueError
            One line, for an invalid value, an option of a requirement that does not
            apply to the mechanism, or a requirement missing an option it needs.
        """
        kw = {}
        for name, (opt, member) in options().items():
            value = self._values[name]
            if value is None:
                kw[name] = None
                continue
            if not member.applies(spec):
                raise ValueError(_not_applicable(member, opt, spec))
            kw[name] = opt.check(value, spec, unit)
        for member in registry():  # values implied by another option (an actuator's datasheet)
            implied = getattr(member, "implied", None)
            for name, value in (implied(kw, spec, unit) if implied else {}).items():
                if kw[name] is None:
                    kw[name] = value
        out = Requirements(**kw)
        for member in requirements():
            for needed in getattr(member, "needs_options", ()):
                if member.active(out, spec) and getattr(out, needed) is None:
                    raise ValueError(f"{member.options[0].name} needs {needed} (the actuators' limit)")
        return out

    def names(self, spec) -> tuple:
        """The names of the active requirements.

        Parameters
        ----------
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.

        Returns
        -------
        tuple of str
            In constraint order.
        """
        return tuple(r.name for r in requirements() if r.active(self, spec))

    def describe(self, name, unit) -> str:
        """A requirement in words (for messages).

        Parameters
        ----------
        name : str
            The requirement's name.
        unit : str
            The task's length unit.

        Returns
        -------
        str
            Its :meth:`~mechopt.requirements.base.Requirement.describe`.
        """
        return next(r for r in requirements() if r.name == name).describe(self, unit)


def _rebuild(values):
    return Requirements(**values)


def _not_applicable(member, opt, spec) -> str:
    """The one-line refusal of an option whose requirement does not apply to ``spec``."""
    from mechopt import mechanisms as _mechanisms

    where = [n for n in _mechanisms.designed() if member.applies(_mechanisms.design_spec(n))]
    hint = getattr(member, "instead", "")
    return (f"{opt.name} applies to {' and '.join('the ' + n for n in where)}, not the {spec.name}"
            + (f": use {hint}" if hint else ""))
