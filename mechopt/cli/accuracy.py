"""``mechopt accuracy DESIGN_DIR --error-model FILE [--samples N]``: the accuracy budget
of a design made by ``mechopt design``.

Runs :func:`mechopt.workflows.accuracy.accuracy`: prints the proven worst-case position
error over the design's task samples (the bound, its first-order part and its
second-order remainder, in um, and where it is reached), the largest error of the
Monte Carlo draws (exact forward kinematics of the perturbed mechanism) and their
ratio, and writes the error map (``--figure``, default ``DESIGN_DIR/error_map.png``;
colour bar in um). ``--json`` prints one JSON object instead (keys in docs/outputs.md).
"""
from __future__ import annotations

import json
import math

NAME = "accuracy"


def add_parser(subparsers):
    """Register ``accuracy``: the design folder, the error model, the Monte Carlo options."""
    p = subparsers.add_parser(NAME, help="accuracy budget of a design: proven worst-case position error",
                              description="The proven worst-case position error of a `mechopt design` "
                                          "design over its task under an error model (actuator resolution "
                                          "and backlash, joint clearance, link and base tolerances), its "
                                          "Monte Carlo check and an error map (um).")
    p.add_argument("design_dir", metavar="DESIGN_DIR", help="a `mechopt design` output folder (design.json, run.json)")
    p.add_argument("--error-model", required=True, metavar="FILE",
                   help="the tolerances, a JSON or TOML file: encoder_counts [counts/rev], backlash_arcmin, "
                        "resolution_um, backlash_um, clearance_um, link_tol_um, base_tol_um (docs/outputs.md)")
    p.add_argument("--samples", type=int, default=1000, metavar="N",
                   help="Monte Carlo draws per task sample, exact perturbed forward kinematics (default 1000)")
    p.add_argument("--draw", default="vertices", choices=("vertices", "uniform"),
                   help="where the draws lie in the tolerance box: its vertices (clearances on their circles; "
                        "where the largest error lies) or uniformly (default vertices)")
    p.add_argument("--seed", type=int, default=1, help="seed of the Monte Carlo draws (default 1)")
    p.add_argument("--figure", default=None, metavar="PATH",
                   help="the error map (default DESIGN_DIR/error_map.png)")
    p.add_argument("--json", action="store_true", help="print one JSON object (keys in docs/outputs.md)")


def run(args) -> int:
    """Evaluate the design's accuracy budget, print it, write the error map."""
    from pathlib import Path

    from mechopt.analysis.accuracy import load_error_model
    from mechopt.workflows.accuracy import accuracy

    model = load_error_model(args.error_model)
    figure = args.figure or str(Path(args.design_dir) / "error_map.png")
    res = accuracy(args.design_dir, model, args.samples, args.seed, args.draw, figure)
    if args.json:
        print(json.dumps({k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                          for k, v in res.items()}, allow_nan=False))
        return 0
    u = res["unit"]
    print(f"{res['mechanism']} over {res['poses']} task samples:")
    print(f"  proven worst-case position error  {res['bound_um']:.4g} um at ({res['at'][0]:.4g}, "
          f"{res['at'][1]:.4g}) {u} (first order <= {res['linear_um']:.4g} um, second-order remainder "
          f"<= {res['remainder_um']:.3g} um)")
    print(f"  maximum over the task (refined)   {res['task_max_um']:.4g} um (the samples' maximum refined by "
          "zooming, as --max-error checks)")
    print(f"  worst along x / y (first order)   {res['worst_x_um']:.4g} / {res['worst_y_um']:.4g} um")
    print(f"  Monte Carlo maximum               {res['mc_max_um']:.4g} um ({res['samples']} {res['draw']} "
          f"draws per sample, seed {res['seed']}); bound / Monte Carlo = {res['ratio']:.4f}")
    if res["unbounded_poses"]:
        print(f"  {res['unbounded_poses']} samples without a proof (unreachable or next to a type-II singularity)")
    print(f"wrote {figure}")
    return 0
