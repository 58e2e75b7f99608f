"""Write ``docs/outputs.md``: every file, CSV column and JSON key a ``mechopt`` command writes.

    python docs/gen_outputs.py            # rewrite docs/outputs.md
    python docs/gen_outputs.py --check    # exit status 1 if docs/outputs.md is not current

The names come from the code wherever the code defines them: the registered
mechanisms, their declared parameters and ``summary()`` keys,
:data:`mechopt.analysis.evaluate.DISK_KEYS`, every registered problem's variables,
objectives (with their units), constraints and derived columns (one evaluation of
the design in the middle of its bounds), the Liu 2006 regions, the atlas columns,
the design objectives, requirements and mechanism lengths, and the reproduction
table's columns, kinds and statuses. Meanings and units live in the glossaries
below; a name the code produces without a glossary entry stops the script, so the
page cannot silently miss a new column. The keys of dictionaries that the code
builds inline (``run.json``, ``atlas.json``, ``design.json``, ``manifest.json``)
are listed here by hand; ``tests/test_docs.py`` runs the commands and checks that
every file, column and key they write is on the page, and that the page is current.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

PAGE = Path(__file__).resolve().parent / "outputs.md"

# --------------------------------------------------------------------------- glossaries
#: ``mechopt evaluate`` of a mechanism with ``disk_indices`` (DISK_KEYS)
EVAL_DISK = {
    "r_mic": ("radius of the maximal inscribed circle (MIC): the largest disk centred on the y axis "
              "free of singular points of the working mode (Liu 2006 footnote 2, Le 2013 sec. III)", "L"),
    "mic_center_y": ("y of the MIC centre `(0, mic_center_y)`", "L"),
    "gci": ("global conditioning index: mean LCI over the MIC (Liu 2006 eq. 4), `quadrature` rule", "-"),
    "mci": ("maximum LCI over the MIC (Liu 2006 sec. 2.1)", "-"),
    "gvi_max": ("mean of `|V|max = 1/s_min` over the disk of radius `r_mic/2` (Liu eq. 10-11)", "L"),
    "gvi_min": ("mean of `|V|min = 1/s_max` over that disk (Liu eq. 10-11)", "L"),
    "gpi_max": ("mean of `|tau|max = s_max` over that disk (Liu eq. 13-14)", "1/L"),
    "gpi_min": ("mean of `|tau|min = s_min` over that disk (Liu eq. 13-14)", "1/L"),
    "gsi_max": ("mean of `|D|max = 1/s_min^2` over that disk, unit actuator stiffness (Liu eq. 18-19)", "L^2"),
    "gsi_min": ("mean of `|D|min = 1/s_max^2` over that disk (Liu eq. 18-19)", "L^2"),
    "usable_area": ("area of the usable workspace: the connected singularity-free region above the base "
                    "holding the MIC centre (Liu sec. 3.2.1)", "L^2"),
    "gcw_area": ("area of the good-conditioning workspace (GCW): usable points with LCI >= `gamma` "
                 "(Liu sec. 3.2.3, Fig. 25); 0 when empty", "L^2"),
    "gcw_gci": ("mean LCI over the GCW (null when it is empty)", "-"),
    "gcw_gsi_max": ("mean of `|D|max` over the GCW (null when empty)", "L^2"),
    "gcw_gsi_min": ("mean of `|D|min` over the GCW (null when empty)", "L^2"),
    "gcw_square_side": ("side of the largest square centred on the y axis inside the GCW (Liu Fig. 28); "
                        "0 when none", "L"),
    "gcw_square_center_y": ("y of that square's centre (null when none)", "L"),
    "theta1_range_deg": ("`[lo, hi]` of crank angle 1 over the GCW, continuous (Le eq. 17-18); "
                         "null when the GCW is empty", "deg"),
    "theta2_range_deg": ("`[lo, hi]` of crank angle 2 over the GCW (Le eq. 17-18)", "deg"),
    "quadrature": ("rule of the disk means: `area` (true area mean) or `polar` (uniform (r, theta) "
                   "grid, Liu's)", ""),
    "mode": ("working mode (signs of Le eq. 17-18, leg 1 first)", ""),
    "gamma": ("LCI level bounding the GCW", "-"),
}
#: ``mechopt evaluate``: the mechanism's own ``summary()`` keys, per mechanism
EVAL_SUMMARY = {
    "asymmetric-five-bar": {
        "workspace_area": ("area of the reachable set (mid-point raster rule)", "L^2"),
        "mean_lci": ("area mean of the LCI over the reachable set", "-"),
        "mean_tqi": ("area mean of the TQI (Stan 2008 eq. 9) over the reachable set", "-"),
        "quadrature": ("the rule of the means: `raster-N` (N cells across the smaller side of the "
                       "bounding box)", ""),
    },
    "biglide": {
        "workspace_area": ("exact area of the workspace (Stan 2008 eq. 8, the instance's mode)", "L^2"),
        "gtqi": ("area mean of the TQI over the workspace (Stan eq. 9)", "-"),
        "tqi_integral": ("integral of the TQI over the workspace (the numerator of `gtqi`)", "L^2"),
        "k_av_1": ("Wu 2008 eq. (7) velocity output ratio of leg 1 over the x range (null when "
                   "unbounded, `l2 >= 2 l1`)", "-"),
        "k_av_2": ("the same for leg 2", "-"),
        "quadrature": ("the rule of `gtqi`: `adaptive-1d`", ""),
    },
    "bipod": {
        "workspace_area": ("exact area of the workspace (Stan 2008 eq. 8, the instance's branch)", "L^2"),
        "gtqi": ("exact area mean of the TQI (Stan eq. 9)", "-"),
        "tqi_integral": ("integral of the TQI over the workspace (the numerator of `gtqi`)", "L^2"),
        "q1_min_over_b": ("Stan's design variable `q1_min / b` (eq. 11)", "-"),
        "quadrature": ("how the mean is taken: `exact` (closed form)", ""),
    },
    "gantry": {
        "workspace_area": ("exact area of the reachable set", "length_unit^2"),
        "k_av": ("global velocity output ratio, literal reading of Wu 2008 eq. (7) over `[-b/2, b/2]`",
                 "-"),
        "d": ("Wu eq. (14)", "length_unit"),
        "d1": ("half the distance of the columns, Wu eq. (15)", "length_unit"),
        "l": ("link length, Wu eq. (15)", "length_unit"),
        "stroke": ("actuator stroke `|q_iL - q_iS|`, Wu eq. (16)", "length_unit"),
        "eta_d": ("global dynamic index: area mean of kappa_D over the task rectangle (Wu eq. 44)", "-"),
        "gtqi": ("area mean of the TQI over the task rectangle", "-"),
        "quadrature": ("the rule of the means: `gauss-legendre-NxN`", ""),
    },
}
#: a design of each mechanism for the page's example commands (required parameters)
EVAL_EXAMPLES = {
    "asymmetric-five-bar": {"a1": 1.0, "c1": 1.5, "a2": 0.8, "c2": 1.7, "r3": 0.5},
    "biglide": {"l1": 1.0, "l2": 1.1, "q1_min": 0.0, "q1_max": 1.0},
    "bipod": {"b": 60.0, "q1_min": 80.0, "q1_max": 130.0},
    "five-bar": {"r1": 0.85, "r2": 1.6, "r3": 0.55},
    "gantry": {},
}

#: unit of the lengths of each problem family
FAMILY_UNIT = {
    "le2013": "lengths in units of the crank `l1` (= 1)",
    "liu2006": "non-dimensional lengths `r1 + r2 + r3 = 3`",
    "stan2008": "lengths in units of the Bipod's `b` (= 1) or the Biglide's `L1` (= 1)",
    "wu2008": "lengths in mm (the task is 500 x 400 mm)",
    "design": "lengths in the task's unit (`--unit`, default mm)",
}
#: front.csv columns of the problems, per family (objectives take their unit from the code)
PROBLEM_COLUMNS = {
    "le2013": {
        "rho": ("`l2 / l1`, the distal-to-crank ratio (Le eq. 24)", "-"),
        "l0": ("half base distance (our `r3`); eq. (24) `l0 = sqrt(2)/2 (l2 - l1)` unless relaxed", "l1"),
        "gamma": ("LCI level guaranteed on the square (Le eq. 23); a variable and an objective of the "
                  "`-gamma` problems", "-"),
        "a_max": ("side of the largest square centred at the MIC centre inside the MIC on which "
                  "`1/kappa >= gamma` and the joint limits hold (Le eq. 23-26, Fig. 4)", "l1"),
        "r_mic": ("MIC radius", "l1"),
        "mic_center_y": ("y of the MIC centre", "l1"),
        "lci_min": ("smallest LCI inside the square (empty without a square)", "-"),
        "lci_max": ("largest LCI inside the square (empty without a square)", "-"),
        "violation": ("the value of `g_square_exists` (a copy among the derived columns)", "-"),
    },
    "liu2006": {
        "u": ("share of `r1` in `r1 + r2`: `r1 = u (3 - r3)`, `r2 = (1 - u)(3 - r3)`", "-"),
        "r1": ("crank length", "L"),
        "r2": ("distal link length", "L"),
        "r3": ("half the base distance", "L"),
        **{k: EVAL_DISK[k] for k in ("r_mic", "mic_center_y", "gci", "mci", "gvi_max", "gvi_min",
                                     "gpi_max", "gpi_min", "gsi_max", "gsi_min")},
    },
    "stan2008": {
        "q1_min_over_b": ("Bipod design variable `u = q1_min / b` (Stan eq. 11-12), `q_max = 1.6 q_min`",
                          "-"),
        "L2": ("Biglide link length (`L1 = 1`, strokes `[0, 1]`)", "L"),
        "W": ("exact workspace area (Stan eq. 8)", "L^2"),
        "T": ("area mean of the TQI over the workspace (Stan eq. 9)", "-"),
        "W_n": ("`W / W_ref`, `W_ref` the area at the upper bound of the design variable", "-"),
    },
    "wu2008": {
        "theta_1S_deg": ("smallest link angle `theta_1S` (Wu sec. 4.3)", "deg"),
        "k_av": ("global velocity output ratio, literal reading of Wu eq. (7)", "-"),
        "l": ("link length (eq. 15)", "mm"),
        "d": ("eq. (14)", "mm"),
        "d1": ("half the distance of the columns (eq. 15)", "mm"),
        "stroke": ("actuator stroke (eq. 16)", "mm"),
        "eta_d": ("global dynamic index: mean kappa_D over the task (eq. 44)", "-"),
    },
    "design": {
        "size": ("sum of the link lengths (objective `size`)", "unit"),
        "min-lci": ("minimum LCI over the task (objective)", "-"),
        "lci_min": ("minimum LCI over the task", "-"),
        "reach_margin": ("certified clearance of the task inside the reachable set", "unit"),
        "mode_index": ("index of the working mode in the mechanism's modes", "-"),
        "mode": ("working mode as an index into the mechanism's modes (with `mode=\"any\"`)", "-"),
        "task_x_rel": ("task placement in x relative to the design's reach, in [-1, 1] (free placement)",
                       "-"),
        "task_y_rel": ("task placement in y relative to the design's reach, in [0, 1] (free placement)",
                       "-"),
    },
}
#: constraint columns ``g_<name>`` (``G <= 0`` is feasible), per family
CONSTRAINTS = {
    "le2013": {
        "square_exists": "`-a_max / a_in` (< 0, `a_in = sqrt(2) r_MIC`) when a square exists; otherwise "
                         "how far the design is from having one: 1 without a MIC, else the larger of "
                         "`(gamma - LCI) / gamma` and the joint-limit excess over pi at the MIC centre",
    },
    "liu2006": {"has_mic": "-1 with a MIC, 1 without one (no index is defined)"},
    "design": {},
}
#: requirements of ``mechopt design``: (meaning of margin_<name> / g_<name>, unit of the margin)
HISTORY = {
    "generation": ("generation number, from 1", "-"),
    "evaluations": ("designs evaluated so far", "-"),
    "n_front": ("designs in the algorithm's current optimum", "-"),
    "best_<objective>": ("best value of each objective over that optimum, natural sign (empty while no "
                         "design is feasible)", "of the objective"),
    "hypervolume": ("with two or more objectives: hypervolume of the feasible optimum in objectives "
                    "normalised to [0, 1] by their declared bounds, reference point 1.1 in every "
                    "direction; in [0, 1.1^m], 0 while nothing is feasible, empty if an objective "
                    "declares no bounds", "-"),
}
RUN_JSON = {
    "problem": ("registry name of the problem", ""),
    "summary": ("the problem's one-line summary", ""),
    "settings": ("every option of the problem, defaults filled in (a run folder of a run with other "
                 "settings is refused): the Liu problems' `region` and `quadrature`, `stan2008-biglide`'s "
                 "`l1`, `q_min`, `q_max`, `wu2008`'s `b`, `h`, `le2013-gamma`'s `tied`, the design "
                 "problem's task and requirements", ""),
    "region": ("setting: the Liu 2006 optimum region (sec. 3.1)", ""),
    "tied": ("setting: the half base follows Le eq. (24) (false: it is a variable)", ""),
    "q_min": ("setting: lower stroke limit of both Biglide sliders", "L"),
    "q_max": ("setting: upper stroke limit of both Biglide sliders", "L"),
    "single_optimum": ("why the front is a single design, or null", ""),
    "algorithm": ("`name`, `pop` and `gen` (the generation limit, null if the termination sets none)", ""),
    "name": ("algorithm name (`ga`, `de`, `nsga2`, `nsga2-mnn`, `nsga3` or a class name)", ""),
    "pop": ("population size", "-"),
    "gen": ("generation limit", "-"),
    "algorithm_settings": ("the pymoo algorithm: `class`, `module`, `pop_size`, `n_offsprings`, its "
                           "operators `sampling`, `selection`, `crossover`, `mutation` (or DE's `mating`) "
                           "and `survival`, each with `class` and its settings under pymoo's names, "
                           "`eliminate_duplicates`, `n_ref_dirs` (NSGA-III), `settings` (a user class)", ""),
    "termination": ("the pymoo termination: `class` and its parameters (`n_max_gen`, `n_max_evals`, "
                    "`max_time`, `fmin`, `xtol`, `cvtol`, `ftol`, `period`)", ""),
    "seed": ("random seed", "-"),
    "n_jobs": ("worker processes used", "-"),
    "n_jobs_auto": ("true when `n_jobs` was chosen by timing the first two generations", ""),
    "seconds_per_generation": ("the timed CPU time of a generation (with `n_jobs_auto`)", "s"),
    "backend": ("`joblib` or `dask`", ""),
    "versions": ("`mechopt`, `pymoo` and `numpy` versions", ""),
    "wall_time_s": ("wall-clock time of the run", "s"),
    "generations": ("generations run", "-"),
    "evaluations": ("designs evaluated", "-"),
    "feasible": ("feasible designs in the final population (0: no feasible design)", "-"),
    "least_violation": ("with no feasible design: the smallest total violation, sum of max(0, g)", "-"),
    "least_violating_design": ("with no feasible design: the variables of that design", ""),
    "constraint_violations": ("with no feasible design: its max(0, g) per `g_*` column", "-"),
}
SUBKEYS = {  # names listed under a key of run.json / manifest.json; not re-described
    "class", "module", "pop_size", "n_offsprings", "sampling", "selection", "crossover", "mutation",
    "mating", "survival", "eliminate_duplicates", "n_ref_dirs", "n_max_gen", "n_max_evals", "max_time",
    "fmin", "xtol", "cvtol", "ftol", "period", "mechopt", "pymoo", "numpy",
}
SWEEP_JSON = {
    "weights": ("the weights run", "-"),
    "feasible_weights": ("weights whose optimum is feasible", "-"),
    "evaluations": ("designs evaluated by all runs (the NSGA-II front and every weight)", "-"),
    "feasible": ("feasible designs in the final populations of all runs", "-"),
    "least_violation": ("with no feasible design anywhere: the smallest total violation", "-"),
    "least_violating_design": ("with no feasible design anywhere: that design's variables", ""),
    "constraint_violations": ("with no feasible design anywhere: its max(0, g) per `g_*` column", "-"),
}
MANIFEST = {
    "kind": ("the command that wrote the folder: `optimize`, `sweep`, `atlas`, ...", ""),
    "key": ("what fixes the result (problem, its settings, algorithm, termination and seed; for an "
            "atlas its settings): a folder holding another run is refused without `--overwrite`", ""),
    "run_id": ("random identifier of the run (its checkpoint carries the same)", ""),
    "status": ("`running` until every file is in place, then `complete`", ""),
    "files": ("`{file name: sha256}` of every file the run wrote", ""),
    "started": ("start time, ISO 8601 with the UTC offset", ""),
    "finished": ("end time, ISO 8601 with the UTC offset", ""),
    "mechopt": ("mechopt version", ""),
    "owned": ("files the run wrote outside its set (its `checkpoint.pkl`; for `reproduce`, `README.md` "
              "and the paper folders)", ""),
    "mac": ("HMAC-SHA256 of the other keys under the user's checkpoint key: only an authentic manifest "
            "lets a later run (`--overwrite`) remove the files it lists, and only plain names of the "
            "command's outputs that are regular files (a listed `files` entry also needs its sha256)", ""),
}
DESIGN_JSON = {
    "index": ("row of the design in `front.csv`", "-"),
    "mechanism_name": ("`five-bar`, `biglide`, `bipod` or `gantry`", ""),
    "unit": ("the length unit (`--unit`)", ""),
    "variables": ("the mechanism's lengths by name, `mode`, and `D` with `--shape`", "unit"),
    "task_placement": ("`task_x`, `task_y`: where the task's reference point is placed", "unit"),
    "objectives": ("`{objective: value}`, natural sign", "of `objective_units`"),
    "objective_units": ("`{objective: unit}`", ""),
    "margins": ("`{requirement: margin}` in natural units (the requirements above), > 0 satisfied",
                "see below"),
    "constraints_g": ("`{requirement: g}`, normalised, <= 0 satisfied", "-"),
    "feasible": ("every `g <= 0` under the fine certification", ""),
    "values": ("`type2_min` (smallest sine of the leg angle over the task), `lci_min`, `lci_mean` "
               "(over the interior grid), `size` [unit], and with their options `footprint` [unit], "
               "`speed` [unit/s], `force` [N], `torque` [N m or N], `error_um` [um] (the proven worst-case "
               "position error over the task, with `--max-error` or the `error` objective), `peak_torque`, "
               "`rms_torque` [N m or N] (along the pick-and-place cycle, with `--cycle-time`)", ""),
    "tolerance": ("what the margins rest on: `boundary_gap` [unit], `interior_step` [unit], `reach` and "
                  "`minima` (sentences); for a point task `points`", ""),
    "repr": ("the mechanism as Python (`FiveBar(r1=..., ...)`)", ""),
    "joint_ranges_deg": ("five-bar: `[[lo, hi], [lo, hi]]` crank ranges over the task", "deg"),
    "strokes": ("sliders: `[[q_min, q_max], ...]` actuator ranges over the task", "unit"),
    "stroke": ("sliders: the longest stroke", "unit"),
    "link1_angle_deg": ("gantry, biglide with `--link-angle`: `[lo, hi]` of link 1's angle", "deg"),
    "link2_angle_deg": ("the same for link 2", "deg"),
}
#: `certificate.json` of `mechopt design` (mechopt.workflows.certificate.certificate)
CERTIFICATE_JSON = {
    "certificate_version": ("the format of the file (1)", ""),
    "mechopt_version": ("the mechopt that wrote it", ""),
    "settings": ("the sizing problem, as run.json's `design`", ""),
    "sampling": ("the certification's sampling: `n_boundary`, `n_interior`, `refine`", ""),
    "chosen": ("the index (in `designs`, the row of `front.csv`) of the design of `design.json`", "-"),
    "note": ("what `proven` and `refined-sampled` mean", ""),
    "designs": ("one object per front design (the rows of `front.csv`, in order), keys below", ""),
}
#: the keys of one design of certificate.json and of one requirement under it
CERTIFICATE_DESIGN = {
    "index": ("row of `front.csv`", "-"),
    "digest": ("sha256 of the design record's canonical JSON (as `export.json`'s `design_sha256`); the "
               "chosen design's is that of `design.json`", ""),
    "variables": ("lengths by name and `mode`, as in `design.json`", "unit"),
    "task_placement": ("`task_x`, `task_y`", "unit"),
    "feasible": ("every requirement holds", ""),
    "requirements": ("`{requirement: {...}}` with the keys below", ""),
    "tolerance": ("what the margins rest on, as in `design.json`", ""),
    "tolerance_box": ("with `mechopt design --tolerance T`: the box the design was certified over, the keys of "
                      "`mechopt check --json`'s `box` below (its corners evaluated, no random draws; every "
                      "requirement with an interval bound proven over the whole box)", ""),
}
CERTIFICATE_REQUIREMENT = {
    "margin": ("the requirement's margin (> 0 satisfied), as `margin_<name>` of `front.csv`", "its `unit`"),
    "unit": ("the margin's unit", ""),
    "g": ("normalised constraint, <= 0 satisfied", "-"),
    "holds": ("`g <= 0`", ""),
    "method": ("`proven` (the requirement's own argument over the whole task, `certificate`; for `lci`, "
               "`singular`, `speed` and `force`: the proven lower bound of the minimum, `bound`, meets the "
               "requirement; for `joints` and `stroke`: the margin from the proven outer ranges of the actuator "
               "coordinates is >= 0) or `refined-sampled` (the minimum located on the samples and refined by zooming: "
               "an estimate, not a bound)", ""),
    "certificate": ("the requirement's argument, in words (empty for a sampled one)", ""),
    "describe": ("the requirement in words, with its values", ""),
    "bound": ("`lci`, `singular`, `speed`, `force`: the minimum bounded by interval branch-and-bound over the "
              "task (mechopt.analysis.bounds), keys below; `joints`, `stroke`: the margin bounded from the "
              "actuator coordinates' proven outer ranges (the same search for `min q_i` and `-max q_i`)", ""),
}
#: the keys of a requirement's `bound` (mechopt.workflows.certificate.proven_bounds)
CERTIFICATE_BOUND = {
    "quantity": ("`lci`, `type2` (the type-II function times the design's sign), `speed`, `force`, "
                 "`joint_ranges` (`joints`: the quantity is its margin, rad) or `strokes` (`stroke`: its margin, "
                 "`max_stroke` minus the longest stroke, unit)", ""),
    "lower_bound": ("proven lower bound of the quantity's minimum over the task (the quantity's floor, 0 or -1, "
                    "where a cell may be out of reach; -inf for `joints`, `stroke`)", "the quantity's unit"),
    "estimate": ("the sampled-and-zoomed minimum (the margin's value plus the required level)",
                 "the quantity's unit"),
    "gap": ("`estimate - lower_bound`", "the quantity's unit"),
    "upper": ("the smallest value the search met at a task point (an upper bound of the minimum)",
              "the quantity's unit"),
    "proven_margin": ("`lower_bound` minus the required level: >= 0 proves the requirement", "its `unit`"),
    "method": ("`interval branch-and-bound`", ""),
    "cells": ("cells evaluated", "-"),
    "smallest_cell": ("the smallest cell of the final cover (side of a square, length of a piece of path; 0 for "
                      "points)", "unit"),
    "largest_cell": ("the largest cell of the final cover", "unit"),
    "converged": ("the search reached its stopping gap (2e-3 relative; `joints`, `stroke`: each of the four "
                  "searches within 2e-3 rad or 2e-3 of the task's diameter) within its budget (30000 cells each)",
                  ""),
    "may_unreachable": ("some cell of the final cover may be out of reach (its bound is the floor)", ""),
    "ranges": ("`joints`, `stroke`: `[[lo1, hi1], [lo2, hi2]]`, proven outer ranges of the two actuator "
               "coordinates over the task (each contains the exact range; infinite where a cell may be out of "
               "reach or across a crank angle's branch cut)", "rad or unit"),
    "estimate_ranges": ("`joints`, `stroke`: the sampled-and-zoomed ranges (design.json's `joint_ranges_deg` "
                        "in rad, `strokes`)", "rad or unit"),
    "inner_ranges": ("`joints`, `stroke`: the extremes the search met at task points (inside the exact range)",
                     "rad or unit"),
}
#: `mechopt check --json`
CHECK_JSON = {
    "design": ("the design.json checked", ""),
    "mechanism": ("the mechanism's name", ""),
    "unit": ("the length unit", ""),
    "variables": ("the lengths checked (after `--lengths`), `mode`, `task_x`, `task_y`", "unit"),
    "requirements": ("per requirement, the keys of certificate.json's requirements above", ""),
    "sampling": ("the certification's sampling", ""),
    "box": ("with `--tolerance`: `tolerance` [unit], `evaluated` (mechanisms: the lengths' 2^n corners, the "
            "placement's 4 and 32 seeded points inside the box of lengths and placement), `min_margin` and "
            "`worst` (the lengths and placement where it is) per requirement, "
            "`holds` per requirement, `methods` per requirement (`proven`: over the whole box, by the interval "
            "bound over the task, every length of the box and every placement; reach proven when every cell is "
            "certainly reachable; else `sampled`: nothing is proven between the points), `method` (`proven` "
            "when every requirement is, else `sampled`), `proven` (per bounded requirement over the box: "
            "`lower_bound`, `proven_margin`, `cells`, `converged`, `may_unreachable`; for `joints` and `stroke` "
            "also `ranges`, the proven outer ranges of the actuator coordinates over the task and the whole box "
            "[rad or unit]: a slider machine built within the box needs strokes covering them)", ""),
    "certificate": ("with a certificate.json beside the design: `index` (the certified design with this "
                    "design.json's digest, null if none: edited or another run's), `chosen`, and `disagrees`: "
                    "for a recorded design, each requirement whose claimed margin or verdict the re-check does "
                    "not find (a tampered or stale certificate: it fails the check)", ""),
    "holds": ("every requirement holds (and within the box)", ""),
    "fails": ("the requirements that fail, and `certificate.json: ...` for each claim it disagrees with", ""),
    "file": ("`mechopt check certificate.json`: the certificate re-verified (its report has `file`, "
             "`designs`, `holds`, `fails`)", ""),
    "designs": ("`mechopt check certificate.json`: per recorded design `index`, `mechanism`, `requirements` "
                "(the re-check's, keys as above), `fails` (what does not hold, and each claim not found again: "
                "margin, verdict, `proven`) and with a tolerance box `box` (re-checked over the same box, its "
                "corners and interval bounds)", ""),
}
DESIGN_VALUES = ("type2_min", "lci_min", "lci_mean", "size", "footprint", "speed", "force", "torque", "error_um",
                 "peak_torque", "rms_torque")
#: `mechopt motion`: motion.csv's columns, motion.json's and bodies.json's keys
MOTION_CSV = {
    "t": ("time from the start of the cycle", "s"),
    "x": ("platform point x (task frame)", "m"),
    "y": ("platform point y (task frame)", "m"),
    "q_1, q_2": ("actuator positions (crank angles; slider or strut positions)", "rad or m"),
    "qd_1, qd_2": ("actuator rates", "rad/s or m/s"),
    "qdd_1, qdd_2": ("actuator accelerations", "rad/s^2 or m/s^2"),
    "tau_1, tau_2": ("actuator efforts (torque of a crank, force of a slider or strut), positive along +q",
                     "N m or N"),
    "power_1, power_2": ("mechanical power of each actuator, tau_i qd_i", "W"),
}
MOTION_JSON = {
    "q_min, q_max": ("range of each actuator's position over the motion (two values each)", "rad or m"),
    "qd_peak, qdd_peak": ("largest |rate|, |acceleration| of each actuator", "rad/s, rad/s^2 or m/s, m/s^2"),
    "tau_peak": ("largest |effort| of each actuator", "N m or N"),
    "tau_rms": ("root mean square effort of each actuator over the cycle (trapezoidal rule in time)", "N m or N"),
    "power_peak": ("largest |power| of each actuator", "W"),
    "moving_mass": ("mass of the moving bodies (motors on the frame excluded)", "kg"),
    "cycle_time": ("duration of the motion", "s"),
    "mechanism, unit, path, profile, samples": ("the design's mechanism and length unit, the options", ""),
    "gravity": ("gravity in the plane (gx, gy)", "m/s^2"),
    "mass_source": ("`law`, `wu2008-table2` (the gantry's default), `+user` with --masses bodies", ""),
    "limits": ("`max_speed`, `max_torque`, `rms_limit`: the limits given (null: none)", "rad/s or m/s; N m or N"),
    "within_limits": ("every peak rate, peak effort and RMS effort within the limits given", ""),
}
BODIES_JSON = {
    "source, gravity_m_s2, actuator_inertia, moving_mass_kg": (
        "the model: where the masses come from, its gravity, the rotors' reflected inertia I_r N^2 per "
        "actuator, the moving mass", "-, m/s^2, kg m^2 or kg, kg"),
    "law": ("the mass law: `material`, `density_kg_m3`, `outer_m`, `wall_m` (square tube), `motor_kg`, "
            "`payload_kg`, `carriage_kg`, `rotor_inertia_kg_m2`, `gear_ratio` (null for Wu's Table 2)", ""),
    "bodies": ("one object per body: `name`, `kind` (link, cylinder, rod, carriage, motor, payload, "
               "counterweight), `mass_kg`, `com_m` (centre of mass in the body frame: origin at its first "
               "joint, x along the body), `com_along` (the same as a fraction of `length_m`), "
               "`inertia_com_kg_m2` (about the centre of mass, normal to the plane), `length_m`, `joints` "
               "(the joints it connects)", "kg, m, kg m^2"),
}
DESIGN_TOLERANCE = ("boundary_gap", "interior_step", "reach", "minima", "points", "path_gap")
DESIGN_RUN = {
    "design": ("the sizing problem: `mechanism`, `task` (`kind`, `unit`, `label`, and `vertices`, "
               "`center`/`radius` or `points`), `requirements` (angles in rad), `objectives`, `mode`, "
               "`place`, `min_length`, `max_length`, `shape`, `unit`, `side` (`above`; `below` for the "
               "mirrored search below the base line); the same under `settings`", ""),
    "polished": ("objectives whose best design the local polish improved", ""),
    "dropped_by_certification": ("front designs that failed the fine certification", "-"),
    "tolerance": ("with `--tolerance`: the tolerance T of every length", "unit"),
    "dropped_by_tolerance": ("with `--tolerance`: certified designs dropped because they do not hold over "
                             "their +-T box", "-"),
    "front_size": ("rows of `front.csv`", "-"),
    "other_designs": ("with a free placement searched on both sides of the base line (a five-bar of one "
                      "mode) or `--place free`: the certified designs of the other searches (below the line; "
                      "free-y) merged into this front's candidates", "-"),
    "certification": ("the fine sampling: `n_boundary`, `n_interior`, `refine`", ""),
    "chosen": ("`index` (row of `front.csv`) and `by` (`knee` or the `--pick` weights) of design.json",
               ""),
    "stage_times_s": ("wall time of each stage of the command: `other searches` (with --place free-y below "
                      "the base line, with --place free the free-y search; only then), `optimisation`, `polish`, "
                      "`certification`, `files` (figures drawn, certificate.json computed); `wall_time_s` is their sum", "s"),
    "no_design": ("without a feasible design: the message (the requirement missed most, by how much in its "
                  "unit); the folder then holds run.json, history.csv, population.csv (the final population, "
                  "least violating first, with its g_* columns) and front.png", ""),
    "violations": ("without a feasible design: the least-violating design's normalised violation per "
                   "requirement", ""),
    "fails": ("without a feasible design: how many designs of the final population fail each requirement",
              "-"),
    "sensitivity": ("without a feasible design: the missed requirement's margin at the least-violating design "
                    "after each change measured (`longer links`, `shorter links`: lengths x 1.1, x 0.9; `task "
                    "moved up/down/left/right`: by 10 % of its size; `faster actuators`, `stronger actuators`: "
                    "+10 %); larger helps", "the requirement's unit"),
}
DESIGN_SETTINGS = ("mechanism", "task", "requirements", "objectives", "mode", "place", "min_length",
                   "max_length", "shape", "unit", "side", "kind", "label", "vertices", "center", "radius", "points",
                   "n_boundary", "n_interior", "refine", "settle", "sampling", "by", "optimisation", "polish", "certification", "files")
EXPORT_FILES = {
    "robot.urdf": ("`urdf`: the mechanism as a tree (URDF, lengths in m), cut open at the platform joint; the "
                   "closure frames `closedloop1_A` (leg 1, the platform point) and `closedloop1_B` (leg 2) are "
                   "massless links on fixed joints; in Pinocchio close the loop with a `RigidConstraintModel` "
                   "(`CONTACT_3D`) between them; each body's inertial (mass, centre of mass, inertia) from the "
                   "mechanism's default mass model, as `mechopt motion` uses (`masses` in export.json)"),
    "robot.yaml": ("`urdf`: `closed_loop`, `type` and `name_mot` (the motors) in the format of Gepetto's "
                   "example-parallel-robots"),
    "robot.xml": ("`mjcf`: MuJoCo, the loop closed by `<equality><connect site1=\"closedloop1_A\" "
                  "site2=\"closedloop1_B\">`, position servos named as the motors, the design's ranges "
                  "(`range`, `ctrlrange`), `framepos` sensors of both closure frames, the keyframe `home` at "
                  "the task's centre"),
    "link-<body>.dxf": ("`dxf`: one per rigid link (a body with two pins, the base when it carries two): "
                        "hole circles (layer `HOLES`) at the pins, their centre distance the link length; "
                        "the capsule outline (layer `OUTLINE`); in the design's unit (`$INSUNITS`); "
                        "header property `MECHOPT_DESIGN_SHA256`"),
    "mechanism.svg": "`svg`: the mechanism at the task's centre, the task and the path",
    "path.csv": ("`csv`: one row per path sample (columns below); first line "
                 "`# mechopt design sha256 <digest>`"),
    "path.gif": ("`gif`: the mechanism following the path, one frame per k-th sample, "
                 "`k = ceil(samples / 60)`, 20 frames/s; the GIF comment holds the digest"),
    "export.json": "always: what was exported (keys below)",
    "manifest.json": "the output folder's manifest, as for every command",
}
EXPORT_CSV = {
    "t": ("arc-length fraction of the sample along the path, in [0, 1) (a region: its boundary at uniform "
          "arc length from its first vertex, counter-clockwise; a point task: its points in order)", "-"),
    "q1": ("the actuated joint of leg 1 (`theta1` or `q1`) from the inverse kinematics", "rad or unit"),
    "q2": ("the actuated joint of leg 2", "rad or unit"),
    "x": ("the platform point, task frame", "unit"),
    "y": ("the platform point, task frame", "unit"),
}
EXPORT_JSON = {
    "design_sha256": ("sha256 of design.json's canonical JSON (sorted keys, separators `,` `:`, ASCII): "
                      "every exported file carries it", ""),
    "design": ("the design.json exported", ""),
    "mechanism": ("the mechanism's name", ""),
    "repr": ("the mechanism as Python", ""),
    "formats": ("the formats written", ""),
    "unit": ("the design's length unit (DXF, SVG, CSV, GIF)", ""),
    "simulator_unit": ("`m`: the URDF's and MJCF's length unit", ""),
    "samples": ("path samples (`--samples`, or the points of a point task)", "-"),
    "actuated_joints": ("the motors' joint names, leg 1 first", ""),
    "closure_frames": ("`closedloop1_A`, `closedloop1_B`", ""),
    "link_width": ("width of the links (DXF capsules, the simulators' geoms): 0.1 x the longest pin "
                   "distance", "unit"),
    "home": ("`x`, `y`: the task's centre, where the SVG and the MJCF keyframe put the platform", "unit"),
    "inertia": ("where the URDF's and MJCF's masses come from (a sentence)", ""),
    "masses": ("with `urdf` or `mjcf`: one entry per body of the tree, `body` (its name), `mass_kg`, "
               "`com_m` (x, y, 0 in the body's frame [m]), `inertia_kg_m2` (Ixx, Iyy, Izz about the centre of "
               "mass): the mass model's bodies riding on it (mechopt.export.inertia.body_masses); a body "
               "without mass gets 1e-6 kg", ""),
    "masses_omitted": ("with `urdf` or `mjcf`: the mass model's bodies riding on no body of the tree "
                       "(counterweights on a cable): not in the simulators' files", ""),
    "frames": ("with `gif`: frames of `path.gif`", "-"),
    "frame_step": ("with `gif`: the sample step k between frames", "-"),
    "files": ("`{file name: sha256}` of the exported files", ""),
    "wall_time_s": ("time the export took", "s"),
}
ATLAS_CSV = {
    "r1": ("crank length", "L"),
    "r2": ("distal link length", "L"),
    "r3": ("half the base distance", "L"),
    "s": ("page coordinate `(r1 - r2) / sqrt(2)` (isometric map of `r1 + r2 + r3 = 3`)", "L"),
    "t": ("page coordinate `sqrt(3/2) r3`", "L"),
    **{k: EVAL_DISK[k] for k in ("r_mic", "mic_center_y", "gci", "mci", "gvi_max", "gvi_min", "gpi_max",
                                 "gpi_min", "gsi_max", "gsi_min")},
}
ATLAS_JSON = {
    "mechanism": ("`five-bar`", ""),
    "step": ("lattice step", "L"),
    "indices": ("index groups computed (`--index`)", ""),
    "columns": ("columns of `atlas.csv`", ""),
    "quadrature": ("rule of the disk means", ""),
    "mode": ("working mode", ""),
    "n_designs": ("rows of `atlas.csv`", "-"),
    "n_degenerate": ("designs without a MIC (`r_mic = 0`, NaN indices)", "-"),
    "plane": ("the map of the pictures, `s` and `t`", ""),
    "backend": ("`joblib n_jobs=N` or `dask ADDRESS`", ""),
    "compiled": ("true when the numba kernels ran", ""),
    "kernel": ("`numba` or `numpy`", ""),
    "where": ("the `--where` condition, or null", ""),
    "n_region": ("designs that satisfy it (rows of `region.csv`), or null", "-"),
    "seconds": ("`compute`, `figures` and `total` wall-clock times", "s"),
    "files": ("files written, in order", ""),
}
ATLAS_SUBKEYS = ("compute", "figures", "total")
TABLE_CSV = {
    "quantity": ("name of the reproduced quantity", ""),
    "source": ("where the paper prints it (section, table, figure, equation)", ""),
    "paper": ("the printed value (empty when the paper prints none)", "of `unit`"),
    "reproduced": ("our value", "of `unit`"),
    "unit": ("the printed unit (`L` for the non-dimensional lengths, `-` for none)", ""),
    "rel_error": ("`(reproduced - paper) / |paper|`", "-"),
    "status": ("one of the statuses below", ""),
    "kind": ("one of the kinds below", ""),
    "note": ("tolerance, reading and reason of a difference, evidence of a claim", ""),
    "design": ("Liu 2006 only: the design `r1/r2/r3` of the row", ""),
    "quadrature": ("Liu 2006 only: the rule of the disk means of the row (`polar`, `area`, or empty)", ""),
}
STATUS = {
    "match": "within the row's tolerance (stated in the note)",
    "differs": "outside it; the note says why",
    "not-reported": "the paper prints no value",
    "holds": "a claim of the paper that the computation confirms",
    "fails": "a claim that the computation contradicts",
}
KIND = {
    "computed": "a quantity the paper computed and we recompute: the only rows counted as match/differs",
    "setting": "an input or setting we echo",
    "reading": "a value under another reading of the paper or another quadrature, beside the literal row",
    "claim": "a checkable sentence of the paper (holds/fails)",
}


# --------------------------------------------------------------------------- helpers
class MissingGlossary(SystemExit):
    pass


def _cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _table(header, rows) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + " --- |" * len(header)]
    lines += ["| " + " | ".join(_cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def _codes(names) -> str:
    return ", ".join(f"`{n}`" for n in names)


def _lookup(glossary, name, where):
    if name not in glossary:
        raise MissingGlossary(f"docs/gen_outputs.py: no glossary entry for {name!r} ({where}); add one")
    return glossary[name]


def _unit(u) -> str:
    return u if u else ""


# --------------------------------------------------------------------------- sections
def _conventions() -> str:
    return """# Output reference

