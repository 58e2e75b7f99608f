"""``mechopt explore``: the interactive page of a design run, an optimisation run and an atlas.

The numbers the page draws are checked against independent derivations: the legs'
lengths measured on the drawn joints against the design's lengths in front.csv, the
platform at slider position k against the point at arc-length fraction k/N of the
placed rectangle walked edge by edge here, an atlas region's size against what
``mechopt atlas --where`` prints. The browser tests drive the system Chromium exactly as
tests/test_report.py does (its fixtures; they skip, saying why, only where no browser,
driver or selenium is installed) and save their screenshots into ``$CI_ARTIFACTS``.
"""
from __future__ import annotations

import base64
import gzip
import json
import math
import re
import threading
import time
import urllib.request

import numpy as np
import pandas as pd
import pytest

from mechopt.cli import main
from mechopt.workflows.explore import N_POSES, build_page, page_data, serve, write_page

# the browser, its skip rules and the artefact folder of the report's browser test
from test_report import _browser, artifacts, browser  # noqa: F401

#: the task of the design run: a 100 x 60 mm rectangle about (0, 180), placed along y
W, H = 100.0, 60.0
WHERE = "r_mic > 0.8 and gci > 0.5"


@pytest.fixture(scope="module")
def design_run(tmp_path_factory):
    """A small design run (about 5 s): seven certified designs of a free-y placement."""
    out = tmp_path_factory.mktemp("design")
    assert main(["design", "five-bar", "--task", f"rect:{W:g},{H:g}@0,180", "--min-lci", "0.3",
                 "--place", "free-y", "--min-length", "60", "--max-length", "200", "--gen", "3",
                 "--pop", "8", "--no-polish", "--seed", "1", "--out", str(out)]) == 0
    return out


@pytest.fixture(scope="module")
def atlas_run(tmp_path_factory):
    """A step-0.1 GCI atlas (344 designs) with the count ``mechopt atlas --where`` prints."""
    import contextlib
    import io

    out = tmp_path_factory.mktemp("atlas")
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["atlas", "five-bar", "--step", "0.1", "--index", "gci", "--n-jobs", "1", "--no-figures",
                     "--where", WHERE, "--out", str(out)]) == 0
    m = re.search(r"region '(.*)': (\d+) designs", buf.getvalue())
    assert m and m.group(1) == WHERE
    return out, int(m.group(2))


def _rect_point(cx, cy, t):
    """The point at arc-length fraction ``t`` of the W x H rectangle about ``(cx, cy)``,
    counter-clockwise from its lower-left corner (walked edge by edge)."""
    corners = [(cx - W / 2, cy - H / 2), (cx + W / 2, cy - H / 2), (cx + W / 2, cy + H / 2), (cx - W / 2, cy + H / 2)]
    s = t * 2 * (W + H)
    for k in range(4):
        (x0, y0), (x1, y1) = corners[k], corners[(k + 1) % 4]
        L = math.hypot(x1 - x0, y1 - y0)
        if s <= L:
            return x0 + (x1 - x0) * s / L, y0 + (y1 - y0) * s / L
        s -= L
    return corners[0]


def _check_legs(chains, bases, row, platform):
    """The drawn five-bar is the design of ``row``: base joints at (-r3, 0), (r3, 0), cranks
    of length r1, distal links of length r2 meeting at the platform."""
    r1, r2, r3 = (float(row[k]) for k in ("r1", "r2", "r3"))
    tol = 2e-5 * max(r1, r2, r3)
    assert len(chains) == 2
    for (a, b, p), bx in zip(chains, (-r3, r3)):
        assert a == pytest.approx((bx, 0.0), abs=tol)
        assert math.dist(a, b) == pytest.approx(r1, abs=tol)
        assert math.dist(b, p) == pytest.approx(r2, abs=tol)
        assert p == pytest.approx(platform, abs=tol)
    assert np.ravel(bases).tolist() == pytest.approx([-r3, 0.0, r3, 0.0], abs=tol)


def _payload(html):
    """The data a page embeds, inflated as the browser does."""
    m = re.search(r'id="payload-gz">([^<]*)<', html)
    return json.loads(gzip.decompress(base64.b64decode(m.group(1))))


# --------------------------------------------------------------------------- the data

