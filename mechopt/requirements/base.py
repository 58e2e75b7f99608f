"""The protocol of the requirements and objectives of ``mechopt design``.

A requirement is a bound that must hold over the WHOLE task; an objective is a
quantity the search minimises or maximises. Each lives in one module of
:mod:`mechopt.requirements` and declares every member below; the registry
(:func:`mechopt.requirements.registry`) lists them, the design evaluator
(:class:`mechopt.analysis.design_eval.DesignEvaluator`) loops over the active ones,
the problem takes one constraint column ``g_<name>`` per active requirement and one
objective per chosen objective, and the ``design`` command's options are generated
from the :class:`Option` declarations. A new requirement is one new module.

What every member receives at evaluation is the design's sample context
(:class:`mechopt.analysis.design_context.DesignContext`): the design's mechanism
``ctx.mech``, its design spec ``ctx.spec``, the requirements ``ctx.req``, the task's
samples (boundary points, interior grid, both), the values shared between members
(the Jacobians, LCI and type-II function at the samples, computed once), the
searches that refine a minimum over the task (``ctx.region_min``,
``ctx.region_mins``, ``ctx.leg_ranges``) and a memo (``ctx.memo``) through which
two members share a refined value (the ``lci`` requirement and the ``min-lci``
objective, say).

Units: lengths in the task's unit [L], angles in rad, forces in N, torques in N m
(cranks) or N (sliders); ``unit`` strings use the templates ``{L}`` (the task's
length unit) and ``{T}`` (N m or N).
"""
from __future__ import annotations

import math

__all__ = ["Option", "Requirement", "Objective", "Member"]


class Option:
    """One parameter of :class:`~mechopt.requirements.Requirements` (a keyword of it in
    Python, the option ``--<name with dashes>`` of ``mechopt design``).

    Parameters
    ----------
    name : str
        The keyword, a Python identifier (``min_lci``).
    help : str
        One line for ``--help``, with the unit in the user's terms.
    check : callable, optional
        ``check(value, spec) -> value``: validates the Python value (angles in rad,
        lengths in the task's unit) for the mechanism's design spec and returns it
        normalised; raises ValueError with one line naming the problem. Default: a
        positive finite number.
    parse : callable, optional
        ``parse(text) -> value``: the command-line text to the Python value (degrees to
        rad, for instance). Default: a float.
    metavar : str, optional
        The option's metavar in ``--help``.
    default : object
        The value when the option is not given (None switches it off).
    cli : bool
        False for a Python-only parameter (no command-line option).
    kind : str, optional
        The kind of quantity (``"length"``, ``"speed"``, ``"force"``, ``"effort"``,
        ``"rate"``: :func:`mechopt.core.units.base_unit`): the value may then carry a
        unit (``0.5m/s``, ``2Nm``; a :class:`mechopt.core.units.Quantity` or such a
        string in Python), converted to the option's unit when checked; a bare
        number is in that unit.
    per_actuator : bool
        True for a value given once for both actuators or once per actuator: one value
        or two (``3,2.5`` on the command line, a pair in Python), each checked on its
        own; the checked value is a float for one, a tuple of two floats for two.
    """

    def __init__(self, name, help, check=None, parse=None, metavar=None, default=None, cli=True, kind=None,
                 per_actuator=False):
        self.name, self.help, self.metavar, self.default, self.cli = name, help, metavar, default, cli
        self.kind, self.per_actuator = kind, per_actuator
        self._check, self._parse = check, parse

    @property
    def flag(self) -> str:
        """The command-line option (``--min-lci``)."""
        return "--" + self.name.replace("_", "-")

    def check(self, value, spec, unit="mm"):
        """The validated value (see the class docstring) for a task in ``unit``."""
        if self.per_actuator:
            values = tuple(self._check_one(v, spec, unit) for v in self._values(value))
            return values[0] if len(values) == 1 else values
        return self._check_one(value, spec, unit)

    def _values(self, value) -> tuple:
        """The one or two values of a per-actuator option (a text split at commas)."""
        from mechopt.core import validation as _v

        if isinstance(value, str):
            items = tuple(v.strip() for v in value.split(","))
        elif isinstance(value, (tuple, list)) or (hasattr(value, "shape") and getattr(value, "ndim", 0) == 1):
            items = tuple(value)
        else:
            items = (value,)
        if len(items) not in (1, 2):
            raise ValueError(f"{self.name} takes one value (both actuators) or two (one per actuator), "
                             f"got {_v.show(value)}")
        return items

    def _check_one(self, value, spec, unit):
        from mechopt.core import units as _u
        from mechopt.core import validation as _v

        if self.kind is not None:
            if isinstance(value, str):
                value = _u.parse(value, self.name)
            value = _u.to_base(value, self.kind, unit, spec.angular, self.name)
        if self._check is not None:
            return self._check(value, spec)
        return _v.positive_length(self.name, value)

    def parse(self, text):
        """The Python value of the option's command-line ``text`` (a
        :class:`mechopt.core.units.Quantity` for an option with a ``kind``; a tuple of two
        for two values of a per-actuator option)."""
        if self.per_actuator:
            values = tuple(self._parse_one(v) for v in self._values(str(text)))
            return values[0] if len(values) == 1 else values
        return self._parse_one(text)

    def _parse_one(self, text):
        from mechopt.core import units as _u
        from mechopt.core import validation as _v

        if self._parse is not None:
            return self._parse(text)
        if self.kind is not None:
            return _u.parse(text, self.flag)
        return _v.finite_number(self.flag, text)

    def __repr__(self):
        return f"Option({self.name!r})"


