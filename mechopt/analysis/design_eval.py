"""Evaluate a design of any mechanism against a task: the variables, the sample
context and the loop over the requirements and objectives of
:mod:`mechopt.requirements`.

A designer starts from a task ("cover this 100 x 60 mm rectangle 180 mm in front
of the base with LCI >= 0.4 everywhere, links at most 250 mm"), not from a
non-dimensional atlas. :class:`DesignEvaluator` states such a problem on the shared
evaluators; :func:`mechopt.workflows.design.design` solves it with the seeded runner
and certifies every front design with a finer sampling (:func:`certify`).

* the task (:class:`mechopt.analysis.task.Task`), placed ``"fixed"``, ``"free-y"``
  (moved along y; for a five-bar of one working mode the design workflow searches
  above the base line and, ``side="below"``, below it: :meth:`DesignEvaluator._y_range`)
  or ``"free"`` (moved in x and y);
* the requirements (:class:`mechopt.requirements.Requirements`), which must hold
  over the WHOLE task, each certified as its module states;
* the objectives (:func:`mechopt.requirements.objectives`), any non-empty subset.

Mechanisms (:func:`mechanisms`) and their design variables, in the task's unit. Each
mechanism states them in its own module, as its
:attr:`~mechopt.core.protocol.PlanarMechanism.design_spec` (a
:class:`~mechopt.core.design_spec.DesignSpec`); :func:`get_spec` finds them through
:func:`mechopt.mechanisms.registry`:

===================  ====================================  ===========================================
name                 variables                             derived
===================  ====================================  ===========================================
asymmetric-five-bar  a1, c1, a2, c2, r3 (or D with         crank ranges
                     ``shape``), mode with ``mode="any"``
biglide              l1, l2 (mode ``"--"`` ... ``"-+"``)   strokes: the q range over the task
bipod                b (branch ``"up"``/``"down"``)        strut strokes: the q range over the task
five-bar             r1, r2, r3 (or D with ``shape``),     crank ranges
                     mode with ``mode="any"``
gantry               d1, l (mode ``"--"`` ...)             q_min, stroke: the q range over the task
===================  ====================================  ===========================================

For the slider/strut mechanisms the strokes are not searched: the smallest stroke
that covers the task is the range of each actuator coordinate over the task, and
that range is attained on the task's boundary (:mod:`mechopt.requirements.stroke`).

One evaluation (:meth:`DesignEvaluator.evaluate`): the design's mechanism and the
task's samples (:mod:`mechopt.analysis.sampling`) make a
:class:`~mechopt.analysis.design_context.DesignContext`; every active requirement
screens the design on the samples (a design far from feasible is not refined;
with the search's sampling, a requirement the samples show comfortably met is not
refined either: :meth:`~mechopt.requirements.base.Requirement.settled`),
then gives its margin and ``g``; every chosen objective its value; every member
the values it reports. Constraints are ``G <= 0`` and normalised (lengths by the task
diameter, angles by pi, LCI by gamma, speed and force by their required values); an
infeasible design has ``G > 0`` telling how far it is from feasible.
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import validation as _v
from mechopt import mechanisms as _mechanisms
from mechopt import requirements as _req
from mechopt.analysis import sampling as _s
from mechopt.analysis.design_context import DesignContext
from mechopt.analysis.sampling import Sampling
from mechopt.analysis.task import PLACEMENTS, Task
from mechopt.core.design_spec import DesignSpec
from mechopt.requirements import Requirements

__all__ = ["DesignEvaluator", "NoFeasibleDesign", "certify", "feasible", "knee_index",
           "parse_weights", "parse_pick", "pick_index", "get_spec", "mechanisms", "sensitivity"]

#: the relative step of :func:`sensitivity` (link lengths, placement, actuator limits)
SENSITIVITY_STEP = 0.1

#: placements whose samples a :class:`DesignEvaluator` keeps (:meth:`DesignEvaluator._samples_at`)
_CONTEXTS_KEPT = 8


class NoFeasibleDesign(ValueError):
    """No design satisfies the requirements; ``info`` holds the least-violating one."""

    def __init__(self, message, info=None):
        super().__init__(message)
        self.info = info or {}


def mechanisms() -> tuple[str, ...]:
    """Names of the mechanisms ``mechopt design`` sizes (:func:`mechopt.mechanisms.designed`).

    Returns
    -------
    tuple of str
        The names.
    """
    return _mechanisms.designed()


def get_spec(name) -> DesignSpec:
    """The design specification of mechanism ``name`` (one of :func:`mechanisms`).

    Parameters
    ----------
    name : str
        A designed mechanism.

    Returns
    -------
    mechopt.core.design_spec.DesignSpec
        Its spec.
    """
    return _mechanisms.design_spec(name)


class DesignEvaluator:
    """Evaluates one design (a dict of variables) against a task: every requirement's
    margin, every objective, the derived strokes. Picklable (travels to workers).

    Parameters
    ----------
    mechanism : str
        A designed mechanism.
    task : mechopt.analysis.task.Task
        The task [L].
    requirements : mechopt.requirements.Requirements
        What must hold over the task.
    objectives : sequence of str
        Objective names.
    mode : str, optional
        Working mode or ``"any"``.
    place : str
        ``"fixed"``, ``"free-y"`` or ``"free"``.
    min_length, max_length : float, optional
        Link length bounds [L].
    shape : sequence of float, optional
        Fixed link ratios.
    side : str
        ``"above"`` or ``"below"``: the side of the base line where a free placement
        searched above it is placed (``"below"``: its mirror image; no effect on a fixed
        placement or a mechanism placed around the task's own height).

    Raises
    ------
    ValueError
        One line, for invalid inputs or requirements no geometry can meet.
    """

    def __init__(self, mechanism, task: Task, requirements: Requirements, objectives, mode=None,
                 place="fixed", min_length=None, max_length=None, shape=None, side="above"):
        self.spec = get_spec(mechanism)
        if not isinstance(task, Task):
            raise ValueError(f"task must be a mechopt.analysis.task.Task, got {type(task).__name__}")
        self.task = task
        self.unit = task.unit
        self.req = (requirements or Requirements()).checked(self.spec, self.unit)
        objectives = (objectives,) if isinstance(objectives, str) else tuple(objectives)
        known = _req.objectives()
        if not objectives:
            raise ValueError(f"objectives must name at least one of {', '.join(known)}")
        for ob in objectives:
            _v.choice("objective", ob, tuple(known))
        if len(set(objectives)) != len(objectives):
            raise ValueError(f"objectives must not repeat, got {', '.join(objectives)}")
        for ob in objectives:
            for needed in known[ob].requires:
                if getattr(self.req, needed) is None:
                    flag = _req.options()[needed][0].flag
                    raise ValueError(f"objective {ob} needs {needed} ({flag})")
        #: the active requirements and the chosen objectives (members of mechopt.requirements)
        self.active = tuple(r for r in _req.requirements() if r.active(self.req, self.spec))
        for r in self.active:
            r.precheck(self.req, self.spec, self.unit)
        self._members = _req.registry()
        self._objectives = tuple(known[ob] for ob in objectives)
        self.objectives = objectives
        self.place = _v.choice("place", place, PLACEMENTS)
        if mode in (None, ""):
            mode = self.spec.default_mode
        self.mode_any = mode == "any"
        self.mode = None if self.mode_any else _v.choice("mode", mode, self.spec.modes)
        D = task.diameter
        self.max_length = (_v.positive_length("max_length", max_length) if max_length is not None
                           else 4.0 * max(D, float(np.abs(task.bbox).max())))
        self.min_length = (_v.positive_length("min_length", min_length) if min_length is not None
                           else self.max_length / 1000.0)
        if not self.min_length < self.max_length:
            raise ValueError(f"min_length ({self.min_length:g}) must be below max_length ({self.max_length:g})")
        self.shape = None
        if shape is not None:
            s = _v.finite_numbers("shape", shape, len(self.spec.lengths),
                                  f"{len(self.spec.lengths)} ratios ({', '.join(self.spec.lengths)})")
            if not all(x >= 0 for x in s) or max(s) <= 0:
                raise ValueError(f"shape ratios must be >= 0 and not all 0, got {_v.show(shape)}")
            self.shape = s
        self._precheck()
        self._side = side
        self._build_vars()
        self._contexts = {}  # placement -> samples (_samples_at)

    # --- variables -------------------------------------------------------------------
    def _build_vars(self):
        """pymoo variables: each length ``L`` as ``ln_L = ln(L + c)`` with ``c = min_length``
        (a log scale: the optimiser resolves small and large designs alike, and a
        length may reach 0, e.g. the five-bar's half base), the mode index with
        ``mode="any"``, the task placement ``task_x``/``task_y`` when free."""
        lo = self.spec.lower_bounds(self.min_length)
        c = self._c = self.min_length
        names, xl, xu = [], [], []
        if self.shape is None:
            names += [f"ln_{n}" for n in self.spec.lengths]
            xl += [math.log(v + c) for v in lo]
            xu += [math.log(self.max_length + c)] * len(lo)
        else:
            names.append("ln_D")
            pos = [s for s in self.shape if s > 0]
            xl.append(math.log(self.min_length / min(pos) + c))
            xu.append(math.log(self.max_length / max(self.shape) + c))
        if self.mode_any:
            names.append("mode")
            xl.append(0.0)
            xu.append(len(self.spec.modes) - _v.RESOLUTION)
        # the placement relative to the design's own reach (spec.placement_scale):
        # task_y = y_lo + task_y_rel * scale, task_x = task_x_rel * scale
        x0, x1, y0, y1 = self.task.bbox
        self._half_height = 0.5 * (y1 - y0)
        self._y_lo = self._half_height if self.spec.placement_above_base(self.mode) else None
        #: a free placement to be searched on both sides of the base line: this search
        #: covers the ``side`` (``"above"`` or ``"below"``, :meth:`_y_range`), another the
        #: other side (:func:`mechopt.workflows.design.design`)
        self.both_sides = (self.place != "fixed" and self._y_lo is not None
                           and self.spec.placement_both_sides(self.mode))
        #: ``"below"`` mirrors a free placement searched above the base line (no effect
        #: on a fixed placement or a mechanism searched around the task's own height)
        self.side = _v.choice("side", self._side, ("above", "below"))
        if self.place == "free":
            names.append("task_x_rel")
            xl.append(-1.0)
            xu.append(1.0)
        if self.place in ("free", "free-y"):
            names.append("task_y_rel")
            xl.append(0.0)
            xu.append(1.0)
        self.var_names = tuple(names)
        self.xl, self.xu = np.array(xl, float), np.array(xu, float)

    def _precheck(self):
        """A task no design within the length bounds can reach is an input error."""
        R = self.spec.reach_radius(self.max_length)
        Xr = self.spec.x_reach(self.max_length)
        t, D = self.task, self.task.diameter
        x0, x1, y0, y1 = t.bbox
        far = float(np.abs([x0, x1, y0, y1]).max())
        u = self.unit
        if self.place == "fixed":
            if t.kind == "circle":
                dmax = math.hypot(*t.center) + t.radius
            else:
                p = t.vertices if t.vertices is not None else t.pts
                dmax = float(np.hypot(p[:, 0], p[:, 1]).max())
            if dmax > R:
                raise ValueError(f"the task reaches {dmax:g} {u} from the base midpoint; no {self.spec.name} "
                                 f"with links <= {self.max_length:g} {u} reaches beyond {R:g} {u} "
                                 f"(raise --max-length or move the task)")
            if max(abs(x0), abs(x1)) > Xr:
                raise ValueError(f"the task spans x in [{x0:g}, {x1:g}] {u}; no {self.spec.name} with links "
                                 f"<= {self.max_length:g} {u} reaches |x| > {Xr:g} {u}")
        elif self.place == "free-y":
            if max(abs(x0), abs(x1)) > min(R, Xr):
                raise ValueError(f"the task spans x in [{x0:g}, {x1:g}] {u}; no {self.spec.name} with links "
                                 f"<= {self.max_length:g} {u} reaches |x| > {min(R, Xr):g} {u}")
        if D > 2 * min(R, Xr) and (D > 2 * R or (x1 - x0) > 2 * Xr):
            raise ValueError(f"the task is {D:g} {u} across; no {self.spec.name} with links <= "
                             f"{self.max_length:g} {u} has a workspace that wide (raise --max-length)")
        del far

    def decode(self, x) -> dict:
        """Variables of one row of X as a dict (lengths, ``mode`` string, placement).

        Parameters
        ----------
        x : array_like
            One row of X.

        Returns
        -------
        dict
            The variables.
        """
        x = np.asarray(x, float)
        d = dict(zip(self.var_names, x))
        out = {}
        c = self._c
        if self.shape is None:
            for n in self.spec.lengths:
                out[n] = max(float(math.exp(d[f"ln_{n}"]) - c), 0.0)
        else:
            D = max(float(math.exp(d["ln_D"]) - c), 0.0)
            for n, s in zip(self.spec.lengths, self.shape):
                out[n] = D * s
            out["D"] = D
        if self.mode_any:
            k = int(np.clip(np.floor(d["mode"]), 0, len(self.spec.modes) - 1))
            out["mode"] = self.spec.modes[k]
        else:
            out["mode"] = self.mode
        rx, ry = self.task.reference
        scale = self.spec.placement_scale(out, self.max_length)
        out["task_x"] = float(d["task_x_rel"] * scale) if "task_x_rel" in d else float(rx)
        if "task_y_rel" in d:
            lo, span = self._y_range(scale)
            out["task_y"] = float(lo + d["task_y_rel"] * span)
        else:
            out["task_y"] = float(ry)
        return out

    def _y_range(self, scale) -> tuple:
        """``(lo, span)`` [L] of a free task height: ``task_y = lo + task_y_rel * span``,
        ``task_y_rel`` in [0, 1], ``scale`` the design's
        :meth:`~mechopt.core.design_spec.DesignSpec.placement_scale`. Above the base line
        (``placement_above_base``): from half the task's height ``h`` up by ``scale``;
        with ``side="below"`` its mirror image (from ``-h`` down by ``scale``);
        otherwise the task's own height ``+- scale``."""
        if self._y_lo is not None:
            return (-self._y_lo, -scale) if self.side == "below" else (self._y_lo, scale)
        return self.task.reference[1] - scale, 2.0 * scale

    def encode(self, v: dict) -> np.ndarray:
        """One row of X from a decoded design (the inverse of :meth:`decode`).

        Parameters
        ----------
        v : dict
            The design's variables.

        Returns
        -------
        ndarray
            The row, in :attr:`var_names` order.
        """
        row = []
        for n in self.var_names:
            if n == "mode":
                row.append(self.spec.modes.index(v["mode"]) + 0.5)
            elif n.startswith("ln_"):
                row.append(math.log(float(v[n[3:]]) + self._c))
            elif n in ("task_x_rel", "task_y_rel"):
                scale = self.spec.placement_scale(v, self.max_length)
                if n == "task_x_rel":
                    row.append(v["task_x"] / scale)
                else:
                    lo, span = self._y_range(scale)
                    row.append((v["task_y"] - lo) / span)
            else:
                row.append(float(v[n]))
        return np.array(row)

    # --- one design -------------------------------------------------------------------
    def mechanism(self, v: dict, sampling: Sampling | None = None):
        """The mechanism of the decoded design ``v`` (strokes derived from its task).

        Parameters
        ----------
        v : dict
            A decoded design (:meth:`decode`).
        sampling : mechopt.analysis.sampling.Sampling, optional
            The task's sampling (default: the search's).

        Returns
        -------
        PlanarMechanism
            The mechanism [L].
        """
        return self._setup(v, sampling or Sampling.fine())[0]

    def _setup(self, v, s: Sampling):
        lengths = {n: v[n] for n in self.spec.lengths}
        smp = self._samples_at(v["task_x"], v["task_y"], s)
        derived = {}
        if self.spec.derived_strokes:
            strokes = []
            for lo, hi in _s.leg_ranges(smp, lambda x, y: self.spec.positions(lengths, v["mode"], x, y),
                                        s.refine):
                if not (math.isfinite(lo) and math.isfinite(hi)):
                    lo, hi = -1.0, 1.0  # some task point out of reach of the link: reach fails
                strokes.append((lo, max(hi, lo + _v.RESOLUTION * self.task.diameter)))
            derived["strokes"] = strokes
            derived["stroke"] = max(hi - lo for lo, hi in strokes)
            mech = self.spec.build(lengths, v["mode"], strokes=strokes)
            # the clearance to the type-I loci alone (the strokes cover the task by construction)
            check = self.spec.build(lengths, v["mode"], strokes=strokes, pad=10.0 * self.task.diameter)
        else:
            mech = self.spec.build(lengths, v["mode"])
            check = mech
        return mech, check, smp, derived

    def _samples_at(self, x, y, s: Sampling) -> dict:
        """The samples of the task placed at ``(x, y)`` (:func:`~mechopt.analysis.sampling.samples`). They do not
        depend on the design, and the polish evaluates hundreds of designs at one
        placement: the last few placements' samples are kept (read-only)."""
        key = (x, y, s.n_boundary, s.n_interior)
        ctx = self._contexts.get(key)
        if ctx is None:
            ctx = _s.samples(self.task.moved_to(x, y), s)
            if len(self._contexts) >= _CONTEXTS_KEPT:
                self._contexts.pop(next(iter(self._contexts), None), None)  # the oldest
            self._contexts[key] = ctx
        return ctx

    def __getstate__(self):  # the samples' cache stays behind (workers build their own)
        state = dict(self.__dict__)
        state.pop("_contexts", None)
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._contexts = {}

    def context(self, v: dict, sampling: Sampling | None = None) -> DesignContext:
        """The sample context of the decoded design ``v`` (:class:`DesignContext`): its
        mechanism, the task's samples, its derived strokes; ``refine`` from the sampling
        and the active requirements' screens; ``settled`` (with a sampling that settles,
        :attr:`Sampling.settle <mechopt.analysis.sampling.Sampling.settle>`) from their
        :meth:`~mechopt.requirements.base.Requirement.settled`; the crank ranges of a
        design with cranks.

        Parameters
        ----------
        v : dict
            A decoded design (:meth:`decode`).
        sampling : mechopt.analysis.sampling.Sampling, optional
            The task's sampling (default: the search's).

        Returns
        -------
        mechopt.analysis.design_context.DesignContext
            The context.
        """
        s = sampling or Sampling()
        mech, check, smp, derived = self._setup(v, s)
        ctx = DesignContext(self.spec, mech, check, smp, self.req, self.objectives, self.unit,
                            self.task.diameter, self.max_length, derived)
        # refine only designs that are feasible or nearly so on the samples
        ctx.refine = s.refine and all(r.screen(ctx) for r in self.active)
        if s.settle and ctx.refine:
            ctx.settled = frozenset(r.name for r in self.active if r.settled(ctx))
        if self.spec.angular:
            # the search's sampling refines the crank ranges only for the joints requirement
            # (they are reported from the certification's, which always refines them)
            need = not s.settle or any(r.name == "joints" for r in self.active)
            derived["joint_ranges"] = ctx.joint_ranges(need and ctx.refines("joints"))
        return ctx

    def evaluate(self, v: dict, sampling: Sampling | None = None) -> dict:
        """Every active requirement's ``g`` (<= 0 feasible) and margin, every objective,
        the reported and derived values of the decoded design ``v``: a loop over the
        members of :mod:`mechopt.requirements` on one :class:`DesignContext`.

        Parameters
        ----------
        v : dict
            A decoded design (:meth:`decode`).
        sampling : mechopt.analysis.sampling.Sampling, optional
            The task's sampling (default: the search's).

        Returns
        -------
        dict
            ``g``, ``margin``, ``objectives``, ``values`` and ``derived``.
        """
        names = tuple(r.name for r in self.active)
        validity = self.spec.validity({n: v[n] for n in self.spec.lengths}, self.max_length)
        if validity > 0:
            return self._invalid(v, names, validity)
        ctx = self.context(v, sampling)
        out = {"g": {}, "margin": {}, "objectives": {}, "values": {}, "derived": ctx.derived,
               "mechanism": ctx.mech, "names": names}
        for r in self.active:
            out["margin"][r.name], out["g"][r.name] = r.evaluate(ctx)
        for ob in self._objectives:
            out["objectives"][ob.name] = ob.value(ctx)
        for member in self._members:  # after the objectives: reports read what they computed
            out["values"].update(member.report(ctx))
        return out

    def _invalid(self, v, names, validity):
        """A design whose variables describe no mechanism: every constraint violated, the
        reach one by how much; each objective's :meth:`~mechopt.requirements.base.Objective.invalid_value`
        (never read by the search's ranking, the row being infeasible)."""
        lengths = {n: v[n] for n in self.spec.lengths}
        size = 2.0 * sum(lengths.values())
        out = {"g": {n: 1.0 for n in names}, "margin": {n: math.nan for n in names},
               "objectives": {ob.name: ob.invalid_value(self, lengths) for ob in self._objectives},
               "values": {"size": size, "lci_min": 0.0, "lci_mean": 0.0, "type2_min": -1.0},
               "derived": {}, "mechanism": None, "names": names}
        out["g"]["reach"] = 1.0 + validity
        return out

    # --- pymoo rows -------------------------------------------------------------------
    def objective_values(self, res) -> list[float]:
        """The objectives of an evaluation ``res``, in :attr:`objectives` order [their units].

        Parameters
        ----------
        res : dict
            An evaluation (:meth:`evaluate`).

        Returns
        -------
        list of float
            The values.
        """
        return [float(res["objectives"][o]) for o in self.objectives]

    def units(self):
        """``{objective: unit}`` in the task's units.

        Returns
        -------
        dict
            ``{objective: unit}``.
        """
        t = "N m" if self.spec.angular else "N"
        return {ob.name: ob.unit.format(L=self.unit, T=t) for ob in self._objectives}

    def senses(self) -> dict:
        """``{objective: sense}`` (+1 minimised, -1 maximised) of the chosen objectives.

        Returns
        -------
        dict
            ``{objective: sense}``.
        """
        return {ob.name: ob.sense for ob in self._objectives}

    def objective_specs(self):
        """``(name, sense, unit, (lo, hi))`` of each chosen objective (the problem's
        :class:`~mechopt.run.problem.Objective` s; ``(lo, hi)`` the hypervolume's range).

        Returns
        -------
        list of tuple
            ``(name, sense, unit, (lo, hi))``.
        """
        units = self.units()
        return [(ob.name, ob.sense, units[ob.name], ob.bounds(self)) for ob in self._objectives]

    def row(self, v, res) -> dict:
        """One front.csv row: variables (mode as a string), placement, objectives,
        margins (``margin_<requirement>``, natural units), derived values.

        Parameters
        ----------
        v : dict
            A decoded design (:meth:`decode`).
        res : dict
            Its evaluation.

        Returns
        -------
        dict
            ``{column: value}``.
        """
        r = {n: v[n] for n in self.spec.lengths}
        if "D" in v:
            r["D"] = v["D"]
        r["mode"] = v["mode"]
        r["task_x"], r["task_y"] = v["task_x"], v["task_y"]
        for o, val in zip(self.objectives, self.objective_values(res)):
            r[o] = val
        for n in res["names"]:
            r[f"margin_{n}"] = res["margin"][n]
        d = res["derived"]
        if "joint_ranges" in d:
            for i, (lo, hi) in enumerate(d["joint_ranges"], 1):
                r[f"theta{i}_min_deg"], r[f"theta{i}_max_deg"] = math.degrees(lo), math.degrees(hi)
        if "strokes" in d:
            for i, (lo, hi) in enumerate(d["strokes"], 1):
                r[f"q{i}_min"], r[f"q{i}_max"] = lo, hi
            r["stroke"] = d["stroke"]
        for member in self.active:
            r.update(member.columns(d))
        r["size"] = res["values"]["size"]
        r["lci_min"] = res["values"]["lci_min"]
        return r

    def settings(self) -> dict:
        """The evaluator's settings (run.json's ``design`` key).

        Returns
        -------
        dict
            Mechanism, task, the set requirements, objectives, mode, placement, length
            bounds, shape and unit.
        """
        req = {k: v for k, v in self.req.asdict().items() if v is not None}
        out = {"mechanism": self.spec.name, "task": self.task.to_dict(), "requirements": req,
               "objectives": list(self.objectives), "mode": "any" if self.mode_any else self.mode,
               "place": self.place, "min_length": self.min_length, "max_length": self.max_length,
               "shape": list(self.shape) if self.shape else None, "unit": self.unit}
        out["side"] = self.side
        return out


    def record(self, derived) -> dict:
        """design.json's keys from the derived values: crank ranges [deg], strokes [L],
        and what the active requirements add (:meth:`~mechopt.requirements.base.Requirement.record`).

        Parameters
        ----------
        derived : dict
            An evaluation's derived values.

        Returns
        -------
        dict
            The keys.
        """
        rec = {}
        if "joint_ranges" in derived:
            rec["joint_ranges_deg"] = [[math.degrees(a), math.degrees(b)] for a, b in derived["joint_ranges"]]
        if "strokes" in derived:
            rec["strokes"] = [list(s) for s in derived["strokes"]]
            rec["stroke"] = derived["stroke"]
        for member in self.active:
            rec.update(member.record(derived))
        return rec


# ------------------------------------------------------------------ certification
def feasible(g) -> bool:
    """Every requirement holds: each of the values ``g`` (an evaluation's ``"g"`` values,
    a row of G) is ``<= 0``; NaN fails.

    Parameters
    ----------
    g : iterable of float
        Constraint values.

    Returns
    -------
    bool
        Whether all are ``<= 0``.
    """
    return bool(all(v <= 0 for v in g))


def certify(evaluator: DesignEvaluator, v: dict, sampling: Sampling | None = None) -> dict:
    """Re-check one design with the fine sampling (:meth:`Sampling.fine`: 2048 boundary
    points, a 61 x 61 interior grid, zoom refinement); returns the evaluation with
    ``feasible`` (every ``g <= 0``) and ``tolerance`` (what the margins rest on: the
    sampling, and each active requirement's certificate).

    Parameters
    ----------
    evaluator : DesignEvaluator
        The run's evaluator.
    v : dict
        A decoded design (:meth:`DesignEvaluator.decode`).
    sampling : Sampling, optional
        The certifying sampling (default: :meth:`Sampling.fine`).

    Returns
    -------
    dict
        The evaluation (:meth:`DesignEvaluator.evaluate`) plus ``feasible`` (bool) and
        ``tolerance`` (dict: the sample gaps [L] of a region or path and each proven
        requirement's certificate, or the note that a point task is exact at its points).
    """
    s = sampling or Sampling.fine()
    res = evaluator.evaluate(v, s)
    res["feasible"] = feasible(res["g"].values())
    task = evaluator.task
    if task.is_region:
        _, gap = task.boundary_params(s.n_boundary)
        res["tolerance"] = {
            "boundary_gap": gap,
            "interior_step": max(np.ptp(task.bbox[:2]), np.ptp(task.bbox[2:])) / (s.n_interior - 1),
            **{r.name: r.certificate for r in evaluator.active if r.proven},
            "minima": "boundary and interior critical points located on the samples, refined to "
                      "boundary_gap/2048 (boundary) and interior_step/64 (interior)",
        }
    elif task.is_path:
        _, gap = task.boundary_params(s.n_boundary)
        res["tolerance"] = {
            "path_gap": gap,
            **{r.name: r.certificate + " (along the path: sample gap path_gap)" for r in evaluator.active if r.proven},
            "minima": "critical points along the path located on the samples, refined to path_gap/2048",
        }
    else:
        res["tolerance"] = {"points": "exact at the task's points, and only there (path:FILE.csv covers "
                                      "the polyline through them)"}
    return res


# ------------------------------------------------------------------ choosing
def sensitivity(evaluator: DesignEvaluator, v: dict, name: str, sampling: Sampling | None = None) -> dict:
    """How the margin of requirement ``name`` of the decoded design ``v`` changes with
    what a designer can change: measured, one change at a time, by re-evaluating ``v``.

    The changes (each by :data:`SENSITIVITY_STEP` = 10 %): every link length scaled
    by 1.1 and 0.9 (``"longer links"``, ``"shorter links"``; the length bound raised
    by 25 % for the measurement, so the question is what raising ``--max-length``
    would buy), the task moved by 10 % of its diameter up, down, left and right of
    where ``v`` places it, and the actuator limits of the requirement (its options of
    kind ``rate`` or ``effort``) raised by 10 % (``"faster actuators"``,
    ``"stronger actuators"``).

    Parameters
    ----------
    evaluator : DesignEvaluator
        The run's evaluator.
    v : dict
        A decoded design (:meth:`DesignEvaluator.decode`).
    name : str
        An active requirement's name.
    sampling : Sampling, optional
        The sampling of the re-evaluations (the search's by default).

    Returns
    -------
    dict
        ``{change: margin}``: the requirement's margin [its ``margin_unit``] after each
        change; NaN where the changed design is invalid. A larger margin helps.

    Raises
    ------
    ValueError
        When ``name`` is not an active requirement of the evaluator.
    """
    import copy

    step = SENSITIVITY_STEP
    member = next((r for r in evaluator.active if r.name == name), None)
    if member is None:
        raise ValueError(f"{name!r} is not an active requirement of this design run")

    def margin(ev, w):
        return float(ev.evaluate(w, sampling)["margin"][name])

    out = {}
    roomy = copy.copy(evaluator)
    roomy.max_length = evaluator.max_length * (1.0 + 2.5 * step)
    for label, f in (("longer links", 1.0 + step), ("shorter links", 1.0 - step)):
        out[label] = margin(roomy, {**v, **{n: v[n] * f for n in evaluator.spec.lengths}})
    d = step * evaluator.task.diameter
    for label, dx, dy in (("task moved up", 0, d), ("task moved down", 0, -d),
                          ("task moved right", d, 0), ("task moved left", -d, 0)):
        out[label] = margin(evaluator, {**v, "task_x": v["task_x"] + dx, "task_y": v["task_y"] + dy})
    labels = {"rate": "faster actuators", "effort": "stronger actuators"}
    for opt in member.options:
        value = getattr(evaluator.req, opt.name, None)
        if opt.kind in labels and value is not None:
            stronger = copy.copy(evaluator)
            scaled = np.asarray(value, float) * (1.0 + step)
            stronger.req = evaluator.req.replace(**{opt.name: scaled if scaled.ndim else float(scaled)})
            out[labels[opt.kind]] = margin(stronger, v)
    return {k: (m if math.isfinite(m) else math.nan) for k, m in out.items()}


def knee_index(F: np.ndarray) -> int:
    """Knee of a front (minimisation form ``F``, rows = designs): with two objectives
    the design farthest from the line through the two extremes (normalised), with
    one the best, otherwise the design nearest the normalised ideal point.

    Parameters
    ----------
    F : ndarray
        The front, shape ``(n, n_obj)``, minimisation form.

    Returns
    -------
    int
        The knee's row.
    """
    F = np.asarray(F, float)
    if len(F) == 1 or F.shape[1] == 1:
        return int(np.argmin(F[:, 0]))
    lo, hi = F.min(0), F.max(0)
    Z = (F - lo) / np.where(hi > lo, hi - lo, 1.0)
    if F.shape[1] == 2:
        a, b = Z[np.argmin(Z[:, 0])], Z[np.argmin(Z[:, 1])]
        d = b - a
        n = np.hypot(*d)
        if n == 0:
            return int(np.argmin(Z.sum(1)))
        dist = np.abs(d[0] * (Z[:, 1] - a[1]) - d[1] * (Z[:, 0] - a[0])) / n
        return int(np.argmax(dist - _v.ROUNDING * Z.sum(1)))  # ties: the better sum
    return int(np.argmin(np.sqrt((Z ** 2).sum(1))))


def parse_weights(weights, objectives):
    """``{objective: weight}`` from ``"size=1,min-lci=2"`` or a mapping; each a known
    objective of ``objectives`` with a finite weight >= 0, at least one positive.

    Parameters
    ----------
    weights : str or dict
        The weights.
    objectives : sequence of str
        The run's objectives.

    Returns
    -------
    dict
        ``{objective: weight}``.

    Raises
    ------
    ValueError
        One line, for a malformed text, an unknown objective, a negative weight or no
        positive one.
    """
    if isinstance(weights, str):
        d = {}
        for part in weights.split(","):
            if not part.strip():
                continue
            k, sep, val = part.partition("=")
            if not sep:
                raise ValueError(f"--pick must be name=weight,... (e.g. size=1,min-lci=2), got {weights!r}")
            d[k.strip()] = val
        weights = d
    out = {}
    for k, val in dict(weights).items():
        _v.choice("pick objective", k, objectives)
        w = _v.finite_number(f"weight of {k}", val)
        if w < 0:
            raise ValueError(f"weight of {k} must be >= 0, got {w!r}")
        out[k] = w
    if not out or not any(out.values()):
        raise ValueError("--pick needs at least one positive weight")
    return out


#: how :meth:`mechopt.workflows.design.DesignResult.pick` scalarises the weights
PICK_METHODS = ("sum", "asf", "pseudo")


def parse_pick(text, objectives) -> tuple:
    """``(method, {objective: weight})`` from ``"size=1,min-lci=2"`` (a weighted sum),
    ``"asf:size=1,min-lci=2"`` or ``"pseudo:..."`` (or a mapping: a weighted sum).

    Parameters
    ----------
    text : str or dict
        The ``--pick`` value.
    objectives : sequence of str
        The run's objectives.

    Returns
    -------
    method : str
        ``"sum"``, ``"asf"`` or ``"pseudo"``.
    weights : dict
        ``{objective: weight}``.
    """
    method = "sum"
    if isinstance(text, str) and ":" in text:
        method, _, text = text.partition(":")
        method = _v.choice("--pick method", method.strip(), PICK_METHODS)
    return method, parse_weights(text, objectives)


def pick_index(F, objectives, weights=None) -> int:
    """The row of a front ``F`` (minimisation form, columns in ``objectives`` order) chosen
    by ``weights`` (:func:`parse_pick`; None: :func:`knee_index`). The objectives are
    normalised to [0, 1] over the front (``Z``); a weighted sum minimises ``Z w``; ASF
    (pymoo's achievement scalarizing function) minimises ``max_i Z_i / w_i``, which
    reaches designs on non-convex parts of a front that no weighted sum does; pseudo
    takes the design whose pseudo-weights are nearest ``w`` (pymoo's PseudoWeights,
    Deb 2001).

    Parameters
    ----------
    F : ndarray
        The front, minimisation form.
    objectives : sequence of str
        Its columns' objectives.
    weights : str or dict, optional
        As :func:`parse_pick` takes.

    Returns
    -------
    int
        The chosen row.
    """
    F = np.asarray(F, float)
    if weights is None:
        return knee_index(F)
    method, w = parse_pick(weights, objectives)
    lo, hi = F.min(0), F.max(0)
    Z = (F - lo) / np.where(hi > lo, hi - lo, 1.0)
    wv = np.array([w.get(o, 0.0) for o in objectives])
    if method == "asf":
        from pymoo.decomposition.asf import ASF

        # a zero weight does not count its objective (a tiny weight: a huge ratio would)
        return int(np.argmin(ASF().do(Z, np.where(wv > 0, wv / wv.sum(), 1e300))))
    if method == "pseudo":
        from pymoo.mcdm.pseudo_weights import PseudoWeights

        return int(PseudoWeights(wv / wv.sum()).do(F))
    return int(np.argmin(Z @ wv))