def test_design_drawings(design_run):
    """Every front design at every slider position: the legs have the design's lengths
    and the platform sits on the placed rectangle at uniform arc length."""
    front = pd.read_csv(design_run / "front.csv")
    data = page_data(design_run)
    assert data["kind"] == "design" and len(data["designs"]) == len(front) > 1
    assert data["chosen"] == json.loads((design_run / "design.json").read_text())["index"]
    assert data["path_t"] == pytest.approx(np.arange(N_POSES) / N_POSES, abs=1e-6)
    assert data["margins"] == [c for c in front.columns if c.startswith("margin_")] and data["margins"]
    assert data["gamma"] == 0.3
    for i, row in front.iterrows():
        g = data["designs"][i]
        for k in range(N_POSES):
            p = _rect_point(row["task_x"], row["task_y"], k / N_POSES)
            assert (g["path"]["x"][k], g["path"]["y"][k]) == pytest.approx(p, abs=1e-5 * 200)
            pose = g["poses"][k]
            assert pose is not None  # a certified design reaches its whole task
            _check_legs(pose["chains"], pose["bases"], row, p)
        # the outlines are drawn; the reachable boundary encloses the task
        assert len(g["outlines"]["reach"]["x"]) > 20 and len(g["outlines"]["gcw"]["x"]) > 20
        assert min(g["task"]["y"]) == pytest.approx(row["task_y"] - H / 2, abs=1e-5 * 200)


def test_page_is_self_contained(design_run, tmp_path):
    path = write_page(design_run, out=tmp_path / "page.html")
    html = path.read_text()
    html.encode("ascii")
    assert not re.search(r"<script[^>]*\bsrc=", html, re.I)
    assert not re.search(r"<link[^>]*stylesheet", html, re.I)
    assert not re.search(r"""(?:src|href)\s*=\s*["']?\s*(?:https?:)?//""", html, re.I)
    assert _payload(html)["front"] == page_data(design_run)["front"]
    lib = re.search(r'id="plotly-gz">([^<]*)<', html).group(1)
    assert b"plotly" in gzip.decompress(base64.b64decode(lib))[:2000].lower()
    assert path.stat().st_size < 5e6
    assert [p.name for p in tmp_path.iterdir()] == ["page.html"]  # atomic: no temporary left


def test_atlas_regions(atlas_run):
    out, printed = atlas_run
    table = pd.read_csv(out / "atlas.csv")
    data = page_data(out, where=(WHERE, "gci > 0.6 or r3 < 0.2"))
    r0, r1 = data["regions"]
    assert r0["count"] == printed == len(pd.read_csv(out / "region.csv")) == len(r0["index"]) > 0
    # the second condition, counted here without the parser
    other = ((table["gci"] > 0.6) | (table["r3"] < 0.2)).to_numpy()
    assert r1["index"] == np.flatnonzero(other).tolist()
    assert len(r0["outline"]["x"]) > 4 and data["n"] == len(table)
    assert data["table"]["r1"] == pytest.approx(table["r1"].tolist())


def test_readme_atlas_below_5_mb(tmp_path):
    """The step-0.01 atlas of the README (33 824 designs, every index): its page stays
    below 5 MB. Smooth functions of the design with random digits (no pattern for gzip
    to find in the digits) stand for the real indices."""
    from mechopt.run.atlas import DEFAULT_INDICES, design_grid, index_columns

    grid = design_grid(0.01)
    rng = np.random.default_rng(1)
    for k, c in enumerate(index_columns(DEFAULT_INDICES)):
        smooth = 1.0 + np.sin((k + 1) * grid["r1"]) * np.cos(grid["r3"] + k)
        grid[c] = smooth * (1.0 + 1e-3 * rng.uniform(size=len(grid)))
    assert len(grid) == 33824
    grid.to_csv(tmp_path / "atlas.csv", index=False, float_format="%.10g")
    (tmp_path / "atlas.json").write_text(json.dumps({"mechanism": "five-bar", "step": 0.01}))
    size = write_page(tmp_path, where=("r_mic > 0.8 and gci > 0.6",)).stat().st_size
    print(f"README atlas page: {size / 1e6:.2f} MB")
    assert size < 5e6


def test_optimisation_page(tmp_path):
    out = tmp_path / "sweep"
    assert main(["sweep", "wu2008", "--weights", "0:1:0.5", "--pop", "6", "--gen", "3", "--n-jobs", "1",
                 "--out", str(out)]) == 0
    data = page_data(out)
    history = pd.read_csv(out / "history.csv")
    assert data["kind"] == "optimize" and data["objectives"] == [c[5:] for c in history if c.startswith("best_")]
    assert data["history"]["hypervolume"] == pytest.approx(history["hypervolume"].tolist())
    assert len(data["sweep"]["weight"]) == 3
    html = build_page(out)
    assert _payload(html)["kind"] == "optimize"


