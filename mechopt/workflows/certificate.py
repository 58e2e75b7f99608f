"""What a design's numbers rest on, and re-checking a design: ``certificate.json`` and
``mechopt check``.

:func:`certificate` is the content of ``certificate.json``, written by ``mechopt design``
next to ``design.json``: for every front design (and which one ``design.json`` holds)
each active requirement with its margin [its unit], its ``g``, whether it holds, how it
is known (``"proven"``: the requirement's own argument over the whole task, e.g. the
reach's 1-Lipschitz clearance bound; ``"refined-sampled"``: the minimum located on the
samples and refined by zooming, an estimate, not a bound), the sampling, and the
design's digest (:func:`mechopt.export.source.design_digest` of its design record: for
the chosen design, the digest of ``design.json`` itself).

:func:`check` re-evaluates a ``design.json`` (its lengths possibly rounded or edited by
hand, ``--lengths``) with the full evaluator and the certification's sampling
(:func:`mechopt.analysis.design_eval.certify`) against the task and requirements of the
``run.json`` beside it (or ``--task``), and with a tolerance ``T`` also every mechanism
whose lengths lie within ``+- T`` of the nominal ones (:func:`tolerance_box`).
"""
from __future__ import annotations

import itertools
import math
from dataclasses import asdict
from pathlib import Path

import numpy as np

from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.sampling import Sampling

__all__ = ["certificate", "check", "check_certificate", "is_certificate", "tolerance_box", "box_certified", "box_failures", "requirement_entries",
           "proven_bounds", "proven_bounds_of_designs", "format_check", "BOX_SAMPLES", "CERTIFICATE_VERSION", "CLAIM_RTOL", "BOUNDED",
           "RANGED"]

#: the format of certificate.json (a new key keeps it; a changed meaning raises it)
CERTIFICATE_VERSION = 1
#: random mechanisms drawn inside a tolerance box besides its 2^n corners (seeded)
BOX_SAMPLES = 32


#: the requirements whose minimum :func:`proven_bounds` bounds from below (joints and
#: stroke: their margins, from the proven outer ranges of the actuator coordinates)
BOUNDED = ("lci", "singular", "speed", "force", "joints", "stroke")
#: the requirements bounded through the actuator coordinates' ranges
RANGED = ("joints", "stroke")


def _method(member) -> str:
    return "proven" if member.proven else "refined-sampled"


