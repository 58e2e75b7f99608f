"""Fuzz tests (issue 7): random and adversarial arguments for every CLI
sub-command and every public constructor and function.

The contract
------------
CLI (``mechopt.cli.main`` in process, and a few real ``python -m mechopt.cli``):

* the exit status is 0 or 2 and no exception escapes ``main`` (warnings are
  errors here: a RuntimeWarning means an unguarded overflow or 0/0);
* with 2, stderr is exactly one line ``mechopt: error: <message>``, no traceback;
* after a 0, no CSV or JSON file holds a NaN or infinite value (the atlas tables
  may leave a cell empty: that is their documented "no MIC" value);
* after a 2, the example's folder (the ``--out`` path, its parents and any
  results already there) is byte for byte as before.

Python API: every call returns or raises ``ValueError`` with a non-empty one-line
message (never TypeError, ZeroDivisionError, IndexError, OverflowError, a
warning, a hang or a MemoryError).

Every example stays cheap: a fully valid command that would start a long
computation gets small sizes (``--pop 2 --gen 1 --n-jobs 1``, ``--step 0.5``,
``--no-figures``, the fast problems) or one invalid argument appended (the last
value of a repeated option wins). The examples are derandomized, so CI runs the
same ones every time.
"""
from __future__ import annotations

import contextlib
import csv
import io
import itertools
import json
import math
import os
import pickle
import signal
import subprocess
import sys
import warnings
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from mechopt import cli

# --------------------------------------------------------------------------
# settings
# --------------------------------------------------------------------------
N_EVALUATE = 300  # mechopt evaluate ...
N_RUNS = 250  # optimize, sweep, atlas (they write --out)
N_MISC = 150  # every other command, global flags, random tokens
N_API = 1000  # constructors and public functions
#: the unmarked run of each long fuzz test: the same strategies, a quarter of the examples
#: (the full counts above run with ``-m slow``)
CI_SHARE = 4


def fuzz(n):
    return settings(max_examples=n, deadline=None, derandomize=True, database=None,
                    print_blob=False, suppress_health_check=list(HealthCheck))


@pytest.fixture(scope="module")
def fuzz_root(tmp_path_factory):
    return tmp_path_factory.mktemp("fuzz")


_counter = itertools.count()


def _new_workdir(root: Path) -> Path:
    work = root / f"ex{next(_counter)}"
    work.mkdir()
    return work


@contextlib.contextmanager
def _chdir(path):
    old = os.getcwd()
    os.chdir(path)
    try:
        yield
    finally:
        os.chdir(old)


class Hang(Exception):
    """An example ran longer than :data:`HANG_SECONDS` (a hang or a runaway size)."""


#: no single example may take this long (most take milliseconds)
HANG_SECONDS = 30


@contextlib.contextmanager
def no_hang(seconds=HANG_SECONDS):
    """Turn a hang into a failure (SIGALRM; main thread on POSIX only)."""
    if not hasattr(signal, "setitimer"):
        yield
        return

    def _raise(signum, frame):
        raise Hang(f"still running after {seconds} s")

    old = signal.signal(signal.SIGALRM, _raise)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


@contextlib.contextmanager
def strict_warnings():
    """Warnings are errors, except third-party deprecation notices."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for cat in (DeprecationWarning, PendingDeprecationWarning, FutureWarning, ResourceWarning):
            warnings.simplefilter("ignore", cat)
        yield


# --------------------------------------------------------------------------
# folder snapshots and output scans
# --------------------------------------------------------------------------
def snapshot(folder: Path) -> dict:
    """Every path under ``folder`` with its bytes (None for folders) and mode."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(folder):
        for d in dirnames:
            p = Path(dirpath, d)
            out[str(p.relative_to(folder))] = ("dir", p.stat().st_mode)
        for f in filenames:
            p = Path(dirpath, f)
            out[str(p.relative_to(folder))] = (p.read_bytes(), p.stat().st_mode)
    return out


_BAD_TOKENS = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}
#: tables whose empty cells are documented missing values (designs without a MIC)
_EMPTY_CELLS_OK = {"atlas.csv", "region.csv"}


def _reject_constant(token):
    raise AssertionError(f"non-finite JSON constant {token}")


def scan_outputs(folder: Path):
    """No NaN/inf in any CSV or JSON under ``folder``."""
    for p in sorted(folder.rglob("*")):
        if p.suffix == ".json":
            try:
                json.loads(p.read_text(), parse_constant=_reject_constant)
            except AssertionError as exc:
                raise AssertionError(f"{p}: {exc}") from None
        elif p.suffix == ".csv":
            with open(p, newline="") as fh:
                for i, row in enumerate(csv.reader(fh)):
                    for cell in row:
                        c = cell.strip().lower()
                        assert c not in _BAD_TOKENS, f"{p} row {i}: {cell!r} in {row}"
                        if c == "" and i > 0:
                            assert p.name in _EMPTY_CELLS_OK, f"{p} row {i}: empty cell in {row}"


# --------------------------------------------------------------------------
# running main() in process
# --------------------------------------------------------------------------
def run_main(argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), strict_warnings():
        try:
            with no_hang():
                rc = cli.main(list(argv))
        except Hang:
            raise AssertionError(f"mechopt.cli.main({argv!r}) hangs (> {HANG_SECONDS} s)") from None
        except BaseException as exc:  # noqa: BLE001 - that is the finding
            raise AssertionError(
                f"{type(exc).__name__} escaped mechopt.cli.main({argv!r}): {exc}\n"
                f"stderr: {err.getvalue()[-2000:]}") from exc
    return rc, out.getvalue(), err.getvalue()


_EVENT_WORDS = {"evaluate", "five-bar", "bipod", "biglide", "gantry", "optimize", "sweep", "atlas",
                "problems", "run", "reproduce"}


def check_cli(argv, work: Path):
    """Run ``argv`` in ``work`` and check the whole contract; return (rc, out, err)."""
    with _chdir(work):
        before = snapshot(work)
        rc, out, err = run_main(argv)
        after = snapshot(work)
    # 2 bad input, 3 a runtime failure (an unreachable Dask scheduler, an unwritable disk)
    assert rc in (0, 2, 3), f"exit status {rc!r} for {argv!r}; stderr {err!r}"
    words = [a for a in argv[:2] if a in _EVENT_WORDS]
    event(f"{' '.join(words) or 'other'} -> exit {rc}")
    assert "Traceback" not in err, f"traceback for {argv!r}:\n{err}"
    if rc in (2, 3):
        assert err.startswith("mechopt: error: "), f"{argv!r}: stderr {err!r}"
        assert err.endswith("\n") and err.count("\n") == 1 and "\r" not in err, (
            f"{argv!r}: stderr is not one line: {err!r}")
        assert err[len("mechopt: error: "):].strip(), f"{argv!r}: empty message"
        changed = sorted(set(before.items()) ^ set(after.items()))
        assert before == after, (
            f"{argv!r} failed ({err.strip()!r}) but changed its folder: "
            f"{sorted({k for k, _ in changed})}")
    else:
        scan_outputs(work)
    return rc, out, err


# --------------------------------------------------------------------------
# value strategies for the command line: (text, ok) pairs
# --------------------------------------------------------------------------
LENGTH_MIN, LENGTH_MAX = 1e-12, 1e12  # mechopt.core.validation


def _float_text(x):
    return st.sampled_from([repr(x), f"{x:g}", f"{x:.17e}"])


def _as_float(text):
    try:
        return float(text)
    except (TypeError, ValueError, OverflowError):
        return None


def _oracle_pos(t):
    v = _as_float(t)
    return v is not None and math.isfinite(v) and LENGTH_MIN <= v <= LENGTH_MAX


def _oracle_nonneg(t):
    v = _as_float(t)
    return v is not None and math.isfinite(v) and 0 <= v <= LENGTH_MAX


def _oracle_real(t):
    v = _as_float(t)
    return v is not None and math.isfinite(v) and abs(v) <= LENGTH_MAX


def _oracle_unit(t):
    v = _as_float(t)
    return v is not None and 0 < v < 1


def _oracle_deg(t):
    v = _as_float(t)
    return v is not None and 0 < v < 45


def _oracle_int(lo, hi=None):
    def ok(t):
        try:
            v = int(t)
        except (TypeError, ValueError):
            return False
        return v >= lo and (hi is None or v <= hi)
    return ok


ADVERSARIAL_NUMBERS = [
    "0", "-0", "-0.0", "-1", "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e999", "-1e999",
    "1e308", "1.7976931348623157e308", "5e-324", "1e-300", "1e300", "1e13", "1e-13", "2e12",
    "", " ", "x", "1,5", "0x10", "1e", ".", "+", "-", "--", "None", "\udcff", "\u2028",
    "1 2", "١", "1_000", " 7 ", "𝟙",
]
_ANY_TEXT = st.text(st.characters(blacklist_categories=("Cs",), blacklist_characters="\x00"),
                    max_size=8)


