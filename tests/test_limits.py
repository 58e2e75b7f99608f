"""Internal limits: every admissible design evaluates, or says which input is the problem.

Lengths in [1e-12, 1e12] are admissible (``mechopt.core.validation``). ``evaluate`` works
in units of the design's size (a power of two, ``mechopt.analysis.evaluate.unit_of``), so:

* an ordinary design gives exactly the numbers it gave before that (the unit is 1,
  or a power of two, by which these computations scale exactly);
* a design of any size gives the numbers of the same shape at size 1, scaled as
  lengths (``D``), areas (``D^2``), ... (checked against the ordinary design's own
  numbers times ``D^p``: the powers are written out here, independently of
  ``evaluate.disk_powers``);
* where something cannot be evaluated (a workspace double precision cannot
  resolve, legs that never meet), the error is one line that names the design's
  inputs and the condition on them that fails, never an internal quantity.
"""
import json
import math
import re
import warnings

import pytest

from mechopt import Biglide, Bipod, FiveBar
from mechopt.cli import main
from mechopt.analysis.evaluate import _check_raster, disk_evaluation, evaluate, unit_of
from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar
from mechopt.analysis.performance import global_indices
from mechopt.analysis.workspace import gcw, largest_square, mic, usable_region

#: powers of the length of each number of the five-bar's evaluation (J ~ 1/L)
POWERS = {"r_mic": 1, "mic_center_y": 1, "gvi_max": 1, "gvi_min": 1, "gpi_max": -1, "gpi_min": -1,
          "gsi_max": 2, "gsi_min": 2, "usable_area": 2, "gcw_area": 2, "gcw_gsi_max": 2,
          "gcw_gsi_min": 2, "gcw_square_side": 1, "gcw_square_center_y": 1, "workspace_area": 2,
          "tqi_integral": 2}
#: words of internal quantities that a user never passed to ``mechopt evaluate``
INTERNAL = ("step", "center_y", "center", "radius", "box", "factor", "tol")

ORDINARY = [(0.85, 1.6, 0.55, "+-"), (0.7, 1.7, 0.6, "-+"), (1.6, 0.9, 0.5, "+-"),
            (1.2, 1.8, 0.0, "+-"), (1.0, 1.5, 0.5, "++")]


#: evaluations by (repr of the design, options): the size-1 designs that several cases
#: scale (each ordinary design against seven powers of two) are evaluated once
_EVALUATED = {}


def _values(mech, **kw):
    key = (repr(mech), tuple(sorted(kw.items())))
    if key not in _EVALUATED:
        _EVALUATED[key] = evaluate(mech, **kw).values
    return dict(_EVALUATED[key])


#: read off the raster by an argmax over rows that may tie: "accurate to about one cell"
#: (``workspace.largest_square``), so a rounding of the scaled grid may move them one cell
ONE_CELL = ("gcw_square_side", "gcw_square_center_y")


def _assert_scaled(small, big, D, rel, cell=0.0):
    """``big`` (the design times ``D``) equals ``small`` scaled by ``D**p`` (to ``rel``;
    the square's side and centre to one raster cell ``cell`` of the small design)."""
    assert small.keys() == big.keys()
    for k, a in small.items():
        b = big[k]
        if isinstance(a, float):
            want = a * D ** POWERS.get(k, 0)
            if math.isnan(want):
                assert math.isnan(b), k
            elif rel == 0:
                assert b == want, (k, a, b, want)
            else:
                tol = 1.000001 * cell * D if k in ONE_CELL else 0.0
                assert b == pytest.approx(want, rel=rel, abs=tol), k
        else:
            assert a == b or (isinstance(a, list) and b == pytest.approx(a, rel=1e-12)), k


# --- ordinary designs keep their numbers ------------------------------------------------------
def test_unit_is_one_for_designs_of_size_one_and_a_power_of_two_else():
    assert unit_of(FiveBar(0.85, 1.6, 0.55)) == 1.0
    assert unit_of(FiveBar(250.0, 400.0, 120.0)) == 256.0
    assert unit_of(FiveBar(1e-12, 1e-12, 0.0)) == 2.0 ** -39  # clamped: its inverse is admissible
    assert unit_of(FiveBar(1e12, 1e12, 1e12)) == 2.0 ** 39


