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
        """The validated value (see the class docstring) for a task in ``unit``.

        Parameters
        ----------
        value : object
            The option's value (a number, a text or a quantity with a unit; one or two
            for a per-actuator option).
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.
        unit : str
            The task's length unit.

        Returns
        -------
        object
            The checked value in the option's unit (a float, or what ``check`` returns; a
            tuple of two for two values of a per-actuator option).
        """
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
        for two values of a per-actuator option).

        Parameters
        ----------
        text : str
            The command-line text.

        Returns
        -------
        object
            The Python value (a float by default).
        """
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
        """Whether the member applies to a mechanism.

        Parameters
        ----------
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.

        Returns
        -------
        bool
            True when the member applies to that mechanism (default: always).
        """
        return True

    def report(self, ctx) -> dict:
        """Values this member reports into the evaluation's ``values``, active or not.

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context; ``ctx.memo`` holds what other members
            computed (report only what is there, to cost nothing).

        Returns
        -------
        dict
            ``{name: value}`` in the member's units (default: empty).
        """
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
        """Whether the requirement is asked for.

        Parameters
        ----------
        req : mechopt.requirements.Requirements
            The requirements of the run.
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.

        Returns
        -------
        bool
            True when it applies to the mechanism and is always on (:attr:`always`)
            or its first option is set (not None).
        """
        if not self.applies(spec):
            return False
        return self.always or (bool(self.options) and getattr(req, self.options[0].name) is not None)

    def describe(self, req, unit) -> str:
        """The requirement in words, with its values (for messages).

        Parameters
        ----------
        req : mechopt.requirements.Requirements
            The requirements of the run.
        unit : str
            The task's length unit, for the values' units.

        Returns
        -------
        str
            One clause, e.g. ``"stroke <= 200.0 mm"`` (default: the name).
        """
        return self.name

    def precheck(self, req, spec, unit) -> None:
        """Refuse, before any run, requirements no geometry can meet.

        A necessary condition only (default: none).

        Parameters
        ----------
        req : mechopt.requirements.Requirements
            The checked requirements.
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.
        unit : str
            The task's length unit.

        Raises
        ------
        ValueError
            One line giving the reason, when no design can meet the requirement.
        """

    def screen(self, ctx) -> bool:
        """Whether the design is feasible or nearly so by this requirement on the
        samples alone.

        Refining the minima (``ctx.refine``) is worth it only when every active
        requirement's screen passes.

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context.

        Returns
        -------
        bool
            False when the samples already show the requirement clearly violated
            (default: True).
        """
        return True

    def settled(self, ctx) -> bool:
        """Whether the samples alone show the requirement comfortably met, so that the
        search need not refine its minimum (:attr:`Sampling.settle
        <mechopt.analysis.sampling.Sampling.settle>`; the certification always refines).

        A requirement says True only when its sampled margin exceeds many times the
        largest change refinement made on the examples, and when no chosen objective
        reads the same minimum. Soundness does not rest on it: only the sign of ``g``
        reaches the search, and every front design is certified afterwards with the
        refined minima (a wrongly settled design would be dropped there, not
        claimed).

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context.

        Returns
        -------
        bool
            True when the minimum may stay unrefined (default: False).
        """
        return False

    def evaluate(self, ctx) -> tuple:
        """The requirement's margin and constraint for one design over the task.

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context (mechanism, spec, requirements, placed task,
            samples, shared values, refinement searches).

        Returns
        -------
        margin : float
            The margin in natural units [:attr:`margin_unit`], > 0 satisfied.
        g : float
            The normalised constraint, <= 0 satisfied; NaN fails.

        Raises
        ------
        NotImplementedError
            In the base class: every requirement implements it.
        """
        raise NotImplementedError

    def columns(self, derived) -> dict:
        """Extra front.csv columns of this requirement.

        Parameters
        ----------
        derived : dict
            The evaluation's derived values (strokes, refined minima, bounds).

        Returns
        -------
        dict
            ``{column: value}`` (default: empty).
        """
        return {}

    def record(self, derived) -> dict:
        """Extra design.json keys of this requirement.

        Parameters
        ----------
        derived : dict
            The evaluation's derived values.

        Returns
        -------
        dict
            ``{key: value}`` (default: empty).
        """
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
        """The objective's value for one design over the task.

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context.

        Returns
        -------
        float
            The value [:attr:`unit`] in its natural sign (:attr:`sense` turns it into
            pymoo's minimisation form); NaN where the design does not define it.

        Raises
        ------
        NotImplementedError
            In the base class: every objective implements it.
        """
        raise NotImplementedError

    def bounds(self, ev) -> tuple:
        """The reference range of the value, for the hypervolume of history.csv.

        Parameters
        ----------
        ev : mechopt.analysis.design_eval.DesignEvaluator
            The evaluator, whose bounds (``ev.max_length``, ``ev.req``, the task) set
            the range.

        Returns
        -------
        tuple of float
            ``(lo, hi)`` [:attr:`unit`] (:class:`mechopt.run.problem.Objective`);
            values outside it are allowed (default ``(0, 1)``).
        """
        return (0.0, 1.0)

    def invalid_value(self, ev, lengths) -> float:
        """The value reported for a design whose variables describe no mechanism.

        Every constraint of such a design is violated, so the search's ranking never
        reads it.

        Parameters
        ----------
        ev : mechopt.analysis.design_eval.DesignEvaluator
            The evaluator.
        lengths : array_like
            The design's lengths [L].

        Returns
        -------
        float
            NaN by default.
        """
        return math.nan