_BAD_NUMBER_TEXT = st.one_of(
    st.sampled_from(ADVERSARIAL_NUMBERS),
    st.floats(allow_nan=True, allow_infinity=True).flatmap(lambda x: st.sampled_from([repr(x), f"{x:g}"])),
    st.integers(-10**30, 10**30).map(str),
    _ANY_TEXT,
)


def _choice_bad(allowed, extra_bad=()):
    return st.one_of(st.sampled_from(["", " ", "x", "None", "\udcff", "é", *extra_bad,
                                      *(a.upper() for a in allowed), *(f" {a}" for a in allowed)]),
                     _ANY_TEXT)


def _floats_text(lo, hi):
    return st.floats(lo, hi).flatmap(_float_text)


def _in(allowed):
    return lambda t: t in allowed


#: kind -> (sensible values, adversarial values, oracle: is this text valid?)
VALUES = {
    "pos": (st.one_of(_floats_text(0.05, 5.0), st.sampled_from(["1", "0.85", "1e-12", "1e12", " 2 ", "١"])),
            _BAD_NUMBER_TEXT, _oracle_pos),
    "nonneg": (st.one_of(_floats_text(0.0, 2.0), st.sampled_from(["0", "-0.0", "1e-300"])), _BAD_NUMBER_TEXT,
               _oracle_nonneg),
    "real": (_floats_text(-5.0, 5.0), _BAD_NUMBER_TEXT, _oracle_real),
    # ordered pairs (a stroke's ends, the Biglide's l1 < l2), so that clean examples are valid designs
    "pos_lo": (_floats_text(0.3, 1.0), _BAD_NUMBER_TEXT, _oracle_pos),
    "pos_hi": (_floats_text(1.05, 3.0), _BAD_NUMBER_TEXT, _oracle_pos),
    "real_lo": (_floats_text(-3.0, -0.05), _BAD_NUMBER_TEXT, _oracle_real),
    "real_hi": (_floats_text(0.05, 3.0), _BAD_NUMBER_TEXT, _oracle_real),
    "unit": (_floats_text(0.01, 0.99), _BAD_NUMBER_TEXT, _oracle_unit),
    "deg": (_floats_text(0.5, 44.5), _BAD_NUMBER_TEXT, _oracle_deg),
    "mode5": (st.sampled_from(("+-", "-+", "++", "--")), _choice_bad(("+-", "-+", "++", "--"), ("+/", "+", "+-+")),
              _in(("+-", "-+", "++", "--"))),
    "quad": (st.sampled_from(("area", "polar")), _choice_bad(("area", "polar"), ("gauss",)), _in(("area", "polar"))),
    "branch": (st.sampled_from(("up", "down", "full")), _choice_bad(("up", "down", "full")),
               _in(("up", "down", "full"))),
    "unit_name": (st.sampled_from(("mm", "m")), _choice_bad(("mm", "m"), ("cm", "km")), _in(("mm", "m"))),
}


def _value_tokens(draw, opt, text):
    """``--opt value`` or ``--opt=value`` (always the latter for a value that looks like an option)."""
    if text.startswith("-") or draw(st.integers(0, 4)) == 0:
        return [f"{opt}={text}"]
    return [opt, text]


JUNK = ["--bogus", "extra", "-x", "--", "--json=1", "--r", "-"]


@st.composite
def option_tokens(draw, spec, required=()):
    """Tokens for a sub-command's options; returns (tokens, certainly_invalid).

    An example is "clean" (sensible values only), "one" (one thing wrong: a bad
    value, a missing value or required option, an unknown token) or "chaos"
    (anything anywhere), so that valid runs are common and each kind of error
    is also met alone."""
    mode = draw(st.sampled_from(["clean", "clean", "one", "one", "chaos"]))
    groups, invalid = {}, False
    for opt, kind in spec:
        if kind == "flag":
            k = draw(st.integers(0, 9))
            if k < 5:
                continue
            groups[opt] = [opt] * (2 if k == 5 else 1)
            if mode == "chaos" and k == 6:
                groups[opt] = [f"{opt}=x"]
                invalid = True
            continue
        good, bad, oracle = VALUES[kind]
        k = draw(st.integers(0, 9))
        if k < 2 and opt not in required:
            continue
        if mode == "chaos" and k < 1:  # a required option left out
            invalid = True
            continue
        if mode == "chaos" and k == 2:  # the value is missing
            groups[opt] = [opt]
            invalid = True
            continue
        text = draw(bad if mode == "chaos" and k >= 6 else good)
        invalid |= not oracle(text)
        tokens = _value_tokens(draw, opt, text)
        if k == 3:  # given twice: the last one wins
            tokens = _value_tokens(draw, opt, draw(good if mode != "chaos" else st.one_of(good, bad))) + tokens
        groups[opt] = tokens
    if mode == "one":
        opt, kind = draw(st.sampled_from(spec))
        how = draw(st.integers(0, 3))
        if kind == "flag":
            groups[opt] = [f"{opt}=x"]
        elif how == 0 and opt in required:
            groups.pop(opt, None)
        elif how == 1:
            groups[opt] = [opt]
        elif how == 2:
            groups[opt] = groups.get(opt, []) + [draw(st.sampled_from(JUNK))]
        else:
            text = draw(VALUES[kind][1])
            groups[opt] = _value_tokens(draw, opt, text)
            if VALUES[kind][2](text):  # an adversarial text that is in fact valid
                return [t for g in groups.values() for t in g], invalid
        invalid = True
    if mode == "chaos" and draw(st.integers(0, 4)) == 0:
        groups["junk"] = [draw(st.sampled_from(JUNK))]
        invalid = True
    keys = list(groups)
    order = draw(st.permutations(keys)) if keys else []
    return [t for k in order for t in groups[k]], invalid


def _evaluate_specs():
    """``{mechanism: (option specs, required options)}`` of ``mechopt evaluate``, from the
    options the CLI generates its sub-commands from (:func:`mechopt.cli.evaluate.options`),
    with this file's value generators per parameter kind."""
    from mechopt.cli.evaluate import options
    from mechopt.mechanisms import registry

    by_kind = {"length": "pos", "length0": "nonneg", "position": "real", "angle_deg": "deg",
               "fraction": "unit"}
    by_choices = {frozenset(("+-", "-+", "++", "--")): "mode5", frozenset(("area", "polar")): "quad",
                  frozenset(("up", "down", "full")): "branch", frozenset(("mm", "m")): "unit_name"}
    specs = {}
    for name, cls in registry().items():
        params = options(cls)
        spec = [(p.option, by_choices[frozenset(p.choices)] if p.choices else by_kind[p.kind])
                for p in params] + [("--json", "flag")]
        specs[name] = (spec, tuple(p.option for p in params if p.required))
    return specs


EVALUATE_SPECS = _evaluate_specs()
#: appended to a fully valid five-bar command (a full evaluation takes ~1 s)
FIVE_BAR_SPOILERS = [["--gamma", "1.5"], ["--r1", "nan"], ["--mode", "+/"], ["--quadrature", "gauss"],
                     ["--r3", "-1"], ["--r2", "1e13"], ["--gamma=-0.0"], ["--r1", "x"]]


@st.composite
def evaluate_argv(draw):
    mech = draw(st.sampled_from(sorted(EVALUATE_SPECS)))
    spec, required = EVALUATE_SPECS[mech]
    tokens, invalid = draw(option_tokens(spec, required))
    if mech == "five-bar" and not invalid and draw(st.integers(0, 24)) != 0:
        tokens += draw(st.sampled_from(FIVE_BAR_SPOILERS))
    return ["evaluate", mech, *tokens]


def _evaluate_case(fuzz_root, argv):
    rc, out, err = check_cli(argv, _new_workdir(fuzz_root))
    if rc == 0:
        assert out.strip()


