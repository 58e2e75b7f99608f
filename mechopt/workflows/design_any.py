"""Which mechanism? Size every mechanism for one task and keep the designs no other
mechanism beats: ``mechopt design any``.

:func:`design_any` runs :func:`mechopt.workflows.design.design` for each mechanism (the
same task, requirements, objectives and run options; a mechanism to which a
requirement does not apply, or that cannot reach the task within the length bounds,
is skipped with its reason), certifies each front as usual, and merges the fronts: a
design is on the merged front when no design of any mechanism dominates it in the
chosen objectives. The objectives are the same quantities in the same units for every
mechanism (size in the task's unit, LCI, speed, force...), so the comparison is
direct; the ``size`` of each mechanism is its own sum of link lengths (each spec's
docstring), which is what a designer compares. Files: ``front.csv`` (the merged
front, a ``mechanism`` column first), ``fronts.csv`` (every mechanism's certified
front), ``design.json`` (the chosen design, with its mechanism), ``run.json``,
``front.png`` (the fronts coloured by mechanism, the merged front and the chosen
design marked) and ``design.png``.
"""
from __future__ import annotations

import time

import numpy as np
import pandas as pd

from mechopt import mechanisms as _mechanisms
from mechopt.analysis.design_eval import NoFeasibleDesign, parse_pick, pick_index

__all__ = ["design_any", "any_certificate", "ANY_OUTPUTS", "AnyResult"]

#: the files ``mechopt design any`` writes
ANY_OUTPUTS = ("front.csv", "fronts.csv", "design.json", "certificate.json", "run.json", "front.png", "design.png")


class AnyResult:
    """The outcome of :func:`design_any`: ``front`` (the merged front, a ``mechanism``
    column), ``fronts`` (every mechanism's front), ``results`` (``{mechanism:
    DesignResult}``), ``skipped`` (``{mechanism: reason}``), ``chosen`` (the chosen
    design's record) and ``info`` (run.json).

    Parameters
    ----------
    front : DataFrame
        The merged front (a ``mechanism`` column).
    fronts : dict
        ``{mechanism: DataFrame}``.
    results : dict
        ``{mechanism: DesignResult}``.
    skipped : dict
        ``{mechanism: reason}``.
    chosen : dict
        The chosen design's record.
    info : dict
        run.json.
    """

    def __init__(self, front, fronts, results, skipped, chosen, info):
        self.front, self.fronts, self.results = front, fronts, results
        self.skipped, self.chosen, self.info = skipped, chosen, info


def _merged_front(fronts: pd.DataFrame, senses: dict) -> pd.DataFrame:
    """The rows of ``fronts`` no other row dominates in the objectives ``senses``
    (``{name: +1 minimised, -1 maximised}``), sorted by the objectives."""
    F = np.column_stack([s * fronts[o].to_numpy(float) for o, s in senses.items()])
    keep = [i for i in range(len(F)) if not (np.all(F <= F[i], axis=1) & np.any(F < F[i], axis=1)).any()]
    return fronts.iloc[keep].sort_values(list(senses), kind="mergesort").reset_index(drop=True)


def design_any(task, requirements=None, objectives=("size", "min-lci"), *, mechanisms=None, pick=None,
               out=None, overwrite=False, progress=False, **options) -> AnyResult:
    """Size each of ``mechanisms`` (default: every mechanism ``mechopt design`` sizes) for
    ``task`` and merge their certified fronts (module docstring). ``options`` are those
    of :func:`mechopt.workflows.design.design` (mode, place, length bounds, algorithm,
    pop, gen, seed, n_jobs, client, polish). Raises :class:`NoFeasibleDesign` naming
    each mechanism's reason when none has a feasible design.

    Parameters
    ----------
    task : mechopt.analysis.task.Task
        The task.
    requirements : mechopt.requirements.Requirements, optional
        What must hold over the task.
    objectives : sequence of str
        Objective names.
    mechanisms : sequence of str, optional
        The mechanisms to compare.
    pick : dict or str, optional
        Weights choosing design.json (default: the knee).
    out : str or Path, optional
        Output folder.
    overwrite : bool
        Replace another run that ``out`` holds.
    progress : bool
        Log the progress.
    **options : 
        As for :func:`mechopt.workflows.design.design`.

    Returns
    -------
    AnyResult
        The merged front and every mechanism's result.

    Raises
    ------
    mechopt.analysis.design_eval.NoFeasibleDesign
        Naming each mechanism's reason, when none has a feasible design.
    """
    from mechopt.run import io as _io
    from mechopt.workflows.design import json_record, design, plot_design

    names = tuple(mechanisms) if mechanisms else _mechanisms.designed()
    for m in names:
        _mechanisms.design_spec(m)  # an unknown name is a one-line error before any run
    objectives = (objectives,) if isinstance(objectives, str) else tuple(objectives)
    if pick is not None:
        parse_pick(pick, objectives)
    t0 = time.perf_counter()
    results, skipped = {}, {}
    for m in names:
        try:
            results[m] = design(m, task, requirements, objectives, progress=progress, **options)
        except NoFeasibleDesign as exc:
            skipped[m] = f"no feasible design: {exc}"
        except ValueError as exc:  # a requirement that does not apply, a task out of reach
            skipped[m] = str(exc)
    if not results:
        raise NoFeasibleDesign("no mechanism has a feasible design: "
                               + "; ".join(f"{m}: {why}" for m, why in skipped.items()))
    senses = next(iter(results.values())).evaluator.senses()
    fronts = pd.concat([r.front.assign(mechanism=m)[["mechanism", *r.front.columns]] for m, r in results.items()],
                       ignore_index=True)
    front = _merged_front(fronts, senses)
    F = np.column_stack([s * front[o].to_numpy(float) for o, s in senses.items()])
    i = pick_index(F, objectives, pick)
    m = front["mechanism"].iloc[i]
    own = results[m].front
    lengths = [c for c in (*results[m].evaluator.spec.lengths, "mode", "task_x", "task_y") if c in own]
    j = int(np.flatnonzero((own[lengths] == front.iloc[i][lengths]).all(axis=1))[0])
    chosen = results[m].design_at(j)
    info = {"mechanisms": list(names), "skipped": skipped, "objectives": list(objectives),
            "front_size": int(len(front)), "per_mechanism": {k: {"front_size": int(len(r.front)),
                                                                 "on_merged_front": int((front["mechanism"] == k).sum()),
                                                                 "run": r.info} for k, r in results.items()},
            "chosen": {"index": int(i), "mechanism": m, "by": "knee" if pick is None else f"pick {pick}"},
            "wall_time_s": time.perf_counter() - t0}
    if out is not None:
        out = _io.prepare_out_dir(out)
        key = {"task": repr(task.to_dict()), "requirements": repr(requirements), "objectives": list(objectives),
               "mechanisms": list(names), "pick": pick, **{k: repr(v) for k, v in options.items()}}
        fig_front = _plot_fronts(fronts, front, senses, i, results[m].evaluator.units())
        fig_design = plot_design(results[m].evaluator, chosen)
        with _io.run_in(out, "design-any", key, ANY_OUTPUTS, overwrite) as manifest:
            with _io.output_set(out, manifest) as stage:
                _io.write_csv(front, stage / "front.csv")
                _io.write_csv(fronts, stage / "fronts.csv")
                _io.write_json(json_record(chosen), stage / "design.json")
                _io.write_json(any_certificate(results, chosen), stage / "certificate.json")
                _io.write_json(info, stage / "run.json")
                _io.save_figure(fig_front, stage / "front.png")
                _io.save_figure(fig_design, stage / "design.png")
    return AnyResult(front, fronts, results, skipped, chosen, info)


