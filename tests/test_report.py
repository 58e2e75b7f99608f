"""``mechopt report``: the HTML page of a reproduction, read as text and in a real browser.

The browser tests drive the system Chromium with selenium and the system chromedriver
(nothing is downloaded); they skip, saying why, only where no browser, driver or
selenium is installed (``.ci/run`` installs them). The screenshots go to the folder in
``$CI_ARTIFACTS`` when it is set (a CI artefact), else to the test's tmp folder.
"""
from __future__ import annotations

import base64
import os
import re
import shutil
from html import escape, unescape
from html.parser import HTMLParser
from pathlib import Path

import pandas as pd
import pytest

from mechopt.cli import main
from mechopt.workflows.report import build_report, figure_caption, write_report
from mechopt.workflows.reproduce import reproduce, summary_table


@pytest.fixture(scope="module")
def results(tmp_path_factory, quick_reproduction):
    """A quick reproduction of the fastest paper: the session's quick reproduction of
    wu2008 (tests/conftest.py) copied into a folder of its own with the folder's
    manifest (which owns it), then ``reproduce("wu2008", quick=True)`` there, which finds
    the paper done (the same kind of run) and writes the folder's summary as for that
    paper alone (it skipped, not recomputed: the paper's files are the session run's,
    byte for byte)."""
    out = tmp_path_factory.mktemp("results")
    shutil.copytree(quick_reproduction.out / "wu2008", out / "wu2008")
    shutil.copy2(quick_reproduction.out / "manifest.json", out / "manifest.json")
    log = []
    reproduce("wu2008", out=out, quick=True, log=log.append)
    assert any("skipped" in m for m in log), log
    return out


@pytest.fixture(scope="module")
def report(results):
    path = write_report(results, out=results / "report.html")
    return path, path.read_text()


class _Tables(HTMLParser):
    """The text of every cell of every ``<table id=...>``: {id: [[cell, ...], ...]}."""

    def __init__(self):
        super().__init__()
        self.tables, self._id, self._row, self._cell = {}, None, None, None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "table":
            self._id = a.get("id")
            self.tables[self._id] = []
        elif tag == "tr" and self._id is not None:
            self._row = []
        elif tag in ("td", "th") and self._row is not None:
            self._cell = []

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self._row.append(" ".join("".join(self._cell).split()))
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.tables[self._id].append(self._row)
            self._row = None
        elif tag == "table":
            self._id = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)


def _tables(html):
    p = _Tables()
    p.feed(html)
    return p.tables


# --------------------------------------------------------------------------- the HTML as text

def test_self_contained(report):
    _, html = report
    assert not re.search(r"""(?:src|href|action)\s*=\s*["']?\s*(?:https?:)?//""", html, re.I)
    assert not re.search(r"url\(\s*['\"]?(?:https?:)?//", html, re.I)  # no CSS fetch
    assert not re.search(r"<script[^>]*\bsrc=", html, re.I)
    assert not re.search(r"<link[^>]*stylesheet", html, re.I)
    assert html.count("<script") == 1  # the sorter, inline
    srcs = re.findall(r'<img src="([^"]*)"', html)
    assert srcs and all(s.startswith("data:image/png;base64,") for s in srcs)
    html.encode("ascii")  # pure ASCII whatever the locale


def test_every_figure_embedded_with_caption(results, report):
    _, html = report
    pngs = sorted(results.rglob("*.png"))
    srcs = re.findall(r'<img src="data:image/png;base64,([^"]*)"', html)
    contents = {p.read_bytes() for p in pngs}
    assert len(srcs) == len(contents) < len(pngs)  # the quick run's sweep repeats its front.png
    embedded = [base64.b64decode(s) for s in srcs]
    assert len(set(embedded)) == len(embedded)  # no figure twice
    assert all(p.read_bytes() in embedded for p in pngs)
    n = len(contents)
    assert f"{n} figures, fronts and sweeps</p>" in html  # the header counts what is shown
    # the copy is named beside the one shown
    assert ("<code>wu2008/sweep/front.png</code> is the same image as <code>wu2008/front/front.png</code>"
            in html)
    for p in (results / "wu2008").glob("*.png"):
        ref, desc = figure_caption("wu2008", p.name)
        title = f"{ref} redrawn" if ref else "mechopt figure (not a figure of the paper)"
        assert f"<strong>{escape(title)}</strong>: {escape(desc)}." in html
    assert "<strong>Wu 2008 Fig. 2 redrawn</strong>" in html
    assert "Pareto front of problem wu2008-dynamic" in html
    assert "Weighted-sum sweep of problem wu2008" in html


