"""``mechopt check DESIGN.json [--lengths r1=85,...] [--task TASK] [--tolerance T]``:
re-check a design.

Runs :func:`mechopt.workflows.certificate.check`: the design of a ``design.json`` of
``mechopt design`` (its lengths possibly rounded by hand, in the file or with
``--lengths``), re-evaluated with the full evaluator and the certification's sampling
against the task and requirements of the ``run.json`` beside it (or ``--task``), and with
``--tolerance T`` every mechanism whose lengths lie within ``+- T``, the task placed within
``+- T`` in x and y (the box's corners and a seeded sample inside it, sampled; also the interval bounds over the
task and the whole box, which prove LCI, the type-II function, speed, force and reach
where they meet them). Prints one line per requirement
(its margin in its unit, holds or FAILS, proven or refined-sampled) and a last line;
exit status 0 when every requirement holds, 1 naming those that fail, 2 on bad input.

``mechopt check DIR/certificate.json`` re-verifies a certificate
(:func:`mechopt.workflows.certificate.check_certificate`): every design it records,
re-certified from the certificate alone (and over its tolerance box, if it has one),
must hold and every claim must be found again; one line per design.
"""
from __future__ import annotations

import json

NAME = "check"


def add_parser(subparsers):
    """Register ``check``."""
    p = subparsers.add_parser(NAME, help="re-check a design.json (rounded lengths, a tolerance box) or a certificate.json: exit 0 "
                                         "if every requirement holds, 1 if one fails",
                              description="Re-evaluate the design of a design.json with the full evaluator "
                                          "against the task and requirements of the run.json beside it; exit 0 "
                                          "when every requirement holds, 1 when one fails (named), 2 on bad "
                                          "input.")
    p.add_argument("design", metavar="DESIGN.json", help="a design.json written by mechopt design (a run.json "
                                                         "must lie beside it), or a certificate.json to re-verify "
                                                         "every design it records")
    p.add_argument("--lengths", default=None, metavar="NAME=VALUE,...",
                   help="lengths [the design's unit] replacing the file's, e.g. rounded ones: r1=85,r3=12.5")
    p.add_argument("--task", default=None,
                   help="check against this task instead (same syntax as mechopt design --task, lengths [unit] "
                        "of the design, placed as given; default: run.json's task at the design's placement)")
    p.add_argument("--tolerance", default=None, metavar="T",
                   help="also check every length and the task's placement (x, y) within +-T [the design's "
                        "unit] of the nominal ones: the lengths' 2^n corners, the placement's 4 and 32 seeded "
                        "points of the whole box (sampled); also interval bounds over the whole box "
                        "(proven where they meet a requirement)")
    p.add_argument("--json", action="store_true", help="print the report as one JSON object (keys: "
                                                       "docs/outputs.md)")


def run(args) -> int:
    """Check the design, print the report, return 0 (holds) or 1 (fails)."""
    from mechopt.run.io import plain_json
    from mechopt.workflows.certificate import check, check_certificate, format_check, is_certificate

    if is_certificate(args.design):
        given = [o for o, val in (("--lengths", args.lengths), ("--task", args.task), ("--tolerance", args.tolerance))
                 if val is not None]
        if given:
            raise ValueError(f"{given[0]} applies to a design.json; a certificate.json is re-verified as it stands")
        report = check_certificate(args.design)
    else:
        report = check(args.design, task=args.task, tolerance=args.tolerance, lengths=args.lengths)
    if args.json:
        print(json.dumps(plain_json(report), sort_keys=True))
    else:
        print("\n".join(format_check(report)))
    return 0 if report["holds"] else 1