@pytest.mark.parametrize("k", [-39, -20, -3, 1, 8, 20, 39])
@pytest.mark.parametrize("r1, r2, r3, mode", ORDINARY[:3])
def test_power_of_two_sizes_give_the_scaled_numbers_exactly(r1, r2, r3, mode, k):
    D = 2.0 ** k
    if min(v * D for v in (r1, r2)) < 1e-12:
        pytest.skip("not an admissible design")
    _assert_scaled(_values(FiveBar(r1, r2, r3, mode)), _values(FiveBar(r1 * D, r2 * D, r3 * D, mode)), D, 0)


def test_the_issue_design_prints_its_numbers(capsys):
    """``mechopt evaluate five-bar --r1 0.85 --r2 1.6 --r3 0.55 --json``: the numbers it
    printed before the unit was introduced (to the last printed digit on this kind of
    machine; 1e-12 leaves room for another libm)."""
    assert main(["evaluate", "five-bar", "--r1", "0.85", "--r2", "1.6", "--r3", "0.55", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    before = {"r_mic": 0.8499999999990515, "mic_center_y": 1.502497920132682, "gci": 0.7049118749358918,
              "mci": 0.9999999999999997, "gvi_max": 0.8942109866530565, "gvi_min": 0.7313564633712355,
              "gpi_max": 1.3883556963736812, "gpi_min": 1.1190177557278256, "gsi_max": 0.8001172749665512,
              "gsi_min": 0.5423541909527031, "usable_area": 5.129025, "gcw_area": 3.4882875,
              "gcw_gci": 0.7159404027143416, "gcw_gsi_max": 0.7564016543432908,
              "gcw_gsi_min": 0.400534790101815, "gcw_square_side": 1.1125, "gcw_square_center_y": 1.50875}
    for k, v in before.items():
        assert out[k] == pytest.approx(v, rel=1e-12, abs=0), k
    assert out["theta1_range_deg"] == pytest.approx([36.40739407206243, 276.2542627643123], rel=1e-12)
    assert out["theta2_range_deg"] == pytest.approx([-96.25426276431227, 143.59260592793757], rel=1e-12)


@pytest.mark.parametrize("make, D", [
    (lambda D: Bipod(60 * D, 80 * D, 130 * D), 2.0 ** -30),
    (lambda D: Biglide(1 * D, 1.1 * D, 0.0, 1 * D), 2.0 ** 35),
    (lambda D: AsymmetricFiveBar(1 * D, 1.5 * D, 0.8 * D, 1.7 * D, 0.5 * D), 2.0 ** -25),
])
def test_other_mechanisms_scale_exactly_too(make, D):
    _assert_scaled(_values(make(1.0)), _values(make(D)), D, 0)


# --- extreme admissible designs ---------------------------------------------------------------
@pytest.mark.parametrize("r, D", [
    ((1.0, 1.0, 1.0), 1e-12), ((1.0, 1.0, 1.0), 1e12), ((1.0, 1.0, 0.0), 1e12),
    ((1.0, 1.0, 0.0), 1e-12), ((0.85, 1.6, 0.55), 1e11), ((1.0, 1.6 / 0.85, 0.55 / 0.85), 1e-12),
    ((1.0, 1.0, 1e-12), 1e12),
])
def test_extreme_five_bars_are_the_ordinary_ones_scaled(r, D):
    """All 1e-12, all 1e12, (1e12, 1e12, 0), ...: the numbers of the design at size 1
    times ``D**p`` (to rounding: ``D`` is not a power of two)."""
    small = FiveBar(*r)
    _assert_scaled(_values(small), _values(FiveBar(*(v * D for v in r))), D, 1e-9,
                   cell=small.length_scale / 400)


@pytest.mark.parametrize("r, D", [((1.0, 1.0, 0.0), 1e12), ((1.0, 1.0, 1.0), 1e-12)])
def test_public_functions_work_at_extreme_sizes(r, D):
    """Not only ``evaluate``: MIC, global indices, usable region, GCW and square
    directly, in the design's own units (no internal range refuses them)."""
    small, big = FiveBar(*r), FiveBar(*(v * D for v in r))
    for method in ("explicit", "rays"):
        a, b = mic(small, method), mic(big, method)
        assert b.radius == pytest.approx(D * a.radius, rel=1e-6)
        assert b.center_y == pytest.approx(D * a.center_y, rel=1e-4, abs=1e-6 * D)
    ga, gb = global_indices(small), global_indices(big)
    assert gb["gci"] == pytest.approx(ga["gci"], rel=1e-9)
    assert gb["mci"] == pytest.approx(ga["mci"], rel=1e-9)
    assert gb["gsi_max"] == pytest.approx(D * D * ga["gsi_max"], rel=1e-9)
    ua, ub = usable_region(small), usable_region(big)
    assert ub.area == pytest.approx(D * D * ua.area, rel=1e-9)
    sa, sb = largest_square(gcw(small, 0.5, ua)), largest_square(gcw(big, 0.5, ub))
    assert sb[0] == pytest.approx(D * sa[0], rel=1e-9, abs=D * small.length_scale / 400)


@pytest.mark.parametrize("make, D", [
    (lambda D: Bipod(60 * D, 80 * D, 130 * D), 1e-13),
    (lambda D: Bipod(1 * D, 0.5 * D, 1 * D), 1e12),
    (lambda D: Biglide(1 * D, 1.1 * D, 0.0, 1 * D), 1e-12),
    (lambda D: Biglide(0.5 * D, 0.9 * D, -1 * D, 1 * D), 1e12),
    (lambda D: AsymmetricFiveBar(1 * D, 1.5 * D, 1 * D, 1.7 * D, 0.5 * D), 1e-12),
    (lambda D: AsymmetricFiveBar(0.8 * D, 1 * D, 0.7 * D, 1 * D, 0.5 * D), 1e12),
])
def test_extreme_designs_of_the_other_mechanisms(make, D):
    _assert_scaled(_values(make(1.0)), _values(make(D)), D, 1e-9)


# --- what cannot be evaluated says why, in the user's terms ----------------------------------
def _cli_error(capsys, *args):
    assert main(["evaluate", *args, "--json"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechopt: error: ") and err.count("\n") == 1
    return err


@pytest.mark.parametrize("r1, r2, r3, mode, needs", [
    ("1e-12", "1e12", "0", "+-", "min(r1, r2) must be at least"),
    ("1e12", "1e-12", "0", "+-", "min(r1, r2) must be at least"),
    ("1", "1e10", "0", "+-", "min(r1, r2) must be at least"),
    ("1", "1e6", "0", "+-", "min(r1, r2) must be at least about"),
    ("1e6", "1", "0.5", "+-", "min(r1, r2) must be at least about"),
    ("0.1", "0.1", "5", "+-", "r3 must be less than r1 + r2"),
    ("1e-12", "1e-12", "1e12", "+-", "r3 must be less than r1 + r2"),
    ("1", "1", "0", "++", "r3 > 1e-12 (r1 + r2 + r3)/3"),
])
def test_designs_that_cannot_be_evaluated_name_their_inputs(capsys, r1, r2, r3, mode, needs):
    err = _cli_error(capsys, "five-bar", "--r1", r1, "--r2", r2, "--r3", r3, f"--mode={mode}")
    assert needs in err
    assert "FiveBar(r1=" in err  # the design as given
    msg = err.split(": ", 2)[-1]
    assert not any(msg.startswith(w) for w in INTERNAL), err
    with pytest.raises(ValueError) as exc:  # the same from the Python API
        evaluate(FiveBar(float(r1), float(r2), float(r3), mode))
    assert needs in str(exc.value) and "\n" not in str(exc.value)


def test_a_step_giving_too_many_cells_says_which_step_works():
    fb = FiveBar(0.85, 1.6, 0.55)
    with pytest.raises(ValueError, match=r"step 0\.0001 gives a raster .* use a step of at least ([0-9.e-]+)") as exc:
        disk_evaluation(fb, step=1e-4)
    smallest = float(str(exc.value).rsplit(" ", 1)[-1])
    _check_raster(fb, smallest)  # the step it names works
    with pytest.raises(ValueError, match="use a step of at least"):
        _check_raster(fb, 0.99 * smallest)
    # in any unit: the same design in 1e-12 units
    tiny = fb.scaled(1e-12 / 0.55)
    with pytest.raises(ValueError, match="step 1e-17 gives a raster"):
        disk_evaluation(tiny, step=1e-17)
    assert disk_evaluation(tiny, step=tiny.length_scale / 50)["usable_area"] > 0


def test_bad_inputs_still_name_the_input(capsys):
    assert "r1 must lie in [1e-12, 1e+12]" in _cli_error(capsys, "five-bar", "--r1", "8.5e-13", "--r2", "1",
                                                        "--r3", "0")
    assert "r2 must lie" in _cli_error(capsys, "five-bar", "--r1", "1", "--r2", "2e12", "--r3", "0")


# --- limits of the other mechanisms, in the user's terms ------------------------------------
@pytest.mark.parametrize("args, too", [
    (["--b", "1e-12", "--h", "1e-12", "--d2", "1e-12", "--l2", "1e-12"], "below"),
    (["--b", "1e12", "--h", "1"], "above"),
    (["--b", "500", "--h", "1e12"], "above"),
    (["--b", "1e-12", "--h", "1", "--length-unit", "m"], "below"),
])
def test_gantry_synthesis_limits_name_the_users_inputs(capsys, args, too):
    """Wu's synthesis derives d1, l and the stroke from b, h, theta_1S: a task whose
    machine has a length out of [1e-12, 1e12] (in the dynamics' metres too) is refused
    in terms of b, h, theta_1S, with the range of b that works, and that range works."""
    err = _cli_error(capsys, "gantry", *args)
    assert not any(w in err for w in ("d1 must", "l must", "stroke must"))
    b = args[args.index("--b") + 1]
    assert f"b = {float(b):g}" in err and "theta_1S = 10 deg" in err and too in err
    lo, hi = (float(v) for v in re.search(r"b must lie in \[([^,]+), ([^\]]+)\]", err).groups())
    unit = args[args.index("--length-unit") + 1] if "--length-unit" in args else "mm"
    for ok in (1.01 * lo, 0.99 * hi):
        assert main(["evaluate", "gantry", "--b", repr(ok), "--h", "1", "--length-unit", unit,
                     "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["workspace_area"] > 0


def test_asymmetric_five_bar_whose_legs_never_meet(capsys):
    """Unit links 10 apart: the legs' reaches do not overlap, an empty workspace is a
    result (as the five-bar's empty GCW), not an error about a raster step."""
    assert main(["evaluate", "asymmetric-five-bar", "--a1", "1", "--c1", "1", "--a2", "1", "--c2", "1",
                 "--r3", "5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["workspace_area"] == 0.0 and out["mean_lci"] is None and out["mean_tqi"] is None


def test_biglide_empty_to_rounding_has_area_zero_not_negative(capsys):
    """Strokes [0, 1e-12] with l2 = 1.1: the closed form's terms are of size l2^2, its
    -2.2e-16 is round-off about a true 2e-25; the area is 0, the GTQI undefined (null)."""
    assert main(["evaluate", "biglide", "--l1", "1", "--l2", "1.1", "--q1-min", "0", "--q1-max", "1e-12",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["workspace_area"] == 0.0 and out["gtqi"] is None
    assert Biglide(1.0, 1.1, 0.0, 1e-12).workspace_area() == 0.0


@pytest.mark.parametrize("l1, l2, q_max", [
    (1e-12, 1e-3, 1.0), (1e-12, 1.0, 1e3), (1e-3, 1e-3 + 1e-15, 1e6), (1.0, 1.0 + 1e-12, 1e9),
    (1e3, 1e3 + 1e-6, 1e12), (1.0, 1.1, 1e6),
])
def test_biglide_of_mixed_sizes_evaluates_without_a_scipy_warning(l1, l2, q_max):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        v = _values(Biglide(l1, l2, 0.0, q_max))
    assert v["workspace_area"] > 0 and 0 < v["gtqi"] <= 1