class Member:
    """What requirements and objectives share: a name, the options they read, and the
    values they report into an evaluation's ``values`` (design.json)."""

    #: the name (``margin_<name>`` and ``g_<name>`` of a requirement; the objective's name)
    name: str = ""
    #: the options this member declares (each declared by exactly one member)
    options: tuple = ()
    #: what it needs from the sample context (documentation and the contract tests):
    #: some of "points", "clearance", "type2", "jacobian", "singular_values", "ik",
    #: "joints", "strokes"
    needs: tuple = ()

    def applies(self, spec) -> bool:
        """True when the member applies to the mechanism of design spec ``spec``."""
        return True

    def report(self, ctx) -> dict:
        """Values this member reports into the evaluation's ``values`` whether or not it
        is active (default none); it may read ``ctx.memo`` to report only what another
        member computed."""
        return {}

    def __repr__(self):
        return f"{type(self).__name__}({self.name!r})"


class Requirement(Member):
    """A bound over the whole task (module docstring). Subclasses set the class
    attributes and implement :meth:`evaluate` (and :meth:`describe`)."""

    #: how the value is certified over a region and along a path (the argument, in words;
    #: design.json's ``tolerance`` and the docs quote it)
    certificate: str = ""
    #: what ``margin_<name>`` means, and its unit template
    margin_text: str = ""
    margin_unit: str = "-"
    #: True for a requirement that is always active (reach, singular)
    always: bool = False
    #: True when :attr:`certificate` is a proof over the whole task (not a located minimum)
    proven: bool = False

    def active(self, req, spec) -> bool:
        """True when the requirement is asked for: always, or when its first option is set."""
        if not self.applies(spec):
            return False
        return self.always or (bool(self.options) and getattr(req, self.options[0].name) is not None)

    def describe(self, req, unit) -> str:
        """The requirement in words, with its values (for messages)."""
        return self.name

    def precheck(self, req, spec, unit) -> None:
        """Refuse, before any run, requirements no geometry can meet (a necessary
        condition; raise ValueError with one line giving the reason). Default none."""

    def screen(self, ctx) -> bool:
        """Whether the design is feasible or nearly so by this requirement on the samples
        alone: refining the minima (``ctx.refine``) is worth it only when every active
        requirement's screen passes. Default True."""
        return True

    def evaluate(self, ctx) -> tuple:
        """``(margin, g)``: the margin in natural units (> 0 satisfied) and the normalised
        constraint ``g`` (<= 0 satisfied, NaN fails)."""
        raise NotImplementedError

    def columns(self, derived) -> dict:
        """Extra front.csv columns from the evaluation's ``derived`` values (default none)."""
        return {}

    def record(self, derived) -> dict:
        """Extra design.json keys from the evaluation's ``derived`` values (default none)."""
        return {}


class Objective(Member):
    """A quantity to optimise. Subclasses set the class attributes and implement
    :meth:`value`. A value the design does not define (a torque without force
    capacity) is NaN, only on designs some requirement already makes infeasible
    (``g > 0``); pymoo never reads the objectives of an infeasible row (its survival
    and tournaments rank infeasible rows by constraint violation alone)."""

    #: +1 minimised, -1 maximised
    sense: int = 1
    #: unit template ({L}, {T})
    unit: str = "-"
    description: str = ""
    #: options that must be given for the objective (the actuators' limits, a payload)
    requires: tuple = ()

    def value(self, ctx) -> float:
        """The objective's value over the task [its unit], NaN where undefined."""
        raise NotImplementedError

    def bounds(self, ev) -> tuple:
        """``(lo, hi)``: the reference range of the value for the hypervolume of
        history.csv (:class:`mechopt.run.problem.Objective`), from the evaluator ``ev``'s
        bounds (``ev.max_length``, ``ev.req``, the task); values outside it are allowed."""
        return (0.0, 1.0)

    def invalid_value(self, ev, lengths) -> float:
        """The value reported for a design whose variables describe no mechanism (every
        constraint violated, so never read by the search's ranking): NaN by default."""
        return math.nan