@fuzz(N_EVALUATE // CI_SHARE)
@given(evaluate_argv())
def test_cli_evaluate_fuzz(fuzz_root, argv):
    _evaluate_case(fuzz_root, argv)


@pytest.mark.slow
@fuzz(N_EVALUATE)
@given(evaluate_argv())
def test_cli_evaluate_fuzz_full(fuzz_root, argv):
    _evaluate_case(fuzz_root, argv)


# --------------------------------------------------------------------------
# optimize / sweep / atlas: commands that write --out
# --------------------------------------------------------------------------
def _make_out(work: Path, kind: str) -> str:
    """Prepare the example folder for one --out kind; return the --out text."""
    if kind == "new":
        return "out"
    if kind == "absolute":
        return str(work / "out")
    if kind == "nested":
        return "a/b/out"
    if kind == "existing":
        (work / "out").mkdir()
        return "out"
    if kind == "previous":  # results of an earlier run must survive a failed one
        (work / "out").mkdir()
        (work / "out" / "front.csv").write_text("x,y\n1,2\n")
        (work / "out" / "keep.txt").write_text("keep")
        return "out"
    if kind == "file":
        (work / "out").write_text("a file")
        return "out"
    if kind == "under_file":
        (work / "f").write_text("a file")
        return "f/out"
    if kind == "readonly":
        (work / "ro").mkdir()
        os.chmod(work / "ro", 0o500)
        return "ro/out"
    if kind == "dot":
        return "."
    if kind == "empty":
        return ""
    if kind == "unicode":
        return "résultats ü/out"
    if kind == "dash":
        return "-o"
    raise AssertionError(kind)


OUT_KINDS = ("new", "new", "absolute", "nested", "existing", "previous", "file", "under_file",
             "readonly", "dot", "empty", "unicode", "dash")
CLEAN_OUT_KINDS = ("new", "absolute", "nested", "existing", "previous", "dot", "unicode", "dash")
_OUT_INVALID = {"file", "under_file", "empty"}

FAST_PROBLEMS = ("stan2008-bipod", "stan2008-biglide", "wu2008", "wu2008-dynamic")
FAST_2OBJ = ("stan2008-bipod", "stan2008-biglide", "wu2008")
SLOW_PROBLEMS = ("le2013", "le2013-relaxed", "le2013-gamma", "le2013-gamma-relaxed", "liu2006-w-gci",
                 "liu2006-all", "liu2006-many")
BAD_PROBLEMS = ("", "nope", "LE2013", "le2013 ", "stan2008", "wu2008-", "\udcff", "--pop", "-1")

INT_VALUES = {
    "--pop": (("2", "3", "4"), ("1", "0", "-1", "1.5", "x", "1e3", "", "99999999999999999999",
                               "100000000000")),
    "--gen": (("1",), ("0", "-1", "x", "1.0", "")),
    "--seed": (("0", "1", "7", "4294967295", "99999999999999999999"), ("-1", "x", "1.5", "")),
    "--n-jobs": (("1",), ("0", "-1", "-100", "x", "1.0", "")),
    "--checkpoint-every": (("1",), ("0", "-1", "x", "")),
    "--chunk-size": (("1", "3", "100", "10000000000000000000000"), ("0", "-3", "x", "1.5", "")),
}


@st.composite
def int_option(draw, opt, allow_missing=True, clean=False):
    """(tokens, given, ok) for an integer option (never a bad one when ``clean``)."""
    good, bad = INT_VALUES[opt]
    k = draw(st.integers(0, 9))
    if k < 3 and allow_missing:
        return [], False, True
    text = draw(st.sampled_from(good if k < 7 or clean else bad))
    ok = text in good
    toks = [f"{opt}={text}"] if text.startswith("-") or text == "" else [opt, text]
    return toks, True, ok


#: scheduler addresses that dask itself rejects or cannot reach: tried in real
#: processes only (in this process, every failed distributed.Client leaves threads
#: and locks behind, and after a few of them the next one can hang)
DASK_ADDRESSES = ("nonsense", "inproc://", "ü", "tcp://[::1", "tcp://127.0.0.1:abc", "xyz://a:1")
#: --dask values mechopt rejects before creating a client ("" means: no Dask)
DASK_REJECTED = (" ", "\t", "")


def _bad_resume_dir(work: Path, kind: str) -> str:
    d = work / "ck"
    if kind == "missing":
        return "ck"
    d.mkdir()
    payload = {"empty": None, "garbage": b"garbage", "zero": b"", "int": pickle.dumps(5),
               "dict": pickle.dumps({}), "trunc": pickle.dumps({"a": list(range(50))})[:-7],
               "call": b"cbuiltins\nlen\n(S'ab'\ntR.",  # a harmless call: len('ab')
               "badmod": b"cnot_a_module_xyz\nThing\n.", "badattr": b"cos\nnot_a_function_xyz\n.",
               "utf8": b"\x80\x05\x8c\x05\xff\xfe\xfd\xfc\xfb\x94.",
               "wrong": pickle.dumps({"algorithm_state": 1, "state": 2})}[kind]
    if payload is not None:
        (d / "checkpoint.pkl").write_bytes(payload)
    return "ck"


@st.composite
def optimize_argv(draw, work):
    toks, invalid = ["optimize"], False
    clean = draw(st.integers(0, 9)) < 4  # a valid, small run
    pk = 0 if clean else draw(st.integers(0, 9))
    if pk < 6:
        problem = draw(st.sampled_from(FAST_PROBLEMS))
    elif pk < 8:
        problem = draw(st.sampled_from(SLOW_PROBLEMS))
    else:
        problem = draw(st.sampled_from(BAD_PROBLEMS))
        invalid = True
    if clean or draw(st.integers(0, 14)):
        toks.append(problem)
    else:
        invalid = True
    given = {}
    for opt in ("--pop", "--gen", "--seed", "--n-jobs", "--checkpoint-every"):
        t, g, ok = draw(int_option(opt, clean=clean))
        toks += t
        given[opt] = g
        invalid |= not ok
    alg = draw(st.sampled_from([None, "nsga2", "nsga3"] if clean else
                               [None, None, "ga", "nsga2", "nsga3", "GA", "", "x", "nsga4"]))
    if alg is not None:
        toks += [f"--algorithm={alg}"]
        invalid |= alg not in ("ga", "nsga2", "nsga3", "")  # "": the problem's default
    if not clean and draw(st.integers(0, 9)) == 0:
        addr = draw(st.sampled_from(DASK_REJECTED))
        toks += [f"--dask={addr}"]
        invalid |= addr != ""
    out_kind = draw(st.sampled_from(CLEAN_OUT_KINDS if clean else OUT_KINDS))
    if clean or draw(st.integers(0, 14)):
        toks += [f"--out={_make_out(work, out_kind)}"]
        invalid |= out_kind in _OUT_INVALID
    else:
        invalid = True
    if not clean and draw(st.integers(0, 11)) == 0:
        kind = draw(st.sampled_from(["missing", "empty", "garbage", "zero", "int", "dict", "trunc",
                                     "call", "badmod", "badattr", "utf8", "wrong"]))
        toks += ["--resume", _bad_resume_dir(work, kind)]
        invalid = True
    if not invalid:  # keep a valid run small
        toks += [] if given["--pop"] else ["--pop", "2"]
        toks += [] if given["--gen"] else ["--gen", "1"]
        toks += [] if given["--n-jobs"] else ["--n-jobs", "1"]
        if problem in SLOW_PROBLEMS:
            toks += draw(st.sampled_from([["--gen", "0"], ["--pop", "1"], ["--seed", "x"],
                                          ["--algorithm", "nope"], ["--n-jobs", "0"]]))
    return toks


WEIGHTS_GOOD = ("0,1", "0.5", "0:1:0.5", "1", "0:0:1", "0.25, 0.75", "1:1:0.1")
WEIGHTS_BAD = ("", ",", "0:1:0", "0:1:-0.1", "1:0:0.1", "0:1:5e-324", "0:inf:1", "nan", "2", "-0.1,0.5",
               "a", "0:1", "0:1:1e-9", "0:1:0.5:1", "inf", "1e999", "0;1", "\udcff")


@st.composite
def sweep_argv(draw, work):
    toks, invalid = ["sweep"], False
    clean = draw(st.integers(0, 9)) < 4  # a valid, small run
    pk = 0 if clean else draw(st.integers(0, 9))
    if pk < 7:
        problem = draw(st.sampled_from(FAST_2OBJ))
    elif pk < 8:
        problem = draw(st.sampled_from(("le2013", "wu2008-dynamic", "liu2006-many", "le2013-gamma")))
    else:
        problem = draw(st.sampled_from(BAD_PROBLEMS))
        invalid = True
    toks.append(problem)
    given = {}
    for opt in ("--pop", "--gen", "--seed", "--n-jobs"):
        t, g, ok = draw(int_option(opt, clean=clean))
        toks += t
        given[opt] = g
        invalid |= not ok
    k = draw(st.integers(0, 9))
    if k < 7:
        w = draw(st.sampled_from(WEIGHTS_GOOD if k < 4 or clean else WEIGHTS_BAD))
        toks += [f"--weights={w}"]
        invalid |= w in WEIGHTS_BAD
    out_kind = draw(st.sampled_from(CLEAN_OUT_KINDS if clean else OUT_KINDS))
    toks += [f"--out={_make_out(work, out_kind)}"]
    invalid |= out_kind in _OUT_INVALID
    if not invalid:
        toks += [] if given["--pop"] else ["--pop", "2"]
        toks += [] if given["--gen"] else ["--gen", "1"]
        toks += [] if given["--n-jobs"] else ["--n-jobs", "1"]
        if problem not in FAST_2OBJ + FAST_PROBLEMS:
            toks += ["--gen", "0"]
    return toks


STEPS_GOOD = ("0.5", "0.4", "0.3", "0.25", "0.5000")
STEPS_BAD = ("0", "-0.1", "nan", "inf", "1e-300", "5e-324", "0.51", "1e308", "x", "", "-0", "1e-9",
             "0.00001")
INDEX_GOOD = ("gci", "r_mic", "gci,mci", "gvi,gpi,gsi", "gci,gci", " gci , mci ", "gsi,r_mic",
              "gci,mci,gvi,gpi,gsi,r_mic")
INDEX_BAD = ("", ",", "gci,,mci", "GCI", "gci mci", "gvi_max", "x", "gci;mci", "\udcff")
WHERE_NAMES = ("r1", "r2", "r3", "s", "t", "r_mic", "mic_center_y", "gci", "mci", "gvi_max", "gvi_min",
               "gpi_max", "gpi_min", "gsi_max", "gsi_min")
WHERE_BAD_NAMES = ("gvi", "foo", "__import__", "os", "R_MIC", "nan", "inf", "True", "lambda")
WHERE_NUMBERS = ("0", "0.5", "1e999", "-1", "1e", ".5", "5.", "0x1", "1e-400", "- 2", "+3", "--1",
                 "1_0", "١")
WHERE_GOOD = ("r_mic > 0.8 and gci > 0.6", "0 < r3 < 1", "not (r1 > r2) or r_mic >= 0.5", "r_mic > 1e999",
              "r1 == r2", "r_mic > -1", "(s > 0) and (t < 1)", "r_mic != r_mic", "  r_mic>0.1  ")
WHERE_OPS = ("<", "<=", ">", ">=", "==", "!=", "=", "<>", "=>", "!")
WHERE_SPECIAL = ("r_mic >", "and and", "__import__('os')", "gci > 0.5 or", "gci > 0.5 and", "é > 1",
                 "()", "(gci > 0.5", "gci > 0.5)", "not", "not not gci > 0", "gci", "0.5",
                 "r_mic > 0.8 and gci > 0.6", "0 < gci < 1", "gci > 0.5 or not (mci < 0.9)",
                 "r_mic > 0.8\nand gci > 0.6", "gci > 0.5; import os", "gci > 0.5 # c", "",
                 "(" * 3000 + "gci > 0" + ")" * 3000, "not " * 3000 + "gci > 0",
                 "gci > " + "-" * 3000 + "1", "gci > 0 and " * 2000 + "gci > 0",
                 "r_mic > " + "9" * 400, "gci\u00a0> 0", "gci ＞ 0", "ｇｃｉ > 0")


@st.composite
def where_text(draw, depth=0):
    k = draw(st.integers(0, 9))
    if k == 0 and depth == 0:
        return draw(st.sampled_from(WHERE_SPECIAL))
    if k == 1 and depth == 0:
        return draw(_ANY_TEXT)

    def operand():
        j = draw(st.integers(0, 9))
        if j < 5:
            return draw(st.sampled_from(WHERE_NAMES))
        if j < 6:
            return draw(st.sampled_from(WHERE_BAD_NAMES))
        return draw(st.sampled_from(WHERE_NUMBERS))

    def comparison():
        parts = [operand()]
        for _ in range(draw(st.integers(1, 2))):
            j = draw(st.integers(0, 9))
            parts += [draw(st.sampled_from(WHERE_OPS[:6] if j < 8 else WHERE_OPS)), operand()]
        return " ".join(parts)

    if depth >= 2:
        return comparison()
    j = draw(st.integers(0, 9))
    if j < 4:
        text = comparison()
    elif j < 6:
        text = f"{draw(where_text(depth + 1))} {draw(st.sampled_from(['and', 'or', 'AND', 'Or']))} " \
               f"{draw(where_text(depth + 1))}"
    elif j < 7:
        text = f"not {draw(where_text(depth + 1))}"
    else:
        text = f"({draw(where_text(depth + 1))})"
    if depth == 0 and draw(st.integers(0, 5)) == 0:  # mutate: cut it short
        text = text[: draw(st.integers(0, max(len(text) - 1, 0)))]
    return text


@st.composite
def atlas_argv(draw, work):
    toks, invalid = ["atlas", "five-bar"], False
    clean = draw(st.integers(0, 9)) < 4  # a valid, small run
    step_given = draw(st.integers(0, 9)) > 0
    if step_given:
        k = draw(st.integers(0, 9))
        s = draw(st.sampled_from(STEPS_GOOD if k < 7 or clean else STEPS_BAD))
        toks += [f"--step={s}"]
        invalid |= s in STEPS_BAD
    n_index = 6
    if draw(st.booleans()):
        k = draw(st.integers(0, 9))
        idx = draw(st.sampled_from(INDEX_GOOD if k < 7 or clean else INDEX_BAD))
        toks += [f"--index={idx}"]
        invalid |= idx in INDEX_BAD
        n_index = len({s.strip() for s in idx.split(",")})
    for opt, kind in (("--quadrature", "quad"), ("--mode", "mode5")):
        if draw(st.booleans()):
            good, bad, oracle = VALUES[kind]
            text = draw(good if clean else st.one_of(good, good, good, bad))
            toks += [f"{opt}={text}"]
            invalid |= not oracle(text)
    nj_toks, nj_given, nj_ok = draw(int_option("--n-jobs", clean=clean))
    toks += nj_toks
    invalid |= not nj_ok
    dask = not clean and draw(st.integers(0, 9)) == 0
    if dask:  # a scheduler address with a bad timeout, or an address mechopt rejects
        addr = draw(st.sampled_from(DASK_ADDRESSES + DASK_REJECTED))
        toks += [f"--dask={addr}"]
        invalid = True
        bad_timeouts = ['0', '-1', 'nan', 'inf', 'x', '-1e-300', '1e999']
        timeout = draw(st.sampled_from(bad_timeouts if addr in DASK_ADDRESSES else bad_timeouts + ['0.1']))
        toks += [f"--dask-timeout={timeout}"]
    elif not clean and draw(st.integers(0, 9)) == 0:
        t = draw(st.sampled_from(["0.1", "0", "-1", "nan", "inf", "x"]))
        toks += [f"--dask-timeout={t}"]
        invalid |= t in ("x",)
    if draw(st.integers(0, 2)) == 0:
        toks += ["--where", draw(st.sampled_from(WHERE_GOOD) if clean else where_text())]
    ck_toks, _, ck_ok = draw(int_option("--chunk-size", clean=clean))
    toks += ck_toks
    invalid |= not ck_ok
    figures = draw(st.integers(0, 9)) == 0
    if not figures:
        toks.append("--no-figures")
    out_kind = draw(st.sampled_from(CLEAN_OUT_KINDS if clean else OUT_KINDS))
    if clean or draw(st.integers(0, 14)):
        toks += [f"--out={_make_out(work, out_kind)}"]
        invalid |= out_kind in _OUT_INVALID
    else:
        invalid = True
    if not invalid:
        if not step_given:
            toks += ["--step", "0.5"]
        if not nj_given and not dask:
            toks += ["--n-jobs", "1"]
        if figures and n_index > 1:
            toks.append("--no-figures")  # one PNG costs ~0.7 s
    return toks


@fuzz(N_RUNS // CI_SHARE)
@given(st.data())
def test_cli_runs_fuzz(fuzz_root, data):
    _runs_case(fuzz_root, data)


@pytest.mark.slow
@fuzz(N_RUNS)
@given(st.data())
def test_cli_runs_fuzz_full(fuzz_root, data):
    _runs_case(fuzz_root, data)


def _runs_case(fuzz_root, data):
    work = _new_workdir(fuzz_root)
    command = data.draw(st.sampled_from(["optimize", "optimize", "sweep", "atlas", "atlas"]))
    make = {"optimize": optimize_argv, "sweep": sweep_argv, "atlas": atlas_argv}[command]
    argv = data.draw(make(work))
    try:
        rc, out, err = check_cli(argv, work)
    finally:
        if (work / "ro").exists():
            os.chmod(work / "ro", 0o700)
    if rc == 0:
        written = [p for p in work.rglob("*") if p.is_file()]
        assert written, f"{argv!r} exited 0 without writing anything"


# --------------------------------------------------------------------------
# every other command, global flags, random tokens
# --------------------------------------------------------------------------
MISC_ARGV = [
    [], ["--version"], ["-h"], ["--help"], ["--vers"], ["evaluate"], ["evaluate", "-h"],
    ["evaluate", "four-bar"], ["evaluate", "five-bar"], ["evaluate", "five-bar", "--help"],
    ["atlas"], ["atlas", "bipod"], ["atlas", "five-bar"], ["atlas", "five-bar", "-h"],
    ["problems"], ["problems", "x"], ["problems", "--json"], ["run", "--quadrature", "x"],
    ["run", "extra"], ["run", "--quadrature"], ["run", "--quadrature=gauss"], ["reproduce"],
    ["reproduce", "nope"], ["reproduce", "nope", "--out", "out"], ["reproduce", "", "--quick"],
    ["reproduce", "ALL"], ["reproduce", "stan2008", "--out", "f/out"],
    ["reproduce", "stan2008", "--out=out", "--quick", "--force", "--bogus"],
    ["reproduce", "le2013", "--out", ""], ["optimize"], ["sweep"], ["optimize", "--resume"],
    ["nonsense"], ["--verbose"], ["evaluate", "five-bar", "--r1"], ["-"], ["--"], ["\udcff"],
    ["evaluate", "gantry", "--h"], ["evaluate", "gantry", "-h", "--b", "x"],
]
TOKENS = ["evaluate", "five-bar", "bipod", "biglide", "gantry", "atlas", "optimize", "sweep",
          "problems", "reproduce", "run", "--r1", "--r2", "--r3", "--b", "--h", "--out", "--step",
          "--pop", "--gen", "--json", "--quick", "--force", "--mode", "--where", "--weights", "-h",
          "--version", "1", "0", "-1", "nan", "x", "", "--", "wu2008", "le2013", "out", "=", "--=x"]


@st.composite
def misc_argv(draw):
    k = draw(st.integers(0, 2))
    if k == 0:
        return draw(st.sampled_from(MISC_ARGV))
    toks = draw(st.lists(st.one_of(st.sampled_from(TOKENS), _ANY_TEXT), max_size=7))
    # never a complete, long-running command: an unknown flag ends every random list
    return toks + ["--zz-not-an-option"]


@fuzz(N_MISC)
@given(misc_argv())
def test_cli_misc_fuzz(fuzz_root, argv):
    work = _new_workdir(fuzz_root)
    (work / "f").write_text("a file")
    rc, out, err = check_cli(argv, work)
    if rc == 0:
        assert out.strip() or err.strip()


# --------------------------------------------------------------------------
# real processes: nothing but the one line reaches the terminal
# --------------------------------------------------------------------------
SUBPROCESS_CASES = [
    (["evaluate", "five-bar", "--r1", "nan", "--r2", "1", "--r3", "1"], 2),
    (["evaluate", "biglide", "--l1", "5e-324", "--l2", "1e-323", "--q1-min", "0", "--q1-max", "1"], 2),
    (["evaluate", "bipod", "--b", "1e300", "--q1-min", "1", "--q1-max", "1e300"], 2),
    (["atlas", "five-bar", "--step", "0", "--out", "a/b/out"], 2),
    (["atlas", "five-bar", "--step", "0.5", "--dask", "tcp://127.0.0.1:1", "--dask-timeout", "nan",
      "--out", "a/b/out"], 2),
    (["optimize", "wu2008", "--pop", "100000000000", "--gen", "1", "--n-jobs", "1", "--out", "a/out"], 2),
    (["sweep", "wu2008", "--weights", "0:1:1e-9", "--out", "a/out"], 2),
    (["atlas", "five-bar", "--step", "0.5", "--where", "not " * 3000 + "gci > 0", "--out", "out"], 2),
    (["optimize", "wu2008", "--pop", "2", "--gen", "1", "--dask", "nonsense", "--out", "a/out"], 2),
    (["atlas", "five-bar", "--step", "0.5", "--dask", "tcp://127.0.0.1:abc", "--out", "a/out"], 2),
    (["atlas", "five-bar", "--step", "0.5", "--dask", "tcp://127.0.0.1:1", "--dask-timeout", "0.2",
      "--out", "a/out"], 3),  # an unreachable scheduler: a runtime failure
    (["--version"], 0),
]


@pytest.mark.parametrize("argv, status", SUBPROCESS_CASES, ids=lambda v: None)
def test_cli_subprocess_no_traceback(tmp_path, argv, status):
    proc = subprocess.run([sys.executable, "-m", "mechopt.cli", *argv], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == status, proc.stderr
    assert "Traceback" not in proc.stderr and "Warning" not in proc.stderr, proc.stderr
    if status in (2, 3):
        assert proc.stderr.startswith("mechopt: error: ") and proc.stderr.count("\n") == 1, proc.stderr
        assert list(tmp_path.iterdir()) == [], "a failed run left files behind"
    else:
        assert proc.stdout.startswith("mechopt ")


def test_cli_subprocess_undecodable_argument(tmp_path):
    proc = subprocess.run([os.fsencode(sys.executable), b"-m", b"mechopt.cli", b"evaluate",
                           b"five-bar", b"--r1", b"\xff\xfe", b"--r2", b"1", b"--r3", b"0"],
                          cwd=tmp_path, capture_output=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.startswith(b"mechopt: error: ") and proc.stderr.count(b"\n") == 1, proc.stderr


# --------------------------------------------------------------------------
# Python API
# --------------------------------------------------------------------------
NAN, INF = float("nan"), float("inf")
SPECIAL_FLOATS = [NAN, INF, -INF, -0.0, 0.0, 1e308, -1e308, 5e-324, -5e-324, 1e-300, 1e300,
                  2.2250738585072014e-308, 1e13, 1e-13, -1.0]
BAD_OBJECTS = [None, "", "x", "nan", "1,5", "١", b"\xff", [1.0], [], (1.0, 2.0), {}, 1 + 2j, 10**400,
               -10**400, True, object(), np.float64("nan"), np.array([1.0, 2.0]),
               np.array([[1.0, 2.0], [3.0, 4.0]]), Decimal("nan"), Decimal("1e999"), Fraction(1, 3),
               np.int64(-3), "\udcff", "1e999", "-inf"]


#: how many of 20 drawn arguments are sensible, set per example by test_api_fuzz: all
#: (a valid call, checked to return), nearly all (one thing wrong) or about half
_SENSIBLE = [14]


def _pick(good, bad, bias=0):
    return st.integers(0, 19).flatmap(lambda k: good if k < _SENSIBLE[0] + bias else bad)


def mixed(good, p_good=0):
    """Mostly ``good``, else an adversarial number or object."""
    bad = st.one_of(st.sampled_from(SPECIAL_FLOATS), st.sampled_from(BAD_OBJECTS),
                    st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**6, 10**6),
                    _ANY_TEXT)
    return _pick(good, bad, p_good)


def name_of(allowed):
    bad = st.one_of(st.sampled_from([None, "", "x", 1, 0.5, b"up", "\udcff", [allowed[0]],
                                     allowed[0].upper() + "!", f" {allowed[0]}"]), _ANY_TEXT)
    return _pick(st.sampled_from(allowed), bad, 2)


length = mixed(st.floats(0.05, 5.0))
length0 = mixed(st.one_of(st.just(0.0), st.floats(0.0, 2.0)))
real = mixed(st.floats(-5.0, 5.0))
BAD_COUNTS = [0, -1, -7, 1.5, 2.0, "3", "x", "", None, NAN, INF, -INF, True, 10**400, [4], 1e308]


def count(good):
    """A resolution or size: mostly ``good``, else a bad one (never a huge valid one)."""
    return _pick(good, st.sampled_from(BAD_COUNTS))


small_int = count(st.integers(1, 12))
unit_interval = mixed(st.floats(0.01, 0.99))
point = mixed(st.one_of(st.floats(-3.0, 3.0), st.lists(st.floats(-3.0, 3.0), min_size=1, max_size=3)))

_CACHE = {}


def _cached(key, make):
    if key not in _CACHE:
        _CACHE[key] = make()
    return _CACHE[key]


def _five_bar():
    from mechopt import FiveBar

    return _cached("fb", lambda: FiveBar(0.85, 1.6, 0.55))


def _mic():
    from mechopt.analysis.workspace import mic

    return _cached("mic", lambda: mic(_five_bar()))


def _usable():
    from mechopt.analysis.workspace import usable_region

    return _cached("usable", lambda: usable_region(_five_bar(), step=0.05, center=(0.0, _mic().center_y)))


def _gantry_m():
    from mechopt.mechanisms.gantry import wu2008_gantry

    return _cached("gantry", lambda: wu2008_gantry(unit="m"))


# Each target draws its arguments and returns a thunk; the thunk may call several
# public functions (a constructor, then cheap methods on what it built).
API_TARGETS = {}


def target(fn):
    API_TARGETS[fn.__name__] = fn
    return fn


@target
def five_bar(draw):
    from mechopt import FiveBar

    args = [draw(length), draw(length), draw(length0)]
    mode = draw(name_of(("+-", "-+", "++", "--")))
    x, y = draw(point), draw(point)
    other = draw(st.sampled_from(["ik", "fk", "lci", "jacobian", "local", "classify", "scaled",
                                  "with_mode", "type2"]))
    extra = draw(mixed(st.floats(0.1, 10.0)))
    asm = draw(name_of(("up", "down")))

    def run():
        fb = FiveBar(*args, mode=mode)
        repr(fb)
        if other == "ik":
            fb.ik(x, y)
        elif other == "fk":
            fb.fk(x, y, assembly=asm)
        elif other == "lci":
            fb.lci(x, y)
        elif other == "jacobian":
            fb.jacobian(x, y)
        elif other == "local":
            fb.local_indices(x, y)
        elif other == "classify":
            fb.classify_singularity(x, y, tol=extra)
        elif other == "type2":
            fb.type2_function(x, y)
        elif other == "scaled":
            fb.scaled(extra)
        else:
            fb.with_mode(asm)
    return run


@target
def bipod(draw):
    from mechopt import Bipod

    b = draw(length)
    lo = draw(length)
    hi = draw(mixed(st.floats(0.05, 5.0).map(lambda d: (lo if isinstance(lo, float) else 1.0) + d)))
    q2 = [draw(st.one_of(st.none(), length)), draw(st.one_of(st.none(), length))]
    branch = draw(name_of(("up", "down", "full")))
    what = draw(st.sampled_from(["area", "tqi", "gtqi", "fk", "ik"]))
    method = draw(name_of(("exact", "raster")))
    step = draw(st.one_of(st.none(), mixed(st.floats(0.05, 1.0))))
    x, y = draw(point), draw(point)
    asm = draw(name_of(("up", "down")))
    limits = draw(st.booleans())

    def run():
        m = Bipod(b, lo, hi, *q2, branch=branch)
        repr(m)
        if what == "area":
            m.workspace_area()
        elif what == "tqi":
            m.tqi_integral()
        elif what == "gtqi":
            m.gtqi(method=method, step=step)
        elif what == "fk":
            m.fk(x, y, assembly=asm, limits=limits)
        else:
            m.ik(x, y)
    return run


@target
def biglide(draw):
    from mechopt import Biglide

    l1 = draw(length)
    l2 = draw(mixed(st.floats(0.05, 5.0).map(lambda d: (l1 if isinstance(l1, float) else 1.0) + d)))
    q = [draw(real), draw(real), draw(st.one_of(st.none(), real)), draw(st.one_of(st.none(), real))]
    mode = draw(name_of(("--", "++", "+-", "-+")))
    what = draw(st.sampled_from(["area", "tqi", "gtqi", "k_av", "fk", "summary"]))
    method = draw(name_of(("quad", "gauss", "raster")))
    step = draw(st.one_of(st.none(), mixed(st.floats(0.05, 1.0))))
    leg = draw(mixed(st.sampled_from([1, 2])))
    xr = [draw(st.one_of(st.none(), real)), draw(st.one_of(st.none(), real))]
    asm = draw(name_of(("up", "down")))

    def run():
        m = Biglide(l1, l2, *q, mode=mode)
        repr(m)
        if what == "area":
            m.workspace_area()
        elif what == "tqi":
            m.tqi_integral(method=method if method != "raster" else "quad")
        elif what == "gtqi":
            m.gtqi(method=method, step=step)
        elif what == "k_av":
            m.k_av(*xr, leg=leg)
        elif what == "fk":
            m.fk(xr[0] if xr[0] is not None else 0.0, q[0], assembly=asm)
        else:
            m.summary()
    return run


@target
def gantry(draw):
    from mechopt import Gantry

    d1 = draw(length)
    l = draw(mixed(st.floats(0.05, 5.0).map(lambda d: (d1 if isinstance(d1, float) else 1.0) + d)))
    stroke, q_min, l2, d2 = draw(length), draw(real), draw(length0), draw(length0)
    mode = draw(name_of(("--", "++", "-+", "+-")))
    tw = draw(st.one_of(st.none(), st.lists(real, min_size=0, max_size=5), mixed(st.none())))
    what = draw(st.sampled_from(["area", "k_av", "vor", "fk", "classify", "scaled", "task"]))
    xr = [draw(st.one_of(st.none(), real)), draw(st.one_of(st.none(), real))]
    leg = draw(mixed(st.sampled_from([1, 2])))
    reading = draw(name_of(("literal", "chebyshev", "mean")))
    asm = draw(name_of(("up", "down")))
    factor = draw(mixed(st.floats(0.001, 1000.0)))

    def run():
        g = Gantry(d1, l, stroke, q_min=q_min, l2=l2, d2=d2, mode=mode, task_workspace=tw)
        repr(g)
        if what == "area":
            g.workspace_area()
        elif what == "k_av":
            g.k_av(*xr, leg=leg, reading=reading)
        elif what == "vor":
            g.velocity_output_ratio(xr[0] if xr[0] is not None else 0.0, leg=leg)
        elif what == "fk":
            g.fk(xr[0] if xr[0] is not None else 0.0, xr[1] if xr[1] is not None else 0.0, assembly=asm)
        elif what == "classify":
            g.classify_singularity(xr[0] if xr[0] is not None else 0.0, 0.5)
        elif what == "scaled":
            g.scaled(factor)
        else:
            g.task_workspace_area()
    return run


@target
def gantry_synthesis(draw):
    from mechopt.mechanisms import gantry as G

    b, h = draw(length), draw(length)
    th = draw(mixed(st.floats(0.01, 0.78)))
    l2, d2, y0 = draw(length0), draw(length0), draw(real)
    deg = draw(mixed(st.floats(0.5, 44.5)))
    unit = draw(name_of(("mm", "m")))
    n = draw(count(st.integers(1, 8)))
    what = draw(st.sampled_from(["synthesis", "from_synthesis", "k_av_literal", "wu2008", "summary"]))

    def run():
        if what == "synthesis":
            G.dimensional_synthesis(b, h, th)
        elif what == "from_synthesis":
            G.Gantry.from_synthesis(b, h, th, l2=l2, d2=d2, task_y_min=y0)
        elif what == "k_av_literal":
            G.k_av_literal_of_design(th)
        elif what == "wu2008":
            G.wu2008_gantry(deg, unit=unit)
        else:
            G.Gantry.from_parameters(b=b * 100 if isinstance(b, float) else b,
                                     h=h * 100 if isinstance(h, float) else h,
                                     theta_1s_deg=math.degrees(th) if isinstance(th, float) else th,
                                     d2=d2, l2=l2, length_unit=unit).summary(n=n)
    return run


INERTIA_FIELDS = ("m11", "m21", "m12", "m22", "m13", "m23", "m4", "mN", "I12", "I22")
INERTIA_OPTIONAL = ("s12", "s22", "I4", "s4", "m5", "I5", "s5", "g")


@target
def gantry_inertia(draw):
    from mechopt.mechanisms.gantry_dynamics import GantryDynamics, GantryInertia

    kw = {f: draw(mixed(st.floats(0.0, 20.0), p_good=4)) for f in INERTIA_FIELDS}
    for f in INERTIA_OPTIONAL:
        if draw(st.integers(0, 3)) == 0:
            kw[f] = draw(st.one_of(st.none(), mixed(st.floats(0.0, 0.3))))
    if draw(st.integers(0, 9)) == 0:
        kw.pop(draw(st.sampled_from(INERTIA_FIELDS)))
        kw = {**kw, **{k: None for k in INERTIA_FIELDS if k not in kw}}
    what = draw(st.sampled_from(["dynamics", "eta_d", "kappa", "ellipse", "forces", "symmetric"]))
    n = draw(count(st.integers(1, 6)))
    region = draw(st.one_of(st.none(), st.lists(real, max_size=5), mixed(st.none())))
    x, y = draw(real), draw(real)
    kind = draw(name_of(("acceleration", "kinetic")))

    def run():
        inertia = GantryInertia(**kw)
        inertia.moving_mass
        if what == "symmetric":
            inertia.symmetric_variant()
            return
        dyn = GantryDynamics(_gantry_m(), inertia)
        if what == "eta_d":
            dyn.eta_d(region=region, n=n)
        elif what == "kappa":
            dyn.kappa_d_map(region=region, n=n)
        elif what == "ellipse":
            dyn.inertia_ellipse(x, y, kind=kind)
        elif what == "forces":
            dyn.driving_forces(x, y, 0.1, 0.2, 1.0, -1.0, gravity=True)
        else:
            dyn.mass_matrix(x, y)
    return run


@target
def dynamics_helpers(draw):
    from mechopt.mechanisms import gantry_dynamics as D

    box = draw(st.one_of(st.lists(real, min_size=3, max_size=5), mixed(st.none())))
    n = draw(count(st.integers(1, 8)))
    p0 = draw(st.one_of(st.tuples(real, real), mixed(st.none())))
    p1 = draw(st.one_of(st.tuples(real, real), mixed(st.none())))
    v, a = draw(length), draw(length)
    t = draw(st.one_of(real, st.lists(st.floats(0, 5), min_size=1, max_size=4)))
    what = draw(st.sampled_from(["rect", "profile", "trajectory"]))

    def run():
        if what == "rect":
            D.rectangle_rule(box, n)
        elif what == "profile":
            D.trapezoidal_profile(p0, p1, v, a, t)
        else:
            D.wu2008_trajectory(n if not isinstance(n, int) else n + 1)
    return run


ALL_PROBLEMS = FAST_PROBLEMS + SLOW_PROBLEMS


@target
def problems_get(draw):
    from mechopt.problems import available, get

    name = draw(name_of(ALL_PROBLEMS))

    def run():
        p = get(name)
        assert p.summary and "\n" not in p.summary
        if name == "wu2008":
            available()
    return run


@target
def runner_optimize(draw):
    from mechopt.problems import get
    from mechopt.run.runner import optimize

    name = draw(st.sampled_from(FAST_PROBLEMS))
    alg = draw(st.one_of(st.none(), name_of(("ga", "nsga2", "nsga3"))))
    pop = draw(count(st.integers(2, 4)))
    gen = draw(count(st.just(1)))
    seed = draw(mixed(st.integers(0, 2**32 - 1)))
    n_jobs = draw(count(st.just(1)))
    pop = 1 if pop is None else pop  # None means the problem's default size: a long run
    gen = 0 if gen is None else gen

    def run():
        optimize(get(name), alg, pop, gen, seed, n_jobs, None, None, progress=False, plot=False)
    return run


@target
def runner_helpers(draw):
    from mechopt.run import runner as R

    text = draw(st.one_of(st.sampled_from(WEIGHTS_GOOD + WEIGHTS_BAD), _ANY_TEXT,
                          st.sampled_from([None, 5, 0.5, b"0,1", ["0", "1"], "0:1:0.5:"])))
    alg = draw(name_of(("ga", "nsga2", "nsga3")))
    pop = draw(count(st.integers(2, 50)))
    n_obj = draw(st.sampled_from([1, 2, 3, 5]))
    what = draw(st.sampled_from(["weights", "weights", "algorithm"]))

    def run():
        if what == "weights":
            w = R.parse_weights(text)
            assert np.all((w >= 0) & (w <= 1)) and w.size >= 1
        else:
            R.make_algorithm(alg, pop, n_obj)
    return run


@target
def runner_sweep(draw):
    from mechopt.problems import get
    from mechopt.run.runner import sweep

    name = draw(st.sampled_from(FAST_2OBJ + ("wu2008-dynamic",)))
    weights = draw(st.one_of(st.lists(st.floats(0, 1), min_size=1, max_size=3),
                             st.lists(mixed(st.floats(0, 1)), max_size=3)))
    pop = draw(count(st.integers(2, 3)))
    gen = draw(count(st.just(1)))
    pop = 1 if pop is None else pop  # None means the problem's default size: a long run
    gen = 0 if gen is None else gen

    def run():
        sweep(get(name), weights, pop, gen, 1, 1, None, None, progress=False)
    return run


@target
def quadrature(draw):
    from mechopt.core.quadrature import disk_rule, grid_over

    radius = draw(mixed(st.floats(0.0, 3.0)))
    rule = draw(name_of(("area", "polar")))
    n_r, n_t = draw(small_int), draw(small_int)
    box = draw(st.one_of(st.lists(real, min_size=3, max_size=5), mixed(st.none())))
    step = draw(mixed(st.floats(0.05, 1.0)))
    what = draw(st.sampled_from(["disk", "grid"]))

    def run():
        if what == "disk":
            dx, dy, w = disk_rule(radius, rule, n_r, n_t)
            assert np.all(np.isfinite(dx)) and abs(w.sum() - 1) < 1e-9
        else:
            g = grid_over(box, step)
            g.points()
    return run


@target
def workspace(draw):
    from mechopt.analysis import workspace as W

    what = draw(st.sampled_from(["mic", "usable", "gcw", "square", "ranges", "clearance"]))
    method = draw(name_of(("auto", "explicit", "rays")))
    n_y = draw(small_int)
    tol = draw(mixed(st.floats(1e-6, 1e-2)))
    step = draw(mixed(st.floats(0.05, 0.2)))
    center = draw(st.one_of(st.none(), st.tuples(real, mixed(st.floats(1.0, 2.0))), mixed(st.none())))
    gamma = draw(unit_interval)
    cx, cy, r = draw(real), draw(real), draw(length0)

    def run():
        fb = _five_bar()
        if what == "mic":
            W.mic(fb, method, n_y=n_y, tol=tol)
        elif what == "usable":
            W.usable_region(fb, step=step, center=center)
        elif what == "gcw":
            W.gcw(fb, gamma, _usable())
        elif what == "square":
            W.largest_square(W.gcw(fb, gamma, _usable()))
        elif what == "ranges":
            W.joint_ranges(fb, W.gcw(fb, gamma, _usable()))
        else:
            W.type2_clearance(fb, cx, cy, r, n_phi=8, n_r=8, n_refine=4)
    return run


@target
def performance(draw):
    from mechopt.analysis import performance as P
    from mechopt.analysis.evaluate import evaluate

    what = draw(st.sampled_from(["global", "disk_mean", "max_lci", "region", "evaluate"]))
    quad = draw(name_of(("area", "polar")))
    n_r, n_t = draw(small_int), draw(small_int)
    cy, radius = draw(real), draw(mixed(st.floats(0.0, 1.0)))
    iters = draw(count(st.integers(0, 5)))
    gamma = draw(unit_interval)
    step = draw(st.one_of(st.none(), mixed(st.floats(0.1, 0.3))))
    if step is None:
        step = 0.1  # the default raster (length_scale/400) takes ~1 s

    def run():
        fb = _five_bar()
        if what == "global":
            P.global_indices(fb, quad, mic=_mic(), n_r=n_r, n_theta=n_t)
        elif what == "disk_mean":
            P.disk_mean(fb, cy, radius, quad, n_r=n_r, n_theta=n_t)
        elif what == "max_lci":
            P.max_lci(fb, cy, radius, n_r=n_r, n_theta=n_t, iters=iters)
        elif what == "region":
            P.region_indices(fb, _usable())
        else:
            evaluate(fb, quadrature=quad, gamma=gamma, step=step)
    return run


#: admissible lengths from one end of the range to the other (validation.LENGTH_MIN/MAX)
EXTREME_LENGTHS = [1e-12, 3.7e-12, 1e-6, 0.5, 1.0, 1.9, 1e6, 4.2e11, 1e12]
#: what an error of ``evaluate`` may not start with: quantities the user never passed
INTERNAL_NAMES = ("step", "center_y", "center ", "radius", "box", "factor", "tol", "x and y")


@target
def extreme_designs(draw):
    """Designs with lengths anywhere in [1e-12, 1e12], mixed ones included, evaluated in
    full: they return, or raise a ValueError that names the design (its class and
    inputs) rather than an internal quantity."""
    from mechopt import Biglide, Bipod, FiveBar
    from mechopt.analysis.evaluate import evaluate
    from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar

    what = draw(st.sampled_from(["five-bar", "five-bar", "five-bar", "bipod", "biglide", "asymmetric"]))
    lengths = [draw(st.sampled_from(EXTREME_LENGTHS)) for _ in range(5)]
    scale = draw(st.sampled_from(EXTREME_LENGTHS))
    mode = draw(st.sampled_from(["+-", "-+", "++", "--"]))
    r3 = draw(st.sampled_from([0.0, 1e-300, *EXTREME_LENGTHS]))
    coarse = draw(st.booleans())

    def make():
        a, b, c, d, e = lengths
        if what == "five-bar":
            return FiveBar(a, b, r3, mode)
        if what == "bipod":
            return Bipod(a, b, b + c)  # strokes [b, b + c]: may round to b (then refused)
        if what == "biglide":  # one size (mixed sizes: see the report, quad warns)
            return Biglide(scale, scale * (1.0 + b / 2.0), -scale * min(c, 1.9), scale * min(d, 1.9))
        # the asymmetric five-bar with its legs of one size (whose workspaces meet)
        return AsymmetricFiveBar(scale, 1.5 * scale, 0.8 * scale, 1.7 * scale, 0.5 * scale)

    def run():
        mech = make()
        kw = {}
        if coarse and mech.disk_indices:  # a coarse raster keeps most examples cheap
            kw["step"] = mech.length_scale / 40
        try:
            evaluate(mech, **kw)
        except ValueError as exc:
            msg = str(exc)
            assert not msg.startswith(INTERNAL_NAMES), f"{mech!r}: internal limit: {msg}"
            assert repr(mech).split("(")[0] + "(" in msg, f"{mech!r}: the error does not name it: {msg}"
            raise
    return run


@target
def atlas(draw):
    from mechopt.mechanisms.five_bar.batch import evaluate_designs
    from mechopt.run import atlas as A

    what = draw(st.sampled_from(["step", "indices", "grid", "compute", "run", "evaluate"]))
    step = draw(st.one_of(st.sampled_from(STEPS_GOOD + STEPS_BAD), mixed(st.floats(0.25, 0.5))))
    indices = draw(st.one_of(st.sampled_from(INDEX_GOOD + INDEX_BAD), st.lists(name_of(("gci", "mci", "gvi")),
                                                                                 max_size=3),
                             mixed(st.just("gci"))))
    quad = draw(name_of(("area", "polar")))
    mode = draw(name_of(("+-", "-+", "++", "--")))
    n_jobs = draw(count(st.just(1)))
    chunk = draw(st.one_of(st.none(), count(st.integers(1, 50))))
    where = draw(st.one_of(st.none(), where_text()))
    r = [draw(length), draw(length), draw(length0)]
    cheap = isinstance(step, (str, float)) and _as_float(step) is not None and _as_float(step) >= 0.25

    def run():
        if what == "step":
            A.check_step(step)
        elif what == "indices":
            A.parse_indices(indices)
            A.index_columns(indices)
        elif what == "grid":
            A.design_grid(step if cheap else "x")
        elif what == "compute":
            A.compute_atlas(step if cheap else 0, indices, quad, mode, n_jobs=n_jobs, chunk_size=chunk)
        elif what == "evaluate":
            evaluate_designs(*r, quadrature=quad, mode=mode)
        else:
            out = _CACHE["root"] / f"atlas{next(_counter)}"
            A.run_atlas(out, step if cheap else 0, indices, quad, mode, n_jobs=n_jobs, where=where,
                        figures=False, chunk_size=chunk, verbose=False)
    return run


@target
def conditions(draw):
    import pandas as pd

    from mechopt.core.conditions import parse_condition

    text = draw(st.one_of(where_text(), mixed(st.just("gci > 0.5"))))
    names = draw(st.one_of(st.none(), st.just(WHERE_NAMES)))

    def run():
        cond = parse_condition(text, names=names)
        str(cond)
        table = pd.DataFrame({n: np.array([0.1, np.nan, 0.9]) for n in WHERE_NAMES})
        mask = cond.evaluate(table) if names is not None or cond.names <= set(WHERE_NAMES) else None
        if mask is not None:
            assert mask.dtype == bool and mask.shape == (3,)
    return run


@target
def parallel(draw):
    from mechopt.run import parallel as Pa

    n = draw(count(st.integers(1, 4)))
    seq = draw(st.lists(st.integers(), max_size=6))
    # never a client in this process (see DASK_ADDRESSES): a bad address or a bad timeout
    address = draw(st.sampled_from(DASK_ADDRESSES + DASK_REJECTED + (None, 5, b"tcp://a:1", ["tcp://a:1"], 1.5)))
    timeout = draw(st.sampled_from([0.0, -1.0, NAN, INF, -INF, "x", None, "", 1e999, [1.0]]) if
                   address in DASK_ADDRESSES else mixed(st.floats(0.05, 0.2)))
    what = draw(st.sampled_from(["chunks", "map", "connect"]))

    def run():
        if what == "chunks":
            Pa.chunks(seq, n)
        elif what == "map":
            Pa.parallel_map(abs, seq, n_jobs=n if not isinstance(n, int) or n < 1 else 1)
        else:
            client = Pa.connect(address, timeout=timeout)
            client.close()
    return run


@target
def reproduce(draw):
    from mechopt.workflows.reproduce import reproduce as run_reproduce

    paper = draw(st.one_of(st.sampled_from(["", "nope", "LIU2006", "le 2013", None, 5, "al", "\udcff"]),
                           _ANY_TEXT))
    quick = draw(st.booleans())

    def run():
        if paper in ("le2013", "stan2008", "liu2006", "wu2008", "all"):
            return  # a real reproduction takes minutes
        out = _CACHE["root"] / f"never{next(_counter)}"
        try:
            run_reproduce(paper, out=out, quick=quick, log=lambda m: None)
        finally:
            assert not out.exists()
    return run


def check_api(run, label):
    with strict_warnings():
        try:
            with no_hang():
                run()
            event(f"{label}: returned")
        except ValueError as exc:
            event(f"{label}: ValueError")
            msg = str(exc)
            assert msg.strip(), f"{label}: empty ValueError message"
            assert "\n" not in msg and "\r" not in msg, f"{label}: multi-line message {msg!r}"


@fuzz(N_API // CI_SHARE)
@given(st.data())
def test_api_fuzz(fuzz_root, data):
    _api_case(fuzz_root, data)


@pytest.mark.slow
@fuzz(N_API)
@given(st.data())
def test_api_fuzz_full(fuzz_root, data):
    _api_case(fuzz_root, data)


def _api_case(fuzz_root, data):
    _CACHE["root"] = fuzz_root  # where targets may write
    _SENSIBLE[0] = data.draw(st.sampled_from([20, 20, 19, 18, 12]))
    label = data.draw(st.sampled_from(sorted(API_TARGETS)))
    run = API_TARGETS[label](data.draw)
    check_api(run, label)


# --------------------------------------------------------------------------
# each named kind of bad input gives a ValueError that names the parameter
# --------------------------------------------------------------------------
def _named_cases():
    from mechopt import Biglide, Bipod, FiveBar, Gantry
    from mechopt.run.atlas import check_step, parse_indices
    from mechopt.core.conditions import parse_condition
    from mechopt.mechanisms.gantry_dynamics import GantryInertia
    from mechopt.problems import get
    from mechopt.core.quadrature import disk_rule, grid_over
    from mechopt.run.runner import make_algorithm, parse_weights
    from mechopt.analysis.workspace import gcw

    masses = dict(zip(INERTIA_FIELDS, [1.0] * 10))
    cases = []
    for bad in (0.0, -1.0, NAN, INF, 1e300, 1e-300, "x", None, 10**400):
        cases += [(lambda b=bad: FiveBar(b, 1, 1), "r1"),
                  (lambda b=bad: FiveBar(1, 1.5, 0.5).scaled(b), "factor"),
                  (lambda b=bad: Bipod(1, b, 2), "q1_min"),
                  (lambda b=bad: Biglide(1, b, 0, 1), "l2"),
                  (lambda b=bad: Gantry(1, 2, b), "stroke")]
    for bad in (-1.0, NAN, INF, "x"):
        cases += [(lambda b=bad: GantryInertia(**{**masses, "m4": b}), "m4")]
    cases += [(lambda: GantryInertia(**{**masses, "mN": None}), "mN")]
    for bad in ("x", None, "", "UP"):
        cases += [(lambda b=bad: FiveBar(1, 1.5, 0.5, mode=b), "mode"),
                  (lambda b=bad: Bipod(1, 1, 2, branch=b), "branch"),
                  (lambda b=bad: FiveBar(1, 1.5, 0.5).fk(0.1, 0.2, assembly=b), "assembly"),
                  (lambda b=bad: disk_rule(1.0, b), "quadrature"),
                  (lambda b=bad: get(b), "problem"),
                  (lambda b=bad: make_algorithm(b, 10, 2), "algorithm")]
    for bad in (0.0, 1.0, -0.5, NAN, "x", None):
        cases += [(lambda b=bad: gcw(FiveBar(1, 1.5, 0.5), b), "gamma")]
    for bad in (0.0, -0.1, NAN, None, 1e-300):
        cases += [(lambda b=bad: check_step(b), "step"),
                  (lambda b=bad: grid_over((0, 1, 0, 1), b), "step")]
    for bad in ("2", "-0.5", "0:1:0", "nan", "", None, "0:1:1e-9"):
        cases += [(lambda b=bad: parse_weights(b), "weights")]
    for bad in ("r_mic >", "and and", "__import__('os')", "gci > 0.5 or", "gci > é", None,
                "not " * 3000 + "gci > 0"):
        cases += [(lambda b=bad: parse_condition(b, names=("gci", "r_mic")), "where")]
    for bad in (None, 5, "", "GCI"):
        cases += [(lambda b=bad: parse_indices(b), "index")]
    return cases


def test_named_bad_inputs_raise_value_error_naming_the_parameter():
    failures = []
    for make, name in _named_cases():
        try:
            with strict_warnings():
                make()
        except ValueError as exc:
            msg = str(exc)
            if name not in msg or "\n" in msg:
                failures.append(f"{name}: {msg!r}")
        except Exception as exc:  # noqa: BLE001
            failures.append(f"{name}: {type(exc).__name__}: {exc}")
        else:
            failures.append(f"{name}: no error")
    assert not failures, "\n".join(failures)


def test_optimize_pop_and_gen_limits():
    from mechopt.problems import get
    from mechopt.run.runner import optimize

    for pop, gen in ((1, 1), (0, 1), (2, 0), (2, -1), ("x", 1), (2, "y")):
        with pytest.raises(ValueError, match="pop|gen"):
            optimize(get("wu2008"), None, pop, gen, 1, 1, None, None, progress=False, plot=False)