def test_counts_present(results, report):
    _, html = report
    summary = summary_table(Path(results))
    rows = _tables(html)["summary"]
    assert rows[0] == list(summary.columns)
    assert len(rows) == len(summary) + 1
    for row, (_, rec) in zip(rows[1:], summary.iterrows()):
        assert row[0].endswith(rec["paper"])  # "Wu 2008" and the paper's title
        assert row[1:] == [str(int(rec[c])) for c in summary.columns[1:]]


def test_paper_table_and_status_colours(results, report):
    _, html = report
    df = pd.read_csv(results / "wu2008" / "table.csv")
    rows = _tables(html)["table-wu2008"]
    assert set(rows[0]) == set(df.columns) and rows[0][-1] == "note"
    assert len(rows) == len(df) + 1
    colour = {"match": "good", "holds": "good", "differs": "bad", "fails": "bad", "not-reported": "none"}
    for status in set(df["status"]):
        assert f'<td class="status st-{colour[status]}" data-sort="{status}">{status}</td>' in html


def test_differs_rows_have_their_reason(results, report):
    _, html = report
    df = pd.read_csv(results / "wu2008" / "table.csv")
    differs = df[df["status"] == "differs"]
    assert len(differs)  # the quick wu2008 run has one (k_av[table1]); else this test shows nothing
    section = html.split('id="wu2008-differs"')[1].split("</ol>")[0]
    for rec in differs.itertuples():
        assert escape(rec.quantity) in section
        short = re.search(r'<p class="why-short">([^<]*)</p>', section.split(escape(rec.quantity), 1)[1]).group(1)
        short = unescape(short)
        assert len(short) <= 184  # a short item: the reason's first clauses ...
        assert rec.note.startswith(short.removesuffix(" ..."))
        if len(rec.note) > len(short):  # ... and the whole note folded below it
            assert f'<summary>the whole note</summary><p class="why">{escape(rec.note)}</p>' in section


def test_reason_names_the_check():
    from mechopt.workflows.report import _reason

    note = ("our a_MAX at the paper's rho* = 1.9721 (l0 by eq. 24, MIC centre); the bottom-corner LCI binds "
            "there; tol 5e-05 l1 (max of half last digit 5e-05, 1e-05 l1)")
    short, check = _reason(note)
    assert check == "tol 5e-05 l1 (max of half last digit 5e-05, 1e-05 l1)"
    assert short == "our a_MAX at the paper's rho* = 1.9721 (l0 by eq. 24, MIC centre); the bottom-corner LCI binds there"
    short, check = _reason("A. " + "word " * 100)
    assert check == "" and len(short) <= 184 and short.endswith(" ...")


def test_setting_rows_are_neutral(results, tmp_path):
    copy = tmp_path / "results"
    shutil.copytree(results / "wu2008", copy / "wu2008")
    df = pd.read_csv(copy / "wu2008" / "table.csv")
    df.loc[0, ["kind", "status"]] = ["setting", "match"]
    df.loc[1, ["kind", "status"]] = ["setting", "differs"]
    df.to_csv(copy / "wu2008" / "table.csv", index=False)
    rows = build_report(copy).split('id="table-wu2008"')[1].split("</tbody>")[0].split("<tr")[2:4]
    for row, status in zip(rows, ("match", "differs")):
        assert f'<td class="status st-setting" data-sort="{status}">{status}</td>' in row
        assert "st-good" not in row and "st-bad" not in row