def test_cli_and_errors(design_run, atlas_run, tmp_path, capsys):
    page = tmp_path / "sub" / "p.html"
    assert main(["explore", str(design_run), "--out", str(page)]) == 0
    assert capsys.readouterr().out.strip() == f"explore: {page.resolve()}"
    cases = [([str(tmp_path / "absent")], "DIR must be a run folder"),
             ([str(tmp_path / "sub")], "holds no front.csv or atlas.csv"),
             ([str(design_run), "--where", "gci > 1"], "--where applies to an atlas folder"),
             ([str(atlas_run[0]), "--where", "gci >> 1"], "--where"),
             ([str(atlas_run[0]), "--where", "nope > 1"], "nope"),
             ([str(design_run), "--out", str(tmp_path)], "--out must name an HTML file"),
             ([str(design_run), "--port", "70000"], "--port")]
    for args, words in cases:
        assert main(["explore", *args]) == 2, args
        err = capsys.readouterr().err
        assert err.startswith("mechopt: error:") and err.count("\n") == 1 and words in err, err
    assert sorted(p.name for p in (tmp_path / "sub").iterdir()) == ["p.html"]


def test_serve(design_run, tmp_path, capsys):
    path = write_page(design_run, out=tmp_path / "p.html")
    started = {}
    th = threading.Thread(target=serve, args=(path,), kwargs={"open_browser": False,
                                                             "ready": lambda s: started.setdefault("s", s)})
    th.start()
    for _ in range(100):
        if "s" in started:
            break
        time.sleep(0.05)
    server = started["s"]
    try:
        host, port = server.server_address[:2]
        assert host == "127.0.0.1"
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=10) as r:
            assert r.read() == path.read_bytes()
        with pytest.raises(urllib.error.HTTPError):
            urllib.request.urlopen(f"http://127.0.0.1:{port}/other", timeout=10)
    finally:
        server.shutdown()
        th.join(10)
    assert not th.is_alive()
    assert f"serving http://127.0.0.1:{port}/" in capsys.readouterr().out


# --------------------------------------------------------------------------- in a real browser

def _load(browser, path, timeout=60):
    browser.get(path.resolve().as_uri())
    t0 = time.time()
    while time.time() - t0 < timeout:
        if browser.execute_script("return document.body.getAttribute('data-ready')") == "1":
            return browser.execute_script("return window.mechoptTimings")
        time.sleep(0.1)
    raise AssertionError(browser.execute_script("return document.getElementById('status').textContent"))


def _offline(browser):
    """Every resource the page loaded is inline (data:), the page itself a file."""
    names = browser.execute_script(
        "return performance.getEntries().filter(function (e) { return e.name; })"
        ".map(function (e) { return e.entryType + ' ' + e.name; })")
    fetched = [n for n in names if n.split(" ", 1)[0] in ("resource", "navigation")]
    assert any(n.startswith("navigation file:") for n in fetched), names
    assert all(n.startswith("navigation file:") or n.split(" ", 1)[1].startswith("data:") for n in fetched), fetched


def _no_console_error(browser):
    severe = [e for e in browser.get_log("browser") if e.get("level") == "SEVERE"]
    assert severe == []


def _trace(browser, div, name):
    return browser.execute_script(
        "var name = arguments[1];"
        "var t = document.getElementById(arguments[0]).data.filter(function (t) { return t.name === name; })[0];"
        "return t ? [t.x, t.y] : null;", div, name)


def _click_point(browser, div, x, y):
    """A real mouse click on the data point ``(x, y)`` of the Plotly plot ``div``."""
    from selenium.webdriver.common.action_chains import ActionChains

    el = browser.find_element("id", div)
    browser.execute_script("arguments[0].scrollIntoView({block: 'center'});", el)
    dx, dy = browser.execute_script(
        "var gd = arguments[0], xa = gd._fullLayout.xaxis, ya = gd._fullLayout.yaxis, r = gd.getBoundingClientRect();"
        "return [xa._offset + xa.l2p(arguments[1]) - r.width / 2, ya._offset + ya.l2p(arguments[2]) - r.height / 2];",
        el, x, y)
    ActionChains(browser).move_to_element_with_offset(el, int(round(dx)), int(round(dy))).pause(0.2).click().perform()


