"""The command line: JSON keys, readable table, one-line errors with exit status 2."""
import json
import subprocess
import sys

import pytest

from mechopt.cli import main
from mechopt.analysis.evaluate import DISK_KEYS

REQUIRED = {"r_mic", "mic_center_y", "gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min",
            "gsi_max", "gsi_min", "usable_area", "gcw_area", "gcw_gci", "gcw_square_side",
            "theta1_range_deg", "theta2_range_deg", "quadrature", "mode"}


def test_evaluate_five_bar_json(capsys):
    assert main(["evaluate", "five-bar", "--r1", "0.85", "--r2", "1.6", "--r3", "0.55", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert REQUIRED <= set(out) == set(DISK_KEYS) | {"mechanism", "inputs"}
    # the inputs are echoed (with the options that change the numbers)
    assert out["inputs"] == {"r1": 0.85, "r2": 1.6, "r3": 0.55, "mode": "+-", "quadrature": "area",
                             "gamma": 0.5}
    assert out["quadrature"] == "area" and out["mode"] == "+-"
    assert out["r_mic"] == pytest.approx(0.85, rel=1e-6)
    lo, hi = out["theta1_range_deg"]
    assert lo < hi and all(isinstance(v, float) for v in (lo, hi))


def test_evaluate_five_bar_table(capsys):
    assert main(["evaluate", "five-bar", "--r1", "1.1", "--r2", "1.65", "--r3", "0.25",
                 "--quadrature", "polar", "--mode", "+-"]) == 0
    out = capsys.readouterr().out
    assert "gci" in out and "0.792" in out


@pytest.mark.parametrize("argv, message", [
    (["--r1", "0", "--r2", "1", "--r3", "1"], "r1 must be a positive finite length"),
    (["--r1", "-1", "--r2", "1", "--r3", "1"], "r1 must be a positive finite length"),
    (["--r1", "nan", "--r2", "1", "--r3", "1"], "r1 must be finite"),
    (["--r1", "1", "--r2", "inf", "--r3", "1"], "r2 must be finite"),
    (["--r1", "1", "--r2", "1", "--r3", "-0.5"], "r3 must be a non-negative finite length"),
    (["--r1", "1", "--r2", "1", "--r3", "0.5", "--mode", "+/"], "mode must be one of"),
    (["--r1", "1", "--r2", "1", "--r3", "0.5", "--quadrature", "gauss"], "quadrature must be one of"),
    (["--r1", "1", "--r2", "1", "--r3", "0.5", "--gamma", "1.0"], "gamma must lie in the open interval"),
    (["--r1", "1", "--r2", "1", "--r3", "0.5", "--gamma", "0"], "gamma must lie in the open interval"),
    (["--r1", "0.1", "--r2", "0.1", "--r3", "5"], "MIC radius 0"),
    (["--r1", "abc", "--r2", "1", "--r3", "1"], "invalid float value"),
    (["--r2", "1", "--r3", "1"], "required: --r1"),
])
def test_bad_input_is_one_line_exit_2(capsys, argv, message):
    assert main(["evaluate", "five-bar", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("mechopt: error: ")
    assert message in err


def test_console_script_exit_status_and_no_traceback():
    proc = subprocess.run([sys.executable, "-m", "mechopt.cli", "evaluate", "five-bar",
                           "--r1", "-1", "--r2", "1", "--r3", "1"], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and proc.stderr.strip().startswith("mechopt: error:")
    assert proc.stdout == ""


def test_json_has_no_nan_or_infinity(capsys):
    # k_av is unbounded when the x range contains a guide: printed as null, valid JSON
    assert main(["evaluate", "biglide", "--l1", "0.3", "--l2", "1.615", "--q1-min", "-1.9",
                 "--q1-max", "3", "--q2-min", "-3", "--mode=-+", "--json"]) == 0
    text = capsys.readouterr().out
    out = json.loads(text, parse_constant=lambda c: pytest.fail(f"non-standard JSON constant {c}"))
    assert out["k_av_1"] is None and out["workspace_area"] > 0