def test_front_figures_read_plainly():
    """A one-design front is a marker labelled with its value; no axis carries an offset
    (``1e-5+1.329``) or a scientific factor."""
    from mechopt.problems import get
    from mechopt.run.plotting import plot_front

    problem = get("wu2008")
    a, b = (o.name for o in problem.objectives)
    fig = plot_front(problem, pd.DataFrame({a: [1.78606], b: [616.621]}), pd.DataFrame())
    fig.draw_without_rendering()
    ax = fig.axes[0]
    assert [t.get_text() for t in ax.texts] == ["(1.78606, 616.621)"]
    assert ax.get_legend() is None
    # the chosen design of a front is starred
    two = plot_front(problem, pd.DataFrame({a: [1.5, 1.7, 1.9], b: [500.0, 600.0, 700.0]}), pd.DataFrame(), chosen=1)
    star = [c for c in two.axes[0].collections if c.get_label() == "chosen design"]
    assert len(star) == 1 and star[0].get_offsets().tolist() == [[1.7, 600.0]]
    assert ax.get_xlim() == pytest.approx((1.78606 * 0.95, 1.78606 * 1.05))
    assert ax.get_ylim() == pytest.approx((616.621 * 0.95, 616.621 * 1.05))
    le = get("le2013")
    name = le.objectives[0].name
    fig = plot_front(le, pd.DataFrame(), pd.DataFrame({"generation": [1, 2, 3],
                                                         f"best_{name}": [1.3291565, 1.3291565, 1.3292093]}))
    fig.draw_without_rendering()
    ax = fig.axes[0]
    assert ax.yaxis.get_offset_text().get_text() == "" and ax.xaxis.get_offset_text().get_text() == ""
    labels = [t.get_text() for t in ax.get_yticklabels() if t.get_text()]
    assert labels and all(lab.startswith("1.329") for lab in labels), labels


def test_text_is_escaped(results, tmp_path):
    copy = tmp_path / "results"
    shutil.copytree(results / "wu2008", copy / "wu2008")
    df = pd.read_csv(copy / "wu2008" / "table.csv")
    evil = '<script>alert("x")</script> & <b>bold</b> \u2264 1'
    df.loc[0, "note"] = evil
    df.loc[0, "status"] = "differs"
    df.loc[1, "quantity"] = "<img src=x onerror=alert(1)>"
    df.to_csv(copy / "wu2008" / "table.csv", index=False)
    html = build_report(copy)
    assert "<script>alert" not in html and "<b>bold</b>" not in html and "<img src=x" not in html
    assert escape(evil).replace("\u2264", "&#8804;") in html
    assert html.count("<script") == 1


def test_figure_captions_from_file_names():
    assert figure_caption("le2013", "fig5_a_max.png")[0] == "Le 2013 Fig. 5"
    assert figure_caption("liu2006", "fig04a_atlas_gvi_max.png")[0] == "Liu 2006 Fig. 4(a)"
    assert figure_caption("liu2006", "fig02_atlas_gci.png")[0] == "Liu 2006 Fig. 2"
    assert figure_caption("liu2006", "figs08-16_examples.png")[0] == "Liu 2006 Figs. 8-16"
    assert figure_caption("liu2006", "fig17_23_lci_usable.png")[0] == "Liu 2006 Figs. 17 and 23"
    assert figure_caption("liu2006", "ref19_fig19_atlas_r_mic.png")[0] == "Fig. 19 of Liu 2006's Ref. [19]"
    assert "GVI max" in figure_caption("liu2006", "fig04a_atlas_gvi_max.png")[1]
    assert "W-GCI-GSI" in figure_caption("liu2006", "fig13_region_w-gci-gsi.png")[1]
    ref, desc = figure_caption("stan2008", "tradeoff_bipod.png")
    assert ref is None and "Table 2" in desc
    assert figure_caption("wu2008", "some_new_plot.png") == (None, "some new plot")


def test_missing_or_empty_results_dir(tmp_path, capsys):
    for d in (tmp_path / "absent", tmp_path):
        with pytest.raises(ValueError) as exc:
            build_report(d)
        assert "\n" not in str(exc.value) and "mechopt reproduce" in str(exc.value)
        assert main(["report", str(d), "--out", str(tmp_path / "r.html")]) == 2
        err = capsys.readouterr().err
        assert err.startswith("mechopt: error: RESULTS_DIR") and err.count("\n") == 1
    assert not (tmp_path / "r.html").exists() and not (tmp_path / "absent").exists()