def _wait_drawn(browser, i, k, timeout=20):
    """Until the mechanism plot shows design ``i`` at slider position ``k``."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        if browser.execute_script("var d = window.mechoptExplorer.current.drawn; return d ? [d.i, d.k] : null;") == [i, k]:
            return
        time.sleep(0.05)
    raise AssertionError(f"design {i} at position {k} not drawn: "
                         f"{browser.execute_script('return window.mechoptExplorer.current')}")


def _chains(xy):
    """Polylines of a trace with None separators."""
    out, cur = [], []
    for x, y in zip(*xy):
        if x is None:
            if cur:
                out.append(cur)
            cur = []
        else:
            cur.append((x, y))
    return out + ([cur] if cur else [])


def test_design_page_in_browser(browser, design_run, artifacts, tmp_path):
    from selenium.webdriver.common.keys import Keys

    front = pd.read_csv(design_run / "front.csv")
    path = write_page(design_run, out=tmp_path / "explore-design.html")
    timings = _load(browser, path)
    chosen = json.loads((design_run / "design.json").read_text())["index"]
    assert browser.execute_script("return window.mechoptExplorer.current.i") == chosen
    # the design farthest (in the plot's normalised axes) from the others and not the chosen one
    F = front[["size", "min-lci"]].to_numpy(float)
    Z = (F - F.min(0)) / np.ptp(F, axis=0)
    D = np.sqrt(((Z[:, None] - Z[None]) ** 2).sum(-1)) + np.eye(len(Z)) * 9
    D[chosen] = -1
    j = int(np.argmax(D.min(1)))
    _click_point(browser, "front", F[j, 0], F[j, 1])
    _wait_drawn(browser, j, 0)
    shown = browser.execute_script(
        "var o = {}; document.querySelectorAll('#design-vars td[data-value]').forEach(function (td) {"
        "  o[td.getAttribute('data-name')] = Number(td.getAttribute('data-value')); }); return o;")
    for k in ("r1", "r2", "r3", "task_y", "size", "min-lci"):
        assert shown[k] == front.loc[j, k]  # exactly front.csv's number
    assert browser.find_element("css selector", '#design-vars td[data-name="r1"]').text == f"{front.loc[j, 'r1']:.6g}"
    legs = _chains(_trace(browser, "mech", "legs"))
    bases = list(zip(*_trace(browser, "mech", "base joints")))
    p0 = _rect_point(front.loc[j, "task_x"], front.loc[j, "task_y"], 0.0)
    _check_legs([legs[0], legs[1]], bases, front.loc[j], p0)
    # the slider, by the keyboard: k steps along the boundary
    slider = browser.find_element("id", "pose")
    k = 23
    slider.send_keys(*([Keys.ARROW_RIGHT] * k))
    assert int(slider.get_attribute("value")) == k
    _wait_drawn(browser, j, k)  # the page draws the latest position once per animation frame
    px, py = _trace(browser, "mech", "platform")
    p = _rect_point(front.loc[j, "task_x"], front.loc[j, "task_y"], k / N_POSES)
    assert (px[0], py[0]) == pytest.approx(p, abs=1e-3)
    legs = _chains(_trace(browser, "mech", "legs"))
    _check_legs([legs[0], legs[1]], bases, front.loc[j], p)
    _no_console_error(browser)
    _offline(browser)
    browser.execute_script("window.scrollTo(0, 0);")
    shot = artifacts / "explore-design.png"
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000
    print(f"design page {path.stat().st_size / 1e6:.2f} MB, ready in {timings['drawn'] / 1000:.1f} s; {shot}")


def test_atlas_page_in_browser(browser, atlas_run, artifacts, tmp_path):
    out, printed = atlas_run
    table = pd.read_csv(out / "atlas.csv")
    path = write_page(out, out=tmp_path / "explore-atlas.html", where=(WHERE,))
    timings = _load(browser, path)
    region = browser.find_element("css selector", "#regions p.region")
    assert int(region.get_attribute("data-count")) == printed
    assert f": {printed} of {len(table)} designs" in region.text
    xs, ys = _trace(browser, "atlas", f"where {WHERE} ({printed})")
    assert len(xs) == printed
    # a click on a design shows its row
    i = int(np.flatnonzero(table["r3"].to_numpy() == 0.5)[3])
    _click_point(browser, "atlas", table.loc[i, "s"], table.loc[i, "t"])
    time.sleep(0.3)
    assert browser.execute_script("return window.mechoptExplorer.current.i") == i
    shown = browser.execute_script(
        "var o = {}; document.querySelectorAll('#atlas-design td[data-value]').forEach(function (td) {"
        "  o[td.getAttribute('data-name')] = Number(td.getAttribute('data-value')); }); return o;")
    for c in ("r1", "r2", "r3", "gci", "r_mic"):
        assert shown[c] == pytest.approx(table.loc[i, c], rel=1e-5)
    _no_console_error(browser)
    _offline(browser)
    browser.execute_script("window.scrollTo(0, 0);")
    shot = artifacts / "explore-atlas.png"
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000
    print(f"atlas page {path.stat().st_size / 1e6:.2f} MB, ready in {timings['drawn'] / 1000:.1f} s; {shot}")