Every file, CSV column and JSON key that a `mechopt` command writes, with its
meaning and unit. The page is generated by `python docs/gen_outputs.py` from the
code (the names) and the glossaries of that script (meanings and units);
`tests/test_docs.py` runs the commands and fails if they write a file, a column
or a key that is not on this page, or if the page is not current.

Units: `L` is the unit of the lengths given (for the non-dimensional problems of
Liu 2006 and Le 2013, the unit the ratios are counted in: `r1 + r2 + r3 = 3`,
resp. the crank `l1 = 1`); `L^2` that unit squared; `unit` the length unit of
`mechopt design --unit` (default mm); `length_unit` the gantry's `--length-unit`
(default mm); `deg` degrees, `rad` radians, `s` seconds, `N` newton; `-` a
dimensionless number; an empty unit a name, a flag or a text. Angles are in
degrees wherever the name ends in `_deg`, in radians otherwise. In the JSON
files a non-finite number is `null`; in the CSV files an empty cell.

Every command that writes a folder holds it with a lock file `.mechopt.lock`
(the owner's pid) while it runs and writes each file atomically (a temporary
name, then a rename).
"""


def _evaluate() -> str:
    from mechopt.analysis.evaluate import DISK_KEYS, DISK_OPTIONS
    from mechopt.mechanisms import registry

    out = ["## `mechopt evaluate MECHANISM`\n",
           "Prints one design's numbers; with `--json` one JSON object (standard JSON: NaN and "
           "infinity as `null`) with the keys below, in this order. It writes no file. Common keys:\n",
           _table(["key", "meaning", "unit"], [
               ("`mechanism`", "the mechanism as Python (`FiveBar(r1=0.85, ...)`)", ""),
               ("`inputs`", "the declared parameters as used (defaults filled in) and, for the "
                            "five-bar, the evaluation options `quadrature` and `gamma`", "as declared"),
           ])]
    for name, cls in registry().items():
        if name not in EVAL_EXAMPLES:
            raise MissingGlossary(f"docs/gen_outputs.py: add an example design of {name!r} to EVAL_EXAMPLES")
        ex = EVAL_EXAMPLES[name]
        values = {p.name: ex.get(p.name, None if p.required else p.default) for p in cls.parameters}
        mech = cls.from_parameters(**values)
        options = DISK_OPTIONS if cls.disk_indices else ()
        args = " ".join(f"{p.option} {ex[p.name]:g}" for p in cls.parameters if p.name in ex)
        out.append(f"### `mechopt evaluate {name}`\n")
        out.append(f"{cls.cli_help[:1].upper()}{cls.cli_help[1:]} (`{cls.__module__}.{cls.__name__}`), e.g. "
                   f"`mechopt evaluate {name} {args} --json`.".replace("  ", " ") + "\n")
        rows = []
        for p in cls.parameters + options:
            default = "required" if p.required else ("q1 value" if p.default is None else f"`{p.default}`")
            unit = {"L": "L", "-": "-" if p.kind == "fraction" else "", "length unit": "length_unit"}.get(
                p.unit, p.unit)
            rows.append((f"`{p.name}`", p.help, unit, default))
        out.append("`inputs`:\n")
        out.append(_table(["key", "meaning", "unit", "default"], rows))
        keys = (DISK_KEYS if cls.disk_indices else ()) + tuple(k for k in mech.summary()
                                                               if not (cls.disk_indices and k in DISK_KEYS))
        gloss = {**(EVAL_DISK if cls.disk_indices else {}), **EVAL_SUMMARY.get(name, {})}
        rows = []
        for k in keys:
            meaning, unit = _lookup(gloss, k, f"mechopt evaluate {name}")
            rows.append((f"`{k}`", meaning, _unit(unit)))
        out.append("Values:\n")
        out.append(_table(["key", "meaning", "unit"], rows))
    out.append(_evaluate_errors())
    return "\n".join(out)


#: mechopt evaluate --error-model FILE --at X,Y (mechopt.analysis.accuracy.POSE_KEYS)
EVAL_ERRORS = {
    "error_at": ("the poses `[[x, y], ...]` of `--at`, in the mechanism's frame", "L"),
    "error_bound_um": ("proven worst-case position error at each pose under the error model (first order over "
                       "the tolerance box plus a proven second-order remainder; null where not proven)", "um"),
    "error_linear_um": ("its first-order part at each pose (the linear map's worst case, an upper bound)", "um"),
    "error_remainder_um": ("its second-order remainder at each pose (error_bound_um - error_linear_um)", "um"),
    "error_x_um": ("first-order worst error along x at each pose", "um"),
    "error_y_um": ("first-order worst error along y at each pose", "um"),
}


def _evaluate_errors() -> str:
    from mechopt.analysis.accuracy import POSE_KEYS
    from mechopt.mechanisms import registry

    names = ", ".join(f"`{n}`" for n, cls in registry().items() if cls.error_spec is not None)
    rows = [(f"`{k}`", *_lookup(EVAL_ERRORS, k, "mechopt evaluate --error-model")) for k in POSE_KEYS]
    return "\n".join([
        "### `mechopt evaluate MECHANISM --error-model FILE --at X,Y`\n",
        f"For a mechanism with an error model ({names}), `--error-model` (a JSON or TOML file or "
        "`key=value` pairs, the keys of the error model file under `mechopt accuracy`) with one or more "
        "`--at X,Y` poses [L] adds these keys after the values, one list entry per pose; `inputs` then also "
        "echoes `error_model` (the model, every key) and `unit` (`--unit`, the unit of the lengths: mm, "
        "cm, m or in; default mm):\n",
        _table(["key", "meaning", "unit"], [(k, m, _unit(u)) for k, m, u in rows])])


def _family(problem) -> str:
    return type(problem).__module__.rsplit(".", 1)[-1]


def _problem_columns():
    """``[(name, problem, front columns)]`` of every registered problem."""
    import numpy as np

    from mechopt.problems import get, names

    rows = []
    for n in names():
        p = get(n)
        x = (np.asarray(p.xl, float) + np.asarray(p.xu, float)) / 2.0
        rows.append((n, p, list(p.describe(x[None, :]))))
    return rows


def _problem_glossary(fam, problem):
    """name -> (meaning, unit) of every front.csv column of ``problem``."""
    gloss = dict(PROBLEM_COLUMNS.get(fam, {}))
    for v in problem.var_names:
        if fam == "design" and v.startswith("ln_"):  # the search variables of the lengths
            gloss[v] = (f"search variable `ln({v[3:]} + min_length)` of the length `{v[3:]}`", "ln(unit)")
    for ob in problem.objectives:
        meaning, unit = gloss.get(ob.name, (None, None))
        sense = "maximised" if ob.sense < 0 else "minimised"
        gloss[ob.name] = (f"objective, {sense}" + (f": {meaning}" if meaning else ""), ob.unit or unit)
    for c in problem.constr_names:
        gloss[f"g_{c}"] = (_constraint_meaning(fam, c), "-")
    return gloss


def _constraint_meaning(fam, c) -> str:
    if c in CONSTRAINTS.get(fam, {}):
        return "constraint: " + CONSTRAINTS[fam][c]
    if fam == "liu2006":
        from mechopt.problems.liu2006 import REGIONS

        for reg in REGIONS.values():
            for q, op, t in reg:
                if f"{q}{'_min' if op == '>' else '_max'}" == c:
                    form = f"({t:g} - {q}) / {t:g}" if op == ">" else f"({q} - {t:g}) / {t:g}"
                    return f"constraint `{q} {op} {t:g}` (Liu 2006 sec. 3.1), relative: {form}"
    if fam == "design":
        from mechopt import requirements as _req

        texts = {r.name: r.margin_text for r in _req.requirements()}
        if c in texts:
            return f"constraint, normalised: {texts[c]}"
    raise MissingGlossary(f"docs/gen_outputs.py: no meaning for constraint {c!r} of family {fam!r}")


def _optimize(problems) -> str:
    out = ["## `mechopt optimize PROBLEM`\n",
           "Runs a registered problem (`mechopt problems` lists them) with a seeded pymoo algorithm and "
           "writes into `--out`:\n",
           _table(["file", "content"], [
               ("`front.csv`", "one row per non-dominated feasible design of the final population: the "
                               "variables, the objectives with their natural sign (a maximised quantity "
                               "is positive), the constraint values `g_<name>` (`G <= 0` feasible, "
                               "normalised by a scale of their quantity) and the derived indices; with "
                               "no feasible design only the header"),
               ("`history.csv`", "one row per generation (columns below)"),
               ("`run.json`", "the run: problem, settings, algorithm, termination, seed, processes, "
                              "versions, times, counts (keys below)"),
               ("`front.png`", "the front (a convergence curve for one objective; with no feasible "
                               "design the population coloured by violation)"),
               ("`manifest.json`", "the run's record (keys below), rewritten last with `\"status\": "
                                   "\"complete\"`"),
               ("`checkpoint.pkl`", "with `--checkpoint-every K`: the algorithm state every K generations "
                                    "(`mechopt optimize --resume DIR`); removed when the run completes"),
           ])]
    out.append("### Columns of `front.csv` and `history.csv`, per problem\n")
    out.append("`history.csv` has `generation`, `evaluations`, `n_front`, one `best_<objective>` per "
               "objective and, with two or more objectives, `hypervolume`:\n")
    out.append(_table(["column", "meaning", "unit"], [(f"`{k}`", m, u) for k, (m, u) in HISTORY.items()]))
    by_family = {}
    for n, p, cols in problems:
        by_family.setdefault(_family(p), []).append((n, p, cols))
    for fam, items in by_family.items():
        out.append(f"#### {fam} problems ({FAMILY_UNIT.get(fam, '')})\n")
        rows = []
        gloss = {}
        for n, p, cols in items:
            g = _problem_glossary(fam, p)
            for c in cols:
                gloss.setdefault(c, _lookup(g, c, f"front.csv of {n}"))
            best = [f"best_{ob.name}" for ob in p.objectives] + (["hypervolume"] if p.n_obj >= 2 else [])
            rows.append((f"`{n}`", p.summary, _codes(cols), _codes(best)))
        out.append(_table(["problem", "summary", "front.csv columns", "history.csv: best and hypervolume"],
                          rows))
        out.append(_table(["column", "meaning", "unit"],
                          [(f"`{k}`", m, _unit(u)) for k, (m, u) in gloss.items()]))
    out.append("### `run.json`\n")
    out.append(_table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in RUN_JSON.items()]))
    out.append("### `manifest.json`\n")
    out.append("Written by `optimize`, `sweep`, `atlas` and `design` when the run starts (`\"status\": \"running\"`) "
               "and rewritten last:\n")
    out.append(_table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in MANIFEST.items()]))
    return "\n".join(out)


def _sweep(problems) -> str:
    out = ["## `mechopt sweep PROBLEM`\n",
           "Weighted-sum optima of a two-objective problem, one GA run per weight, after an NSGA-II "
           "run of the same seed whose front scales the objectives. It writes `sweep.csv`, `sweep.png` "
           "(the front and the optima), `run.json` (the keys of `optimize` for the NSGA-II run, and "
           "`sweep`), `front.csv` and `history.csv` (of the NSGA-II run) and `manifest.json`.\n",
           "`sweep.csv` has one row per weight: `weight`, then the columns of the GA run's "
           "`front.csv` (the problem's variables, `z`, the `g_<name>` constraint columns and the "
           "derived columns, which include both objectives by name), then `feasible` and `violation`:\n",
           _table(["column", "meaning", "unit"], [
               ("`weight`", "the weight `w` in [0, 1] of the problem's FIRST objective (the table "
                            "below names it); `1 - w` weighs the second", "-"),
               ("`z`", "the weighted sum at the optimum, minimised: `Z = w f1/s1 + (1 - w) f2/s2` "
                       "with `f` in pymoo's minimisation form (`f = -value` for a maximised objective) "
                       "and `s` the span of each objective over the NSGA-II front; Stan 2008 uses its "
                       "own `Z = W1 T + W2 W_n` with `W2 = w`, `W1 = 1 - w`, negated (`z = -Z`)", "-"),
               ("`feasible`", "true when the weight's GA run found a feasible design; false: the row "
                              "holds its least-violating design and empty objectives", ""),
               ("`violation`", "total violation `sum max(0, g)` of the row's design (0 when feasible)",
                "-"),
           ]),
           "`run.json` carries the sweep's totals under `\"sweep\"`:\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in SWEEP_JSON.items()]),
           "The problems with two objectives, and what the weight weighs:\n"]
    rows = []
    for n, p, _ in problems:
        if p.n_obj != 2:
            continue
        own = "Stan's `Z = W1 T + W2 W_n`" if hasattr(p, "weighted_sum") else "normalised weighted sum"
        rows.append((f"`{n}`", f"`{p.objectives[0].name}`", f"`{p.objectives[1].name}`", own))
    out.append(_table(["problem", "`weight` weighs", "`1 - weight` weighs", "scalarisation"], rows))
    return "\n".join(out)


def _design() -> str:
    from mechopt import mechanisms as _mechanisms
    from mechopt import requirements as _req

    requirements = {r.name: r for r in _req.requirements()}
    names = []
    rows = []
    for m in _mechanisms.designed():
        spec = _mechanisms.design_spec(m)
        for r in requirements.values():
            if r.applies(spec) and r.name not in names:
                names.append(r.name)
        if spec.angular:
            derived = [f"theta{i}_{e}_deg" for i in (1, 2) for e in ("min", "max")]
        else:
            derived = [f"q{i}_{e}" for i in (1, 2) for e in ("min", "max")] + ["stroke"]
        if spec.link_angles is not None:
            derived += [f"link{i}_angle_{e}_deg" for i in (1, 2) for e in ("min", "max")]
        rows.append((f"`{m}`", _codes(spec.lengths), _codes(spec.modes), _codes(derived)))
    out = ["## `mechopt design MECHANISM`\n",
           "Sizes a mechanism for a task region. It writes into `--out`, all at once when the run "
           "succeeds: `front.csv`, `design.json`, `certificate.json`, `run.json`, `history.csv` (as for "
           "`optimize`), "
           "`front.png` and `design.png` (the chosen mechanism at the task's centre with the task, its "
           "good-conditioning workspace, the type-II locus, the reachable boundary and the crank "
           "ranges; with a collision option (`--min-clearance`, `--link-width`, `--carriage-length`, "
           "`--min-joint-angle`, `--keep-out`, `--min-base`, `--motor-diameter` or the `clearance` "
           "objective) also its bodies as capsules with their widths, the keep-out zone hatched and "
           "the worst-clearance pose dashed, its clearance in the legend). Lengths are in `--unit` "
           "(`unit` below).\n",
           "`mechopt design any` (every mechanism, or `--mechanisms`) writes `front.csv` (the merged front: "
           "a `mechanism` column first, then the columns below of each row's mechanism, empty where that "
           "mechanism has none), `fronts.csv` (every mechanism's certified front, same columns), "
           "`design.json` (the chosen design, its `mechanism_name`), `certificate.json` (every "
           "mechanism's certificate in one `designs` list, each entry with its `mechanism`; `settings` per "
           "mechanism; `chosen` indexes design.json's design: `mechopt check` re-checks it), "
           "`run.json` (`mechanisms`, `skipped` "
           "with each reason, `objectives`, `front_size`, `per_mechanism` with each run's run.json, "
           "`chosen`, `wall_time_s`), `front.png` (the fronts coloured by mechanism) and `design.png`.\n",
           "### `front.csv`\n",
           "One row per certified Pareto design: the mechanism's lengths, `D` (with `--shape`), "
           "`mode`, `task_x`, `task_y`, one column per objective, `margin_<requirement>` per "
           "requirement, the derived ranges, `size` and `lci_min`:\n",
           _table(["mechanism", "lengths [unit]", "modes", "derived columns"], rows),
           _table(["column", "meaning", "unit"], [
               ("`D`", "with `--shape R1,R2,R3`: the scale, lengths `D * R_i` (Liu 2006 eq. 20)", "unit"),
               ("`mode`", "working mode (five-bar `+-` ...; bipod `up`, `down`)", ""),
               ("`task_x`", "x of the task's reference point (its centre) in the base frame", "unit"),
               ("`task_y`", "y of the task's reference point", "unit"),
               ("`theta1_min_deg`, `theta1_max_deg`, `theta2_min_deg`, `theta2_max_deg`",
                "mechanisms with cranks (five-bar, asymmetric five-bar): crank ranges over the task", "deg"),
               ("`q1_min`, `q1_max`, `q2_min`, `q2_max`", "sliders: actuator ranges over the task", "unit"),
               ("`stroke`", "sliders: the longest stroke", "unit"),
               ("`link1_angle_min_deg`, `link1_angle_max_deg`, `link2_angle_min_deg`, `link2_angle_max_deg`",
                "gantry, biglide with `--link-angle`: link angle ranges from the slider axis", "deg"),
               ("`size`", "sum of the link lengths", "unit"),
               ("`lci_min`", "minimum LCI over the task", "-"),
               ("`tolerance_max`", "with `--tolerance T`: the largest of T, 2T, 4T, 8T whose box the design "
                "holds over (certified as for T): a lower bound of the largest tolerance it survives", "unit"),
           ]),
           "Objectives (`--objectives`, each a column of its name):\n",
           _table(["objective", "sense", "meaning", "unit"],
                  [(f"`{k}`", "max" if ob.sense < 0 else "min", ob.description, ob.unit.format(L="unit", T="N m or N"))
                   for k, ob in _req.objectives().items()]),
           "Requirements: `margin_<name>` in `front.csv` and `margins` in `design.json` (natural units, "
           "> 0 satisfied), `g_<name>` of the search and `constraints_g` (normalised: lengths by the "
           "task diameter, angles by pi, LCI by its level, speed and force by their required values; "
           "<= 0 satisfied). The search's `g_<name>` (population.csv) of a requirement its "
           "samples show comfortably met is the samples' value, not refined (LCI, singular, joints, speed and force; "
           "front.csv and design.json hold the certification's refined values):\n",
           _table(["requirement", "margin", "unit of the margin"],
                  [(f"`{n}` (`margin_{n}`, `g_{n}`)", requirements[n].margin_text,
                    requirements[n].margin_unit.format(L="unit")) for n in names]),
           "### `design.json`\n",
           "The chosen design (the knee of the front, or `--pick`), certified:\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in DESIGN_JSON.items()]),
           f"Keys under `values`: {_codes(DESIGN_VALUES)}; under `tolerance`: {_codes(DESIGN_TOLERANCE)}.\n",
           "### `certificate.json`\n",
           "What every front design's numbers rest on (mechopt.workflows.certificate); `mechopt check` "
           "re-checks a design:\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in CERTIFICATE_JSON.items()]),
           "Keys of each design under `designs`:\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in CERTIFICATE_DESIGN.items()]),
           "Keys of each requirement under a design's `requirements`:\n",
           _table(["key", "meaning", "unit"],
                  [(f"`{k}`", m, _unit(u)) for k, (m, u) in CERTIFICATE_REQUIREMENT.items()]),
           "Keys of a requirement's `bound` (`lci`, `singular`, `speed`, `force`; the proven lower bound of "
           "the minimum the requirement rests on, interval branch-and-bound over the task: "
           "mechopt.analysis.bounds):\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in CERTIFICATE_BOUND.items()]),
           "### `run.json`\n",
           "The keys of `optimize`'s `run.json` (`problem` is `design`) and:\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in DESIGN_RUN.items()]),
           f"Keys inside `design`, `settings`, `certification` and `chosen`: {_codes(DESIGN_SETTINGS)} "
           "(`settle`: the search leaves unrefined the minima its samples show comfortably met).\n",
           "The registered problem `design` (`mechopt optimize design`, the five-bar example of "
           "`problems/design.py`) searches the lengths as `ln_<length> = ln(length + min_length)` "
           "(`ln_D` with a shape) and the placement as `task_x_rel`, `task_y_rel`; its `front.csv` is "
           "listed with the other problems above.\n"]
    return "\n".join(out)


def _check() -> str:
    out = ["## `mechopt check DESIGN.json`\n",
           "Re-evaluates the design of a `design.json` (lengths possibly rounded by hand, or replaced by "
           "`--lengths`) with the full evaluator and the certification's sampling against the task and "
           "requirements of the `run.json` beside it (or `--task`), and with `--tolerance T` every length "
           "within +-T. Prints one line per requirement (margin in its unit, holds or FAILS, proven or "
           "refined-sampled) and a last line (`all requirements hold` or `fails: ...`); exit status 0 when "
           "every requirement holds, 1 when one fails, 2 on bad input. Writes no file. With `--json`, one "
           "object:\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in CHECK_JSON.items()])]
    return "\n".join(out)


def _motion() -> str:
    def rows(d):
        return [(", ".join(f"`{k.strip()}`" for k in key.split(",")), m, _unit(u)) for key, (m, u) in d.items()]
    return "\n".join([
        "## `mechopt motion DESIGN_DIR`\n",
        "Runs the chosen design of a `mechopt design` folder along a timed motion (`--path`: the "
        "task's pick-and-place cycle, a segment or a CSV polyline; `--profile`, `--cycle-time`) with "
        "its mass model (`--masses`, default the stated 20 x 20 x 2 mm aluminium tube law; Wu 2008 "
        "Table 2 for the gantry) and writes into `--out` (default the design's folder) `motion.csv`, "
        "`motion.json`, `bodies.json` and `motion.png` (effort and rate of each actuator over time "
        "with the limits given drawn). Actuator 1 is the leg of `q1` (the left crank of a five-bar).\n",
        "`motion.csv`:\n", _table(["column", "meaning", "unit"], rows(MOTION_CSV)),
        "`motion.json` (per-actuator values are lists of two):\n",
        _table(["key", "meaning", "unit"], rows(MOTION_JSON)),
        "`bodies.json`:\n", _table(["key", "meaning", "unit"], rows(BODIES_JSON)),
        "Keys inside `bodies`, `law` and `limits`: `name`, `kind`, `mass_kg`, `com_m`, `com_along`, "
        "`inertia_com_kg_m2`, `length_m`, `joints`, `material`, `density_kg_m3`, `outer_m`, `wall_m`, "
        "`motor_kg`, `payload_kg`, `carriage_kg`, `rotor_inertia_kg_m2`, `gear_ratio`, `max_speed`, "
        "`max_torque`, `rms_limit`.\n"])


def _export() -> str:
    from mechopt.export import FORMATS

    out = ["## `mechopt export DESIGN.json --to DIR`\n",
           "Exports the design of a `mechopt design` run (its `design.json`, with the `run.json` beside it "
           f"for the task) in the formats of `--format` ({_codes(FORMATS)}; default all), all at once, into "
           "`--to`. Naming: the actuated joints carry the mechanism's actuator names (`theta1`, `theta2` for "
           "cranks; `q1`, `q2` for sliders and struts), passive joints their role and leg (`elbow1`, "
           "`pivot1`, `base1`, ...), the closure frames are `closedloop1_A` (leg 1: the platform point) "
           "and `closedloop1_B` (leg 2). The tree of each mechanism is declared in its own module "
           "(`kinematic_tree()`, `mechopt.core.kinematic_tree`).\n",
           _table(["file", "content"], [(f"`{k}`", m) for k, m in EXPORT_FILES.items()]),
           "### `path.csv`\n",
           _table(["column", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in EXPORT_CSV.items()]),
           "### `export.json`\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in EXPORT_JSON.items()])]
    return "\n".join(out)


#: mechopt accuracy --json (mechopt.workflows.accuracy.ACCURACY_KEYS)
ACCURACY = {
    "mechanism": ("the design's mechanism (its repr)", ""),
    "unit": ("the task's length unit", ""),
    "poses": ("task samples evaluated (192 boundary points and the 13 x 13 grid kept inside)", "-"),
    "bound_um": ("proven worst-case position error: the largest bound over the samples", "um"),
    "task_max_um": ("the maximum of the bound over the task: the samples' maximum refined by zooming "
                    "(mechopt.analysis.sampling), what `--max-error` checks; >= bound_um", "um"),
    "linear_um": ("its first-order part at that sample (the linear map's worst case, an upper bound)", "um"),
    "remainder_um": ("its second-order remainder at that sample (bound_um - linear_um)", "um"),
    "worst_x_um": ("largest first-order worst error along x over the samples", "um"),
    "worst_y_um": ("largest first-order worst error along y over the samples", "um"),
    "at": ("the task point [x, y] of bound_um", "unit"),
    "mc_max_um": ("largest error of the Monte Carlo draws (exact perturbed forward kinematics)", "um"),
    "ratio": ("bound_um / mc_max_um (>= 1 when the bound holds)", "-"),
    "samples": ("Monte Carlo draws per task sample (--samples)", "-"),
    "draw": ("where the draws lie in the tolerance box: vertices or uniform (--draw)", ""),
    "seed": ("seed of the draws (--seed)", "-"),
    "unbounded_poses": ("samples without a proof (unreachable, or next to a type-II singularity)", "-"),
}
#: the keys of an error model file (mechopt.analysis.accuracy.ErrorModel)
ERROR_MODEL = {
    "encoder_counts": ("counts per revolution of each crank's encoder (0: exact); +/- pi/counts rad; one "
                       "number, or one per motor `[16384, 4096]` (`16384/4096` in key=value form; also "
                       "`mechopt design --encoder`)", "-"),
    "backlash_arcmin": ("lost motion of each crank's drive, full width (+/- half of it); one number or one per "
                        "motor", "arcmin"),
    "resolution_um": ("one count of each slider's or strut's scale (+/- half of it); one number or one per "
                      "motor", "um"),
    "backlash_um": ("lost motion of each slider's or strut's drive (+/- half of it); one number or one per "
                    "motor", "um"),
    "clearance_um": ("radial clearance of each passive joint (the pin's centre within it of the bore's)", "um"),
    "link_tol_um": ("tolerance on each link length, +/-", "um"),
    "base_tol_um": ("tolerance on each coordinate of each base joint or guide, +/-", "um"),
}


def _accuracy() -> str:
    from dataclasses import fields

    from mechopt.analysis.accuracy import ErrorModel
    from mechopt.workflows.accuracy import ACCURACY_KEYS

    rows = [(f"`{k}`", *_lookup(ACCURACY, k, "accuracy")) for k in ACCURACY_KEYS]
    model = [(f"`{f.name}`", *_lookup(ERROR_MODEL, f.name, "error model")) for f in fields(ErrorModel)]
    out = ["## `mechopt accuracy DESIGN_DIR`\n",
           "Reads a `mechopt design` folder (`design.json`, `run.json`) and an error model "
           "(`--error-model FILE`, JSON or TOML, the keys below, each 0 when left out), prints the proven "
           "worst-case position error over the design's task samples, the Monte Carlo maximum and their "
           "ratio, and writes the error map `error_map.png` into `DESIGN_DIR` (or `--figure PATH`): the "
           "bound over the task, colour bar in um. With `--json` it prints one JSON object:\n",
           _table(["key", "meaning", "unit"], [(k, m, _unit(u)) for k, m, u in rows]),
           "The error model file:\n",
           _table(["key", "meaning", "unit"], [(k, m, _unit(u)) for k, m, u in model])]
    return "\n".join(out)


def _atlas() -> str:
    from mechopt.run.atlas import DEFAULT_INDICES, design_grid, index_columns

    cols = list(design_grid(0.5).columns) + [c for c in index_columns(DEFAULT_INDICES)]
    rows = [(f"`{c}`", *_lookup(ATLAS_CSV, c, "atlas.csv")) for c in cols]
    pngs = [f"atlas_{c}.png" for c in index_columns(DEFAULT_INDICES) if c != "mic_center_y"]
    out = ["## `mechopt atlas five-bar`\n",
           "Evaluates every design of Liu 2006's space `r1 + r2 + r3 = 3`, `0 <= r3 <= 1.5` on a "
           "lattice (`--step`, non-dimensional). It writes `atlas.csv`, `region.csv` (with `--where`: "
           "the rows that satisfy it, same columns), `atlas.json`, `manifest.json` (as for `optimize`) "
           "and one figure per index column, " + _codes(pngs) + " (with `--index`, those of the chosen "
           "groups). While it runs, finished chunks are kept in `.atlas_chunks/` (a rerun resumes "
           "from them); the folder is removed when `atlas.csv` is complete.\n",
           "`atlas.csv` (a design without a MIC has `r_mic = 0` and empty indices; `--index` keeps "
           "`r1` to `mic_center_y` and the chosen groups):\n",
           _table(["column", "meaning", "unit"], rows),
           "`atlas.json`:\n",
           _table(["key", "meaning", "unit"], [(f"`{k}`", m, _unit(u)) for k, (m, u) in ATLAS_JSON.items()]),
           f"Keys under `seconds`: {_codes(ATLAS_SUBKEYS)}.\n"]
    return "\n".join(out)


def _reproduce() -> str:
    from mechopt.core.published import KINDS, STATUSES, TABLE_COLUMNS
    from mechopt.workflows.reproduce import PAPERS

    cols = list(TABLE_COLUMNS) + [c for c in TABLE_CSV if c not in TABLE_COLUMNS]
    for s in STATUSES:
        _lookup(STATUS, s, "status")
    for k in KINDS:
        _lookup(KIND, k, "kind")
    out = ["## `mechopt reproduce PAPER`\n",
           f"Reproduces {', '.join(f'`{p}`' for p in PAPERS)} (or `all`) into `--out` (default "
           "`results`), one folder per paper, and writes the summary `README.md` (the counts per paper "
           "and why each computed quantity differs) and `manifest.json` (kind `reproduce`: a folder holding a "
           "`README.md` or a paper folder that no reproduction wrote is refused, never written into). "
           "Per paper:\n",
           _table(["file", "content"], [
               ("`table.csv`", "one row per published number, claim or setting (columns below)"),
               ("`table.md`", "the same table in Markdown, under the paper's title"),
               ("`reproduce.json`", "how the folder was made: `quick` (true for `--quick`) and `mechopt` "
                                    "(the version); a finished paper is reused only by a run of the same "
                                    "kind"),
               ("`*.png`", "the redrawn figures (e.g. `le2013/fig5_a_max.png`)"),
               ("`*.csv`", "the paper's own curves and scans behind the figures (e.g. `le2013/curve.csv`, "
                           "`wu2008/k_av_vs_theta.csv`)"),
               ("run folders", "fronts and sweeps of the paper's problems (e.g. `le2013/front/`, "
                               "`le2013/sweep/`) with the files of `optimize` and `sweep` above"),
           ]),
           "`table.csv`:\n",
           _table(["column", "meaning", "unit"], [(f"`{c}`", *_lookup(TABLE_CSV, c, "table.csv")) for c in cols]),
           _table(["status", "meaning"], [(f"`{s}`", STATUS[s]) for s in STATUSES]),
           _table(["kind", "meaning"], [(f"`{k}`", KIND[k]) for k in KINDS]),
           "## `mechopt report [RESULTS_DIR]`\n",
           "Writes one self-contained HTML page, `RESULTS_DIR/report.html` (or `--out FILE`): the "
           "summary counts, each paper's `table.csv` (sortable, statuses coloured), every figure, "
           "front and sweep, all embedded (an image that another already shows, a sweep's copy of its "
           "front, is named, not repeated). It prints the path.\n",
           "## `mechopt explore DIR`\n",
           "Writes one self-contained, interactive HTML page of a run folder, `DIR/explore.html` (or "
           "`--out PAGE.html`), and prints its path; `--serve` then serves it on 127.0.0.1 and opens "
           "it in the browser. Plotly and the data are embedded (gzip, base64) and inflated by the "
           "browser: the page works offline. A design run (`front.csv`, `run.json`, `design.json`): the "
           "front on any two columns, parallel coordinates, the mechanism of any front design over its "
           "placed task (reachable boundary, type-II locus, the GCW when `--min-lci` was asked; with a "
           "collision option its capsules, keep-out zone and worst poses as in design.png) with "
           "its row, and a slider moving the platform along the task (72 boundary points at uniform "
           "arc length, or at most 200 task points). An optimisation run (`front.csv`, `history.csv`, "
           "`sweep.csv`): the front, the hypervolume per generation, the sweep. An atlas (`atlas.csv`): "
           "the design triangle coloured by any index, each `--where` condition as a region. Drawings "
           "and atlas values are rounded to 6 significant digits; it writes no other file.\n",
           "## `mechopt problems`\n",
           "Prints one line per registered problem (`name  summary`); it writes no file.\n"]
    return "\n".join(out)


def render() -> str:
    problems = _problem_columns()
    parts = [_conventions(), _evaluate(), _optimize(problems), _sweep(problems), _design(), _check(), _motion(),
             _export(),
             _accuracy(), _atlas(),
             _reproduce()]
    text = "\n".join(p.rstrip("\n") + "\n" for p in parts)
    while "\n\n\n" in text:
        text = text.replace("\n\n\n", "\n\n")
    return text


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="exit 1 if docs/outputs.md is not current")
    args = ap.parse_args(argv)
    text = render()
    if args.check:
        if not PAGE.exists() or PAGE.read_text() != text:
            print("docs/outputs.md is not current: run python docs/gen_outputs.py", file=sys.stderr)
            return 1
        return 0
    PAGE.write_text(text)
    print(f"wrote docs/outputs.md ({len(text.splitlines())} lines)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