def test_cli(results, tmp_path, capsys):
    out = tmp_path / "sub" / "r.html"
    assert main(["report", str(results), "--out", str(out)]) == 0
    assert capsys.readouterr().out.strip() == f"report: {out.resolve()}"
    assert out.read_text().startswith("<!DOCTYPE html>")
    assert [p.name for p in out.parent.iterdir()] == ["r.html"]  # atomic: no temporary left
    assert main(["report", str(results)]) == 0  # default: RESULTS_DIR/report.html
    assert capsys.readouterr().out.strip() == f"report: {(results / 'report.html').resolve()}"
    assert main(["report", str(results), "--out", str(tmp_path)]) == 2  # a folder is not a file
    assert "--out must name an HTML file" in capsys.readouterr().err


# --------------------------------------------------------------------------- in a real browser

def _browser():
    """(chromium binary, chromedriver) or skip saying what is missing."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        pytest.skip("selenium is not installed (pip install -e '.[test]')")
    binary = os.environ.get("CHROME_BIN") or next(
        (shutil.which(b) for b in ("chromium", "chromium-browser", "google-chrome") if shutil.which(b)), None)
    if not binary:
        pytest.skip("no Chromium browser installed (apt-get install chromium chromium-driver; .ci/run does)")
    driver = os.environ.get("CHROMEDRIVER") or shutil.which("chromedriver")
    if not driver:
        pytest.skip("no chromedriver installed (apt-get install chromium-driver; .ci/run does)")
    return binary, driver


@pytest.fixture(scope="module")
def browser():
    binary, driver_path = _browser()
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = binary
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                "--window-size=1400,1000", "--disable-extensions", "--no-first-run"):
        opts.add_argument(arg)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    drv = webdriver.Chrome(service=Service(executable_path=driver_path), options=opts)
    try:
        yield drv
    finally:
        drv.quit()


@pytest.fixture
def artifacts(tmp_path):
    folder = Path(os.environ["CI_ARTIFACTS"]) if os.environ.get("CI_ARTIFACTS") else tmp_path
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def _column(browser, table_id, col):
    """The sort keys of column ``col`` of a table, top to bottom (data-sort, else the text)."""
    return browser.execute_script(
        "var t = document.getElementById(arguments[0]), col = arguments[1];"
        "return Array.prototype.map.call(t.tBodies[0].rows, function (r) {"
        "  var c = r.cells[col], v = c.getAttribute('data-sort');"
        "  return v === null ? c.textContent.trim() : v; });", table_id, col)


def _click_header(browser, table_id, name):
    from selenium.webdriver.common.by import By

    headers = browser.find_elements(By.CSS_SELECTOR, f"#{table_id} thead th")
    names = [h.text.strip() for h in headers]
    col = names.index(name)
    browser.execute_script("arguments[0].scrollIntoView({block: 'center'});", headers[col])
    headers[col].click()  # a real click (fails if something covers the header)
    return col


def test_in_browser(browser, report, artifacts):
    path, _ = report
    browser.get(path.resolve().as_uri())
    assert browser.title.startswith("mechopt reproduction report")

    # every image decodes
    widths = browser.execute_async_script(
        "var done = arguments[arguments.length - 1];"
        "Promise.all(Array.prototype.map.call(document.images, function (i) {"
        "  return i.decode().then(function () { return i.naturalWidth; }, function () { return 0; });"
        "})).then(done);")
    assert widths and all(w > 0 for w in widths), widths
    assert len(widths) == len({p.read_bytes() for p in path.parent.rglob("*.png")})  # each image once

    # the tables sort: numbers numerically (empty cells last), text alphabetically, twice reverses
    tid = "table-wu2008"
    col = _click_header(browser, tid, "rel_error")
    vals = _column(browser, tid, col)
    nums = [float(v) for v in vals if v != ""]
    assert nums == sorted(nums) and vals[len(nums):] == [""] * (len(vals) - len(nums))
    assert browser.find_elements("css selector", f"#{tid} thead th")[col].get_attribute("aria-sort") == "ascending"
    _click_header(browser, tid, "rel_error")
    nums = [float(v) for v in _column(browser, tid, col) if v != ""]
    assert nums == sorted(nums, reverse=True)
    col = _click_header(browser, tid, "status")
    status = _column(browser, tid, col)
    assert status == sorted(status) and len(set(status)) > 1

    # no console error (read after the clicks: the sorter ran too)
    severe = [e for e in browser.get_log("browser") if e.get("level") == "SEVERE"]
    assert severe == []

    # screenshots, as CI artefacts: the top of the page and the whole page
    browser.execute_script("window.scrollTo(0, 0);")
    top = artifacts / "report-top.png"
    assert browser.save_screenshot(str(top)) and top.stat().st_size > 10_000
    metrics = browser.execute_cdp_cmd("Page.getLayoutMetrics", {})
    size = metrics.get("cssContentSize") or metrics["contentSize"]
    shot = browser.execute_cdp_cmd("Page.captureScreenshot", {
        "format": "png", "captureBeyondViewport": True,
        "clip": {"x": 0, "y": 0, "width": size["width"], "height": min(size["height"], 16000), "scale": 1}})
    full = artifacts / "report-full.png"
    full.write_bytes(base64.b64decode(shot["data"]))
    assert full.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    shutil.copy(path, artifacts / "report.html")
    print(f"screenshots: {top}, {full}")


def test_tables_fit_at_1280_px(browser, results, tmp_path, artifacts):
    """At a 1280 px window no table is wider than its frame or the window (with every
    folded note opened too), settings are not green, and no image is shown twice."""
    copy = tmp_path / "results"
    shutil.copytree(results / "wu2008", copy / "wu2008")
    df = pd.read_csv(copy / "wu2008" / "table.csv")
    df.loc[0, ["kind", "status"]] = ["setting", "match"]
    df.to_csv(copy / "wu2008" / "table.csv", index=False)
    path = write_report(copy, out=copy / "report.html")
    browser.set_window_size(1280, 1000)
    try:
        browser.get(path.resolve().as_uri())
        widths = ("var W = document.documentElement.clientWidth;"
                  "return Array.prototype.map.call(document.querySelectorAll('table'), function (t) {"
                  "  var f = t.parentNode, r = t.getBoundingClientRect();"
                  "  return [t.id, Math.ceil(r.right), W, f.scrollWidth, f.clientWidth]; });")
        for opened in (False, True):
            if opened:
                browser.execute_script("document.querySelectorAll('details').forEach(function (d) { d.open = true; });")
            for tid, right, window, scroll, frame in browser.execute_script(widths):
                assert right <= window and scroll <= frame, (tid, opened, right, window, scroll, frame)
        colours = browser.execute_script(
            "var t = document.getElementById('table-wu2008'), h = Array.prototype.map.call(t.tHead.rows[0].cells,"
            "  function (c) { return c.textContent.trim(); }), k = h.indexOf('kind'), s = h.indexOf('status');"
            "return Array.prototype.map.call(t.tBodies[0].rows, function (r) {"
            "  return [r.cells[k].textContent.trim(), r.cells[s].textContent.trim(),"
            "          getComputedStyle(r.cells[s]).backgroundColor]; });")
        rgb = lambda c: [int(v) for v in re.findall(r"\d+", c)[:3]]  # noqa: E731
        settings = [rgb(c) for kind, _, c in colours if kind == "setting"]
        matched = [rgb(c) for kind, st, c in colours if kind != "setting" and st == "match"]
        assert settings and matched
        for r, g, b in settings:
            assert not (g > r + 15 and g > b + 15), (r, g, b)  # not green
        assert all(m[1] > m[0] + 15 for m in matched)  # a computed match is (the check can tell)
        srcs = browser.execute_script("return Array.prototype.map.call(document.images, function (i) { return i.src; });")
        assert len(srcs) == len(set(srcs))
        browser.execute_script("document.getElementById('table-wu2008').scrollIntoView();")
        shot = artifacts / "report-1280.png"
        assert browser.save_screenshot(str(shot))
    finally:
        browser.set_window_size(1400, 1000)