def any_certificate(results: dict, chosen: dict) -> dict:
    """certificate.json of ``mechopt design any``: every mechanism's certificate
    (:func:`mechopt.workflows.certificate.certificate`) in one list of designs, each
    entry with its ``mechanism`` and an index over the list, ``settings`` per mechanism,
    and ``chosen`` the index of design.json's design (by its digest).

    Parameters
    ----------
    results : dict
        ``{mechanism: DesignResult}`` of the run.
    chosen : dict
        The chosen design's record (design.json before JSON conversion).

    Returns
    -------
    dict
        Plain JSON data: ``certificate_version``, ``mechopt_version``, ``settings``
        (``{mechanism: settings}``), ``sampling``, ``chosen``, ``designs`` and ``note``.
    """
    from mechopt.export.source import design_digest
    from mechopt.run.io import plain_json
    from mechopt.workflows.certificate import certificate

    out, designs = None, []
    for m, r in results.items():
        c = certificate(r)
        if out is None:
            out = {k: c[k] for k in ("certificate_version", "mechopt_version", "sampling", "note")}
            out["settings"] = {}
        out["settings"][m] = c["settings"]
        designs += [{**d, "mechanism": m, "index": len(designs) + k} for k, d in enumerate(c["designs"])]
    digest = design_digest(plain_json({k: val for k, val in chosen.items() if k != "mechanism"}))
    out["chosen"] = next(d["index"] for d in designs if d["digest"] == digest)
    out["designs"] = designs
    return out


def _plot_fronts(fronts, front, senses, chosen, units):
    """Every mechanism's front (one colour each), the merged front circled and the
    chosen design starred, in the first two objectives (or the one objective against
    the mechanism)."""
    from matplotlib.figure import Figure

    obs = list(senses)
    fig = Figure(figsize=(6.5, 4.5))
    ax = fig.add_subplot()
    label = {o: f"{o} [{units[o]}]" if units[o] not in ("", "-") else f"{o} [-]" for o in obs}
    mechs = list(dict.fromkeys(fronts["mechanism"]))
    for k, m in enumerate(mechs):
        rows = fronts[fronts["mechanism"] == m]
        x = rows[obs[0]] if len(obs) > 1 else np.full(len(rows), k)
        y = rows[obs[1]] if len(obs) > 1 else rows[obs[0]]
        ax.scatter(x, y, s=16, color=f"C{k}", label=m)
    x = front[obs[0]] if len(obs) > 1 else front["mechanism"].map(mechs.index)
    y = front[obs[1]] if len(obs) > 1 else front[obs[0]]
    ax.scatter(x, y, s=70, facecolors="none", edgecolors="k", linewidths=1.0, label="merged front")
    ax.scatter([np.asarray(x)[chosen]], [np.asarray(y)[chosen]], marker="*", s=220, color="C3",
               edgecolors="k", linewidths=0.6, label="chosen design")
    if len(obs) > 1:
        ax.set_xlabel(label[obs[0]])
        ax.set_ylabel(label[obs[1]])
    else:
        ax.set_xticks(range(len(mechs)), mechs)
        ax.set_ylabel(label[obs[0]])
    if len(obs) == 1:
        ax.ticklabel_format(useOffset=False, axis="y")
    ax.legend(fontsize=7)
    ax.set_title(f"one front across mechanisms: {len(front)} designs", fontsize=10)
    return fig