def requirement_entries(ev: DesignEvaluator, res: dict, bounds: dict | None = None) -> dict:
    """``{requirement: {margin, unit, g, holds, method, certificate}}`` of an evaluation
    ``res`` (:func:`~mechopt.analysis.design_eval.certify`) by the evaluator ``ev``.

    Parameters
    ----------
    ev : mechopt.analysis.design_eval.DesignEvaluator
        The evaluator.
    res : dict
        An evaluation of it (``margin`` and ``g`` per active requirement are read).
    bounds : dict, optional
        :func:`proven_bounds` of the same design: each is recorded as the requirement's
        ``bound``, and a requirement whose proven lower bound meets it is ``"proven"``.

    Returns
    -------
    dict
        Per active requirement: ``margin`` [``unit``], ``unit``, ``g``, ``holds``
        (``g <= 0``), ``method`` (``"proven"`` or ``"refined-sampled"``),
        ``certificate`` and ``describe`` (the requirement in words); with ``bounds``
        also ``bound``.
    """
    out = {}
    for r in ev.active:
        m, g = res["margin"][r.name], res["g"][r.name]
        out[r.name] = {"margin": float(m), "unit": r.margin_unit.format(L=ev.unit), "g": float(g),
                       "holds": bool(g <= 0), "method": _method(r), "certificate": r.certificate,
                       "describe": ev.req.describe(r.name, ev.unit)}
        b = (bounds or {}).get(r.name)
        if b is not None:
            out[r.name]["bound"] = b
            if b["proven_margin"] >= 0:
                out[r.name]["method"] = "proven"
                what = (f"proven lower bound {b['lower_bound']:.6g} of the minimum" if "ranges" not in b else
                        f"proven lower bound {b['lower_bound']:.6g} of the margin from the proven outer ranges "
                        + ", ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in b["ranges"]))
                out[r.name]["certificate"] = (f"{what} by {b['method']} ({b['cells']} cells, smallest "
                                              f"{b['smallest_cell']:.3g} {ev.unit}; mechopt.analysis.bounds); "
                                              f"estimate {b['estimate']:.6g}: {r.certificate}")
    return out


def proven_bounds(ev: DesignEvaluator, v: dict, margins: dict | None = None, budget: int | None = None,
                  tolerance: float | None = None) -> dict:
    """Proven lower bounds of the minima the active requirements of :data:`BOUNDED` rest on,
    for the decoded design ``v`` (:func:`mechopt.analysis.bounds.lower_bound`, interval
    branch-and-bound over the placed task): LCI, the type-II function with the design's
    sign, the guaranteed speed and force in the requirements' reading of the actuator
    limits. The bound is over the mechanism whose strokes are padded (the evaluator's
    ``check``: the same Jacobian; a slider mechanism's strokes are sized to cover the
    task, which the reach requirement proves). For ``joints`` and ``stroke`` the
    bounded quantity is the margin itself: from the proven outer ranges of both actuator
    coordinates over the task (:func:`mechopt.analysis.bounds.outer_range`), the smallest
    distance of the crank ranges to their limits [rad], or ``max_stroke`` minus the
    longest outer range [L].

    Parameters
    ----------
    ev : mechopt.analysis.design_eval.DesignEvaluator
        The evaluator.
    v : dict
        A decoded design (lengths, mode, placement).
    margins : dict, optional
        The design's margins by requirement (its certification's; with ``tolerance``
        the sampled box's smallest): the estimates are ``margin + required level``;
        default: computed again.
    budget : int, optional
        Cells per quantity (default :data:`mechopt.analysis.bounds.BUDGET`).
    tolerance : float, optional
        ``T`` [L]: bound over every mechanism whose design lengths lie within ``+- T`` of
        ``v``'s (clipped at 0) and every placement of the task within ``+- T`` of ``v``'s
        in x and y (the mode stays ``v``'s), for mechanisms whose enclosure takes length
        intervals (every mechanism of mechopt); ValueError for the others.

    Returns
    -------
    dict
        Per bounded active requirement: ``quantity``, ``lower_bound`` (proven) and
        ``estimate`` (the sampled-and-zoomed minimum) [the quantity's unit], ``gap``
        (``estimate - lower_bound``), ``upper`` (the smallest value the search met at a
        task point), ``proven_margin`` (``lower_bound`` minus the required level [the
        margin's unit]), ``method``, ``cells``, ``smallest_cell``, ``largest_cell`` [L],
        ``converged`` and ``may_unreachable``; for ``joints`` and ``stroke`` also ``ranges``
        (the proven outer ranges [rad or L]), ``estimate_ranges`` (the sampled ones: the
        derived ``joint_ranges`` or ``strokes``) and ``inner_ranges`` (the extremes the
        search met at task points). Empty for an invalid design.

    Raises
    ------
    ValueError
        With ``tolerance``, for a mechanism whose enclosure takes no length intervals.
    """
    return proven_bounds_of_designs(ev, [v], [margins], budget=budget, tolerance=tolerance)[0]


def proven_bounds_of_designs(ev: DesignEvaluator, vs: list, margins: list | None = None, budget: int | None = None,
                             tolerance: float | None = None) -> list:
    """:func:`proven_bounds` of several decoded designs of one evaluator, every search of
    every design run in lock-step (:func:`mechopt.analysis.bounds.lower_bounds_of_designs`:
    the enclosures over the cells of designs that differ only in their lengths computed in
    one vectorised call; each bound as alone).

    Parameters
    ----------
    ev : mechopt.analysis.design_eval.DesignEvaluator
        The evaluator.
    vs : list of dict
        Decoded designs.
    margins : list, optional
        Per design, :func:`proven_bounds`' ``margins`` (None entries: computed again).
    budget, tolerance
        As :func:`proven_bounds`'.

    Returns
    -------
    list of dict
        Per design, :func:`proven_bounds`' result.

    Raises
    ------
    ValueError
        As :func:`proven_bounds`.
    """
    from mechopt.analysis import bounds as _b

    margins = [None] * len(vs) if margins is None else list(margins)
    plans = [_plan(ev, v, m, tolerance) for v, m in zip(vs, margins)]
    live = [p for p in plans if p is not None]
    if not live:
        return [{} for _ in plans]
    kw = dict(budget=budget or _b.BUDGET, lengths=None, shift=tolerance or 0.0, names=tuple(ev.spec.lengths))

    def designs(these, ranges=True):  # lower_bounds_of_designs' designs (without the range searches)
        return [(p["ctx"].check, p["to_mech"], p["qs"] if ranges else p["qs"][:len(p["searches"])],
                 p["ups"] if ranges else p["ups"][:len(p["searches"])]) for p in these]
    if tolerance is None:
        for p, f in zip(live, _b.lower_bounds_of_designs(live[0]["ctx"].task, designs(live), **kw)):
            p["found"] = f
    for p in live if tolerance is not None else []:  # each design over its own box of lengths
        kw["lengths"] = p["lengths"]
        try:
            (p["found"],) = _b.lower_bounds_of_designs(p["ctx"].task, designs([p]), **kw)
        except ValueError:  # an actuator enclosure without length intervals
            if not p["ranged"]:
                raise
            (p["found"],), p["ranged"] = _b.lower_bounds_of_designs(p["ctx"].task, designs([p], False), **kw), []
    return [{} if p is None else _assemble(p) for p in plans]


def _plan(ev, v, margins, tolerance):
    """What :func:`proven_bounds` bounds for the design ``v``: its context, the quantities
    and their ``upper`` values (the closure's, then four per range requirement), the
    estimates; None when nothing is bounded."""
    from mechopt.analysis import bounds as _b
    from mechopt.requirements.force import effort_factor, force
    from mechopt.requirements.lci import lci_min
    from mechopt.requirements.speed import limits, reading, speed

    active = {r.name: r for r in ev.active if r.name in BOUNDED}
    if not active or ev.spec.validity({n: v[n] for n in ev.spec.lengths}, ev.max_length) > 0:
        return None
    ctx = ev.context(v, Sampling.fine())
    req = ctx.req
    lengths = None if tolerance is None else {
        n: (max(float(v[n]) - tolerance, 0.0), float(v[n]) + tolerance) for n in ev.spec.lengths}
    searches, ranged = [], []  # (name, quantity, required level, estimate); range requirements
    for name, r in active.items():
        if name in RANGED:
            est = float(margins[name]) if margins is not None and name in margins else float(r.evaluate(ctx)[0])
            ranged.append((name, est))
            continue
        if name == "lci":
            q, need = _b.lci_quantity(), req.min_lci
            est = (lambda: lci_min(ctx))
        elif name == "singular":
            q, need = _b.type2_quantity(r.sign(ctx)), req.singularity_margin
            est = (lambda: r.minimum(ctx))
        elif name == "speed":
            q, need = _b.speed_quantity(limits(req.actuator_speed), reading(ctx)), req.min_speed
            est = (lambda: speed(ctx))
        else:
            q = _b.force_quantity(limits(req.actuator_torque), reading(ctx), effort_factor(ctx))
            need, est = req.min_force, (lambda: force(ctx))
        est = float(margins[name]) + float(need) if margins is not None and name in margins else float(est())
        searches.append((name, q, need, est))
    qs = [q for _, q, _, _ in searches]
    # over a tolerance box the nominal design's values need not reach the box's minimum:
    # the sampled box minimum (a value of a mechanism of the box) stops the search
    ups = [est if tolerance is not None and math.isfinite(est) else math.inf for *_, est in searches]
    for name, _ in ranged:
        qs += _b.range_quantities(1.0 if name == "joints" else ctx.task.diameter)
        ups += [math.inf] * 4
    return {"ctx": ctx, "active": list(active), "lengths": lengths, "searches": searches, "ranged": ranged,
            "qs": qs, "ups": ups, "to_mech": lambda x, y: ctx.spec.to_mech(ctx.check, x, y)}


def _assemble(p) -> dict:
    """:func:`proven_bounds`' result from a :func:`_plan` and its bounds ``p["found"]``."""
    from mechopt.analysis import bounds as _b

    out, searches, found = {}, p["searches"], p["found"]
    for (name, q, need, est), b in zip(searches, found):
        out[name] = {"quantity": q.name, "lower_bound": b.lower, "estimate": est, "gap": est - b.lower,
                     "upper": b.upper, "proven_margin": b.lower - float(need),
                     "method": _b.METHOD, "cells": b.cells, "smallest_cell": b.smallest_cell,
                     "largest_cell": b.largest_cell, "converged": b.converged, "may_unreachable": b.may_unreachable}
    for k, (name, est) in enumerate(p["ranged"]):
        at = len(searches) + 4 * k
        out[name] = _ranges(p["ctx"], name, est, _b.Ranges.of(found[at:at + 4]))
    return dict(sorted(out.items(), key=lambda kv: p["active"].index(kv[0])))


def _ranges(ctx, name, est, rg) -> dict:
    """:func:`proven_bounds`' entry of ``joints`` or ``stroke``: the margin's lower bound
    from the proven outer ranges ``rg`` (:class:`mechopt.analysis.bounds.Ranges`) over
    the placed task."""
    from mechopt.analysis import bounds as _b

    joints = name == "joints"

    def margin(ranges):
        if joints:
            return min(min(lo - a, b - hi) for (lo, hi), (a, b) in zip(ranges, ctx.req.joint_limits))
        return ctx.req.max_stroke - max(hi - lo for lo, hi in ranges)
    with np.errstate(invalid="ignore"):
        lower, upper = float(margin(rg.outer)), float(margin(rg.inner))
    lower = -math.inf if math.isnan(lower) else lower
    ranges = ctx.derived["joint_ranges" if joints else "strokes"]
    return {"quantity": "joint_ranges" if joints else "strokes", "lower_bound": lower, "estimate": est,
            "gap": est - lower, "upper": upper, "proven_margin": lower, "method": _b.METHOD, "cells": rg.cells,
            "smallest_cell": min(b.smallest_cell for b in rg.bounds),
            "largest_cell": max(b.largest_cell for b in rg.bounds), "converged": rg.converged,
            "may_unreachable": rg.may_unreachable, "ranges": [list(map(float, o)) for o in rg.outer],
            "estimate_ranges": [list(map(float, o)) for o in ranges],
            "inner_ranges": [list(map(float, o)) for o in rg.inner]}


def _bounds_of(item) -> list:
    """:func:`proven_bounds` of front design records ``(ev, recs)``, in lock-step
    (:func:`proven_bounds_of_designs`; module level: it runs in workers)."""
    ev, recs = item
    return proven_bounds_of_designs(ev, [_variables(rec, ev.spec, None) for rec in recs],
                                    [rec["margins"] for rec in recs])


def certificate(result) -> dict:
    """certificate.json's content for a :class:`~mechopt.workflows.design.DesignResult`:
    the mechopt version, the mechanism, unit, task and requirements (run.json's
    ``design`` settings), the sampling of the certification, the index of the chosen
    design, and per front design its variables, placement, digest, each requirement
    (:func:`requirement_entries`) and what the margins rest on (``tolerance``).

    Parameters
    ----------
    result : mechopt.workflows.design.DesignResult
        A design run's result.

    Returns
    -------
    dict
        Plain JSON data: ``certificate_version``, ``mechopt_version``, ``settings``,
        ``sampling``, ``chosen``, ``designs`` (one entry per front design) and ``note``.
    """
    from mechopt import __version__
    from mechopt.export.source import design_digest
    from mechopt.run.io import plain_json

    from mechopt.run.parallel import parallel_map

    ev = result.evaluator
    designs = []
    recs = [result.design_at(i) for i in range(len(result.front))]
    # the bounds of the front designs, spread over the run's workers
    # (a chunk of designs per worker, each chunk's searches in lock-step)
    n_jobs = max(1, min(int(result.info.get("n_jobs") or 1), len(recs)))
    chunks = [recs[k::n_jobs] for k in range(n_jobs)]
    done = parallel_map(_bounds_of, [(ev, c) for c in chunks], n_jobs)
    every = [done[k % n_jobs][k // n_jobs] for k in range(len(recs))]
    for i, (rec, bounds) in enumerate(zip(recs, every)):
        res = {"margin": rec["margins"], "g": rec["constraints_g"]}
        # the digest of the record as design.json holds it (without the mechanism object)
        digest = design_digest(plain_json({k: val for k, val in rec.items() if k != "mechanism"}))
        designs.append({"index": i, "digest": digest, "variables": rec["variables"],
                        "task_placement": rec["task_placement"], "feasible": bool(rec["feasible"]),
                        "requirements": requirement_entries(ev, res, bounds), "tolerance": rec["tolerance"]})
        if i in result.boxes:  # a run with --tolerance: the box it certified the design over
            designs[-1]["tolerance_box"] = result.boxes[i]
    return {"certificate_version": CERTIFICATE_VERSION, "mechopt_version": __version__,
            "settings": ev.settings(), "sampling": asdict(Sampling.fine()),
            "chosen": int(result.chosen_index), "designs": designs,
            "note": "proven: the requirement's argument holds over the whole task (for LCI, the type-II "
                    "function, speed and force: the proven lower bound of the minimum by interval "
                    "branch-and-bound, 'bound', meets it; for joints and stroke: the margin from the proven "
                    "outer ranges of the actuator coordinates, 'bound', is >= 0); refined-sampled: the minimum located on the samples "
                    "and refined by zooming (an estimate, not a bound)"}


# ------------------------------------------------------------------ check
def _read_design(path):
    """``(design.json, run.json's design settings)``: one-line ValueError otherwise."""
    from mechopt.run import io as _io

    path = Path(path)
    try:
        rec = _io.read_json(path, f"DESIGN.json {str(path)!r}")
    except FileNotFoundError:
        raise ValueError(f"DESIGN.json {str(path)!r} does not exist") from None
    except IsADirectoryError:
        raise ValueError(f"DESIGN.json {str(path)!r} is a folder") from None
    if not isinstance(rec, dict) or not {"mechanism_name", "variables", "task_placement", "unit"} <= set(rec):
        raise ValueError(f"{str(path)!r} is not a design.json of mechopt design")
    run_path = path.parent / "run.json"
    try:
        run = _io.read_json(run_path, f"run.json {str(run_path)!r}")
    except FileNotFoundError:
        raise ValueError(f"no run.json beside {str(path)!r} (it holds the task and the requirements)") from None
    settings = run.get("design") if isinstance(run, dict) else None
    if settings is None and isinstance(run, dict) and isinstance(run.get("per_mechanism"), dict):
        # a design-any run: the chosen mechanism's own run settings
        own = run["per_mechanism"].get(rec["mechanism_name"])
        settings = own.get("run", {}).get("design") if isinstance(own, dict) else None
    if not isinstance(settings, dict) or settings.get("mechanism") != rec["mechanism_name"]:
        raise ValueError(f"{str(run_path)!r} is not the run.json of this design's run")
    return rec, settings


def _variables(rec, spec, lengths):
    """The design's variables (lengths [L], mode, placement), ``lengths`` (``{name: value}``
    or ``"r1=85,r2=160"``) replacing some."""
    from mechopt.core import validation as _v

    v = rec["variables"]
    try:
        out = {n: float(v[n]) for n in spec.lengths}
        out["mode"] = str(v["mode"])
        out["task_x"] = float(rec["task_placement"]["task_x"])
        out["task_y"] = float(rec["task_placement"]["task_y"])
    except (KeyError, TypeError, ValueError) as exc:
        raise ValueError(f"design.json lacks a design variable or its placement ({exc})") from None
    if isinstance(lengths, str):
        pairs = [p.partition("=") for p in lengths.split(",") if p.strip()]
        if any(not sep for _, sep, _ in pairs):
            raise ValueError(f"--lengths must be name=value,... (e.g. r1=85,r2=160), got {lengths!r}")
        lengths = {k.strip(): val for k, _, val in pairs}
    for k, val in dict(lengths or {}).items():
        _v.choice("length", k, tuple(spec.lengths))
        x = _v.finite_number(k, val)
        if x < 0:
            raise ValueError(f"{k} must be >= 0, got {x!r}")
        out[k] = x
    for k in spec.lengths:
        if not (math.isfinite(out[k]) and out[k] >= 0):
            raise ValueError(f"design.json's {k} must be a finite length >= 0, got {out[k]!r}")
    return out


def tolerance_box(ev: DesignEvaluator, v: dict, tol: float, n_samples: int = BOX_SAMPLES, seed: int = 0,
                  sampling: Sampling | None = None) -> dict:
    """The smallest margin of each requirement over the mechanisms whose lengths lie
    within ``+- tol`` [L] of those of ``v`` (a length the box would make negative is
    clipped at 0), with the task placed within ``+- tol`` of ``v``'s placement in x and
    y (the base placement is a length: the five-bar's ``r3``, ...).

    What is evaluated: the ``2^n`` corners of the lengths' box (``n`` lengths) at the
    design's placement, the 4 corners of the placement's at its lengths, and
    ``n_samples`` points drawn uniformly inside the whole box (seeded), each by
    :func:`~mechopt.analysis.design_eval.certify` with ``sampling`` (default the
    certification's); the working mode stays the design's. What is
    proven: nothing beyond those mechanisms. The margins are not monotone in the
    lengths in general (LCI has interior maxima along a length, the polish leaves
    designs at such peaks), so a minimum inside the box between the evaluated points
    can be lower: the sampled result is never called proven. What is proven, for the
    mechanisms whose enclosure takes length intervals (every mechanism of mechopt): the lower bound
    of each minimum of :func:`proven_bounds` over the task and every length of the
    box and every placement at once (:func:`proven_bounds` with ``tolerance``); where it meets the
    requirement, the requirement is ``"proven"`` over the box; reach is proven over
    the box when every cell of those searches is certainly reachable for every
    mechanism of the box (both legs assemble). Returns ``{"tolerance", "evaluated",
    "min_margin": {name: value}, "worst": {name: lengths}, "holds": {name: bool},
    "method", "methods": {name: "proven" or "sampled"}, "proven": {name: bound}}``.

    Parameters
    ----------
    ev : mechopt.analysis.design_eval.DesignEvaluator
        The evaluator (task, requirements, length bounds).
    v : dict
        The nominal design's decoded variables (lengths [L], mode, placement).
    tol : float
        The tolerance ``+-`` on every length [L].
    n_samples : int
        Random mechanisms inside the box besides its corners.
    seed : int
        Seed of the random draws.
    sampling : mechopt.analysis.sampling.Sampling, optional
        The sampling of each evaluation (default: :meth:`Sampling.fine
        <mechopt.analysis.sampling.Sampling.fine>`).

    Returns
    -------
    dict
        ``tolerance`` [L], ``evaluated`` (how many mechanisms), ``min_margin`` (per
        requirement, its margin's unit; NaN counts as the worst), ``worst`` (the lengths
        [L] where that minimum was found), ``holds`` (per requirement, ``g <= 0`` at
        every evaluated mechanism), ``methods`` (per requirement ``"proven"`` over the
        whole box or ``"sampled"``), ``method`` (``"proven"`` when every requirement is,
        else ``"sampled"``) and ``proven`` (per bounded requirement: ``lower_bound``,
        ``proven_margin``, ``cells``, ``converged``, ``may_unreachable``; for joints and
        stroke also ``ranges``, the proven outer ranges over the task and the box [rad or L]).
    """
    names = list(ev.spec.lengths)
    nominal = np.array([v[n] for n in names])
    n = len(names)
    # the lengths' 2^n corners at the design's placement, the placement's 4 corners at its
    # lengths, then random points of the whole box (lengths and placement)
    corners = np.array(list(itertools.product(*[(-1.0, 1.0)] * n)))
    moves = np.array(list(itertools.product((-1.0, 1.0), (-1.0, 1.0))))
    rng = np.random.default_rng(seed)
    offsets = np.vstack([np.hstack([corners, np.zeros((len(corners), 2))]),
                         np.hstack([np.zeros((len(moves), n)), moves]),
                         rng.uniform(-1.0, 1.0, size=(n_samples, n + 2))])
    worst_m = {r.name: math.inf for r in ev.active}
    worst_at, holds = {}, {r.name: True for r in ev.active}
    for off in offsets:
        L = np.maximum(nominal + tol * off[:n], 0.0)
        at = {**dict(zip(names, map(float, L))), "task_x": float(v["task_x"] + tol * off[n]),
              "task_y": float(v["task_y"] + tol * off[n + 1])}
        res = certify(ev, {**v, **at}, sampling)
        for r in ev.active:
            m, g = float(res["margin"][r.name]), float(res["g"][r.name])
            if not g <= 0:
                holds[r.name] = False
            if not m >= worst_m[r.name]:  # NaN counts as the worst
                worst_m[r.name], worst_at[r.name] = m, at
    out = {"tolerance": float(tol), "evaluated": int(len(offsets)), "min_margin": worst_m, "worst": worst_at,
           "holds": holds, "method": "sampled", "methods": {r.name: "sampled" for r in ev.active}, "proven": {}}
    try:
        sampled = {n: m for n, m in worst_m.items() if math.isfinite(m)}
        bounds = proven_bounds(ev, v, sampled, tolerance=float(tol))
    except ValueError:  # no enclosure over length intervals: sampled only
        return out
    for name, b in bounds.items():
        # joints and stroke also carry their proven outer ranges over the box: the strokes a
        # slider machine must have for every build of the box (each build's own strokes
        # are its range over the task)
        out["proven"][name] = {k: b[k] for k in ("lower_bound", "proven_margin", "cells", "converged",
                                                 "may_unreachable", "ranges") if k in b}
        if b["proven_margin"] >= 0:
            out["methods"][name] = "proven"
    # every cell of the task certain for every mechanism of the box: each reaches the whole
    # task in the working mode (both legs assemble, no base joint in a cell)
    if "reach" in out["methods"] and bounds and not any(b["may_unreachable"] for b in bounds.values()) \
            and holds.get("reach"):
        out["methods"]["reach"] = "proven"
    if all(m == "proven" for m in out["methods"].values()):
        out["method"] = "proven"
    return out


def box_failures(box: dict) -> list:
    """The requirements a tolerance box (:func:`tolerance_box`) does not certify: those
    that fail at an evaluated mechanism, and those whose interval bound over the box does
    not prove them (a bounded requirement must be proven; the others rest on the
    evaluated mechanisms).

    Parameters
    ----------
    box : dict
        A :func:`tolerance_box` result.

    Returns
    -------
    list of str
        The names, in the box's order.
    """
    return [n for n, ok in box["holds"].items()
            if not ok or (n in box["proven"] and box["methods"][n] != "proven")]


def box_certified(box: dict) -> bool:
    """Whether a tolerance box certifies its design: no :func:`box_failures`.

    Parameters
    ----------
    box : dict
        A :func:`tolerance_box` result.

    Returns
    -------
    bool
        True when every requirement holds over the box as :func:`box_failures` asks.
    """
    return not box_failures(box)


#: a margin a certificate claims agrees with the re-check when within this relative
#: difference (the same code gives the same double; another platform's libm may differ
#: in the last bits)
CLAIM_RTOL = 1e-9


def _certificate_match(path: Path, rec: dict, entries: dict):
    """Whether the certificate.json beside ``path`` records this very design.json (its
    digest among the certified designs'): ``{"index": k or None, "chosen": bool,
    "disagrees": [...]}``, or None without a readable certificate.json. A design edited
    by hand (rounded lengths) is not recorded and is checked on its own numbers; for a
    recorded one, every margin and verdict the certificate claims must equal the
    re-check's ``entries`` (to :data:`CLAIM_RTOL`): ``disagrees`` names each that does
    not (a tampered or stale certificate), which fails the check."""
    from mechopt.export.source import design_digest
    from mechopt.run import io as _io

    try:
        cert = _io.read_json(path.parent / "certificate.json")
        digest = design_digest(rec)
        designs = cert["designs"]
        entry = next((d for d in designs if d.get("digest") == digest), None)
        if entry is None:  # not this design.json (edited since, or another run's)
            return {"index": None, "chosen": False, "disagrees": []}
        index, claimed = entry["index"], dict(entry["requirements"])
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None
    return {"index": index, "chosen": index == cert.get("chosen"), "disagrees": _disagreements(claimed, entries)}


def _disagreements(claimed: dict, entries: dict) -> list:
    """The requirements whose claimed margin (to :data:`CLAIM_RTOL`) or verdict a re-check's
    ``entries`` (:func:`requirement_entries`) does not find, or whose claimed ``proven``
    the re-check does not prove: one phrase each."""
    out = []
    for name, e in entries.items():
        c = claimed.get(name)
        try:
            m, ok = float(c["margin"]), c["holds"]
        except (TypeError, KeyError, ValueError):
            out.append(f"{name} (not in certificate.json)")
            continue
        same = m == e["margin"] or abs(m - e["margin"]) <= CLAIM_RTOL * max(1.0, abs(e["margin"]))
        if not same or ok is not e["holds"]:
            out.append(f"{name} (certificate.json claims margin {m:.6g}, the check finds {e['margin']:.6g})")
        elif c.get("method") == "proven" and e["method"] != "proven":
            out.append(f"{name} (certificate.json claims it proven, the check does not prove it)")
    return out


def _evaluator(settings: dict, task, mode) -> DesignEvaluator:
    """The evaluator of one design of a run (run.json's or certificate.json's ``settings``)
    on ``task``, placed as given, in working mode ``mode``."""
    from mechopt.requirements import Requirements

    req = Requirements(**settings.get("requirements", {}))
    return DesignEvaluator(settings["mechanism"], task, req, settings.get("objectives") or ("size",), mode=mode,
                           place="fixed", min_length=settings.get("min_length"),
                           max_length=settings.get("max_length"))


def check(design_path, task=None, tolerance=None, lengths=None, n_samples: int = BOX_SAMPLES) -> dict:
    """Re-check the design of ``design_path`` (a design.json of ``mechopt design``).

    Parameters
    ----------
    design_path : path
        The design.json; the run.json beside it gives the task, requirements and bounds
        (of a ``mechopt design any`` run: those of the design's mechanism).
    task : str or Task, optional
        Another task (:func:`~mechopt.analysis.task.parse_task` text in the design's
        unit), placed as it is given; default run.json's task at the design's placement.
    tolerance : float, optional
        ``T`` [L]: also check every length and the task's placement within ``+- T``
        (:func:`tolerance_box`).
    lengths : dict or str, optional
        Lengths [L] that replace the design's (``"r1=85,r2=160"``), e.g. rounded ones.
    n_samples : int
        Random mechanisms inside the tolerance box besides its corners.

    Returns
    -------
    dict
        ``variables``, ``requirements`` (:func:`requirement_entries` at the nominal
        lengths), ``box`` (:func:`tolerance_box`, with ``tolerance``), ``certificate``
        (whether the certificate.json beside the design records it, by digest, and
        for a recorded design every claimed margin that the re-check does not find:
        each fails the check), ``holds`` (all of them) and ``fails`` (the names of
        those that do not).

    Raises
    ------
    ValueError
        One line, for an unreadable design.json or run.json (or one of another run),
        invalid ``lengths``, a ``task`` in another unit than the design's, or a
        ``tolerance`` that is not a finite length > 0.
    """
    from mechopt.analysis.task import Task, parse_task
    from mechopt.core import validation as _v
    from mechopt.export.source import task_from_dict

    rec, settings = _read_design(design_path)
    from mechopt.analysis.design_eval import get_spec

    spec = get_spec(rec["mechanism_name"])
    v = _variables(rec, spec, lengths)
    unit = rec["unit"]
    if task is None:
        the_task = task_from_dict(settings["task"])
    else:
        the_task = task if isinstance(task, Task) else parse_task(task, unit=unit)
        if the_task.unit != unit:
            raise ValueError(f"--task is in {the_task.unit}, the design in {unit}")
        v["task_x"], v["task_y"] = map(float, the_task.reference)
    if tolerance is not None:
        tolerance = _v.finite_number("--tolerance", tolerance)
        if not tolerance > 0:
            raise ValueError(f"--tolerance must be a length > 0, got {tolerance!r}")
    ev = _evaluator(settings, the_task, v["mode"])
    res = certify(ev, v)
    entries = requirement_entries(ev, res, proven_bounds(ev, v, res["margin"]))
    out = {"design": str(design_path), "mechanism": spec.name, "unit": unit, "variables": v,
           "requirements": entries, "sampling": asdict(Sampling.fine())}
    out["certificate"] = _certificate_match(Path(design_path), rec, entries)
    fails = [n for n, e in entries.items() if not e["holds"]]
    if out["certificate"] is not None:
        fails += [f"certificate.json: {d}" for d in out["certificate"]["disagrees"]]
    if tolerance is not None:
        box = tolerance_box(ev, v, tolerance, n_samples)
        out["box"] = box
        fails += [f"{n} (within +-{tolerance:g} {unit})" for n, ok in box["holds"].items()
                  if not ok and n not in fails]
    out["fails"], out["holds"] = fails, not fails
    return out


def is_certificate(path) -> bool:
    """Whether ``path`` names a certificate.json (a JSON object with
    ``certificate_version``), not a design.json.

    Parameters
    ----------
    path : path
        A file.

    Returns
    -------
    bool
        True for a certificate.json of ``mechopt design``.
    """
    from mechopt.run import io as _io

    try:
        data = _io.read_json(Path(path), f"the file {str(path)!r}")
    except (OSError, ValueError):
        return False
    return isinstance(data, dict) and "certificate_version" in data


def check_certificate(cert_path) -> dict:
    """Re-verify a certificate.json of ``mechopt design`` (or ``design any``): every design
    it records is re-certified from the certificate alone (its settings, variables and
    placement) with the certification's sampling and the proven bounds; each must hold,
    and each claim must be found again (:func:`_disagreements`: margin to
    :data:`CLAIM_RTOL`, verdict, ``proven``); a design certified over a tolerance box is
    re-checked over the same box (:func:`tolerance_box`, its corners and the interval
    bounds, no random draws, as ``mechopt design --tolerance``), which must hold as claimed.

    Parameters
    ----------
    cert_path : path
        The certificate.json.

    Returns
    -------
    dict
        ``file`` (the certificate's path), ``designs`` (per recorded design: ``index``,
        ``mechanism``, ``requirements`` (:func:`requirement_entries` of the re-check),
        ``fails``, with a box ``box``), ``holds`` (every design holds and agrees) and
        ``fails`` (``design <index>: <what>``, each).

    Raises
    ------
    ValueError
        One line, for a file that is not a readable certificate.json.
    """
    from mechopt.export.source import task_from_dict
    from mechopt.run import io as _io

    path = Path(cert_path)
    try:
        cert = _io.read_json(path, f"certificate {str(path)!r}")
        designs, all_settings = cert["designs"], cert["settings"]
        if not isinstance(designs, list) or not isinstance(all_settings, dict):
            raise TypeError
    except FileNotFoundError:
        raise ValueError(f"certificate {str(path)!r} does not exist") from None
    except (KeyError, TypeError):
        raise ValueError(f"{str(path)!r} is not a certificate.json of mechopt design") from None
    out, fails = [], []
    for entry in designs:
        try:
            # design any: settings per mechanism, each entry naming its mechanism
            settings = all_settings[entry["mechanism"]] if "mechanism" in entry else all_settings
            ev = _evaluator(settings, task_from_dict(settings["task"]), str(entry["variables"]["mode"]))
            v = _variables(entry, ev.spec, None)
            claimed = dict(entry["requirements"])
        except (KeyError, TypeError, AttributeError) as exc:
            raise ValueError(f"{str(path)!r}: design {entry.get('index', '?') if isinstance(entry, dict) else '?'} "
                             f"is not a certified design ({exc})") from None
        res = certify(ev, v)
        entries = requirement_entries(ev, res, proven_bounds(ev, v, res["margin"]))
        own = [n for n, e in entries.items() if not e["holds"]]
        own += [f"certificate.json: {d}" for d in _disagreements(claimed, entries)]
        rec = {"index": entry.get("index"), "mechanism": ev.spec.name, "requirements": entries}
        if "tolerance_box" in entry:
            T = float(entry["tolerance_box"]["tolerance"])
            rec["box"] = box = tolerance_box(ev, v, T, n_samples=0)
            own += [f"{n} (within +-{T:g} {ev.unit})" for n in box_failures(box)]
            if entry["tolerance_box"].get("method") == "proven" and box["method"] != "proven":
                own.append(f"certificate.json: the +-{T:g} {ev.unit} box (claimed proven, the check does not prove it)")
        rec["fails"] = own
        out.append(rec)
        fails += [f"design {rec['index']}: {f}" for f in own]
    return {"file": str(path), "designs": out, "fails": fails, "holds": not fails}


def format_check(report: dict) -> list:
    """The lines ``mechopt check`` prints for a :func:`check` report.

    Parameters
    ----------
    report : dict
        A :func:`check` report, or a :func:`check_certificate` one.

    Returns
    -------
    list of str
        The lines: the design, one per requirement (with the tolerance box's smallest
        margin when checked), whether certificate.json records it, and the verdict; for a
        certificate one line per recorded design and the verdict.
    """
    if "designs" in report:
        return _format_certificate_check(report)
    u = report["unit"]
    L = ", ".join(f"{k}={report['variables'][k]:.10g}" for k in report["variables"]
                  if k not in ("mode", "task_x", "task_y"))
    lines = [f"{report['mechanism']} {L} {u}, mode {report['variables']['mode']}, task centre at "
             f"({report['variables']['task_x']:.6g}, {report['variables']['task_y']:.6g}) {u}"]
    box = report.get("box")
    for name, e in report["requirements"].items():
        unit = f" {e['unit']}".rstrip(" -")
        line = (f"{name}: margin {e['margin']:.6g}{unit} ({'holds' if e['holds'] else 'FAILS'}, {e['method']}; "
                f"{e['describe']})")
        if box is not None:
            m = box["min_margin"][name]
            line += (f"; within +-{box['tolerance']:g} {u}: smallest margin {m:.6g}{unit} "
                     f"({'holds' if box['holds'][name] else 'FAILS'}, sampled at {box['evaluated']} mechanisms")
            if box.get("methods", {}).get(name) == "proven":
                p = box["proven"].get(name)
                line += (", proven over the box" if p is None else
                         f", proven over the box: lower bound {p['lower_bound']:.6g}, margin {p['proven_margin']:.6g}")
            line += ")"
        lines.append(line)
    cert = report.get("certificate")
    if cert is not None:
        lines.append("certificate.json records this design.json (digest)" if cert["index"] is not None else
                     "certificate.json does not record this design.json (edited since, or another run's): "
                     "checked on its own numbers")
    lines.append("all requirements hold" if report["holds"] else f"fails: {', '.join(report['fails'])}")
    return lines


def _format_certificate_check(report: dict) -> list:
    """:func:`format_check`'s lines for a :func:`check_certificate` report."""
    lines = [f"{report['file']}: {len(report['designs'])} certified designs re-checked"]
    for d in report["designs"]:
        how = ", ".join(f"{n} {e['method']}" for n, e in d["requirements"].items())
        box = d.get("box")
        if box is not None:
            how += f"; +-{box['tolerance']:g} box {box['method']}"
        verdict = "holds, every claim found again" if not d["fails"] else f"FAILS: {', '.join(d['fails'])}"
        lines.append(f"design {d['index']} ({d['mechanism']}): {verdict} ({how})")
    lines.append(f"all {len(report['designs'])} designs hold" if report["holds"]
                 else f"fails: {', '.join(report['fails'])}")
    return lines
