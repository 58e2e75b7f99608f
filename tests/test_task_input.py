"""Task input that must never hang, misread or take minutes: the polygon simplicity
test (against shapely), the points/path file reader (strict: BOM, header, delimiter and
decimal comma, a line that does not parse), FIFOs and devices refused."""
from __future__ import annotations

import os
import threading

import numpy as np
import pytest
from shapely.geometry import LinearRing

from mechopt.analysis.task import Task, _polygon_simple, parse_task, read_points
from mechopt.core import validation as _v


def test_polygon_simplicity_agrees_with_shapely():
    rng = np.random.default_rng(7)
    simple = 0
    for k in range(300):
        n = int(rng.integers(3, 14))
        if k % 2:  # star-shaped about the origin: simple
            t = np.sort(rng.uniform(0, 2 * np.pi, n))
            v = np.c_[np.cos(t), np.sin(t)] * rng.uniform(0.5, 1.5, (n, 1))
        else:  # random vertices: mostly self-intersecting
            v = rng.uniform(-1, 1, (n, 2))
        assert _polygon_simple(v) == LinearRing(v).is_simple, v
        simple += LinearRing(v).is_simple
    assert 100 < simple < 300  # both kinds were tested


def test_a_large_polygon_is_checked_and_a_larger_one_refused():
    t = np.linspace(0, 2 * np.pi, 2001)[:-1]
    r = 1 + 0.3 * np.sin(7 * t)
    assert Task.polygon(np.c_[r * np.cos(t), r * np.sin(t)] * 50 + [0, 200]).kind == "polygon"
    bow = np.r_[np.c_[r * np.cos(t), r * np.sin(t)][:1000], [[0.0, 0.0], [2.0, 2.0]]]  # a crossing edge
    assert not _polygon_simple(bow) and LinearRing(bow).is_simple is False
    n = _v.POLYGON_VERTICES_MAX + 1
    t = np.linspace(0, 2 * np.pi, n + 1)[:-1]
    with pytest.raises(ValueError, match=f"polygon has {n} vertices, more than {_v.POLYGON_VERTICES_MAX}"):
        Task.polygon(np.c_[np.cos(t), np.sin(t)])


@pytest.mark.parametrize("text, expected", [
    ("x,y\n-20,120\n150,500\n", [[-20, 120], [150, 500]]),
    ("\ufeffx,y\n1,2\n3,4\n", [[1, 2], [3, 4]]),                       # a BOM
    ("-20,120;150,500\n1,5;2\n", [[-20.12, 150.5], [1.5, 2]]),          # ';' with decimal commas
    ("x\ty\n1.5\t2\n", [[1.5, 2]]),                                     # tabs
    ("# comment\n\n1e2,2E-1\n", [[100, 0.2]]),
])
def test_points_files_are_read_strictly(tmp_path, text, expected):
    f = tmp_path / "p.csv"
    f.write_text(text, encoding="utf-8")
    assert np.allclose(read_points(f, "--task points:"), expected, rtol=0, atol=1e-12)


@pytest.mark.parametrize("text, line", [
    ("1O,20\n3,4\n", 1),        # a typo on the first line is no header
    ("1,2\n3;4\n", 2),          # another delimiter
    ("1,2,3\n", 1),             # three columns
    ("1,2\nnan,4\n", 2),        # not finite
    ("x,y\n1,2\nfoo,bar\n", 3),
])
def test_a_line_that_does_not_parse_is_named(tmp_path, text, line):
    f = tmp_path / "p.csv"
    f.write_text(text)
    with pytest.raises(ValueError, match=f"line {line} of"):
        parse_task(f"points:{f}")


def test_fifos_and_devices_are_refused_without_reading(tmp_path):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    result = {}

    def call():
        try:
            parse_task(f"path:{fifo}")
        except ValueError as exc:
            result["error"] = str(exc)

    th = threading.Thread(target=call, daemon=True)
    th.start()
    th.join(20)
    assert not th.is_alive(), "reading a FIFO hung"
    assert "--task path:" in result["error"]
    with pytest.raises(ValueError, match="--task points:"):
        parse_task("points:/dev/zero")
    big = tmp_path / "big.csv"
    with open(big, "wb") as fh:
        fh.truncate(_v.POINTS_FILE_BYTES + 1)  # sparse: nothing is read
    with pytest.raises(ValueError, match="--task points:"):
        parse_task(f"points:{big}")
