"""The user-guide pages of issue 34 (evaluate, design, adding a mechanism, adding a
requirement): their code runs and does what the page says; the index links them; the
tables the design page renders from the registry hold every member; the intersphinx
inventories shipped for the offline build are current and load."""
from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = ("guide_evaluate", "guide_design", "guide_add_mechanism", "guide_add_requirement")


def _run_page(name, folder, monkeypatch) -> dict:
    """Every ```python block of ``docs/<name>.md``, in order, in one namespace, in ``folder``."""
    blocks = re.findall(r"```python\n(.*?)```", (DOCS / f"{name}.md").read_text(), flags=re.S)
    assert blocks, name
    monkeypatch.chdir(folder)
    scope: dict = {"__name__": "__page__"}
    for block in blocks:
        exec(compile(block, f"{name}.md", "exec"), scope)  # noqa: S102 - the page's own code
    return scope


def _load(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_index_links_every_guide_page():
    index = (DOCS / "index.rst").read_text()
    for page in PAGES:
        assert f"   {page}\n" in index, page


def test_evaluate_page_runs(tmp_path, monkeypatch):
    scope = _run_page("guide_evaluate", tmp_path, monkeypatch)
    # the MIC of (0.85, 1.6, 0.55) is bounded by the annulus r1 (Liu 2006 sec. 3.1)
    assert scope["res"].values["r_mic"] == pytest.approx(0.85, rel=1e-6)
    # the bipod of Stan 2008 with b = 60 mm: the exact area 4863.88 mm^2 (README)
    assert mechopt_area(scope) == pytest.approx(4863.88, abs=0.01)


def mechopt_area(scope):
    import mechopt

    return mechopt.evaluate(scope["bipod"]).values["workspace_area"]


def test_add_mechanism_page_runs_and_its_stage_is_right(tmp_path, monkeypatch):
    scope = _run_page("guide_add_mechanism", tmp_path, monkeypatch)
    stage = scope["stage"]
    assert scope["ok"].tolist() == [True, False]
    # an independent check of the derived quantities: q = p, so J = I, LCI = 1, the
    # clearance of the centre is the half of the shorter stroke
    assert (scope["J"] == [[1.0, 0.0], [0.0, 1.0]]).all()
    assert stage.lci(10.0, 20.0) == 1.0 and stage.serial_clearance(150.0, 100.0) == 100.0
    assert scope["mechopt"].evaluate(stage).values == {"workspace_area": 300.0 * 200.0}
    # outside the strokes the clearance is minus the distance to the rectangle
    assert stage.serial_clearance(303.0, 204.0) == pytest.approx(-5.0)


def test_add_requirement_page_runs_and_unregisters(tmp_path, monkeypatch):
    from mechopt import requirements as registry
    from mechopt.requirements import Requirements

    before = registry.MODULES
    monkeypatch.setattr(registry, "MODULES", before)  # restored even if the page fails
    scope = _run_page("guide_add_requirement", tmp_path, monkeypatch)
    front = scope["result"].front
    # the task is fixed at (0, 150): the margin is 210 - 150 on every row, exactly
    assert len(front) >= 1 and (front["margin_centre"] == 60.0).all()
    assert registry.MODULES == before and "centre_requirement" not in sys.modules
    with pytest.raises(ValueError, match="unknown requirement 'max_centre_distance'"):
        Requirements(max_centre_distance=1.0)


def test_design_page_runs(tmp_path, monkeypatch):
    scope = _run_page("guide_design", tmp_path, monkeypatch)
    front = scope["result"].front
    assert len(front) >= 1 and scope["chosen"]["feasible"] is True
    assert (front["min-lci"] >= 0.4 - 1e-9).all()


def test_design_page_tables_list_every_member():
    from mechopt.requirements import objectives, requirements

    ext = _load(DOCS / "_ext" / "mechopt_tables.py", "mechopt_tables")
    rows = ext.requirement_rows()
    assert [r[0] for r in rows] == [r.name for r in requirements()]
    for row, member in zip(rows, requirements()):
        assert row[3] == member.certificate and row[4] == ("yes" if member.proven else "no")
        for o in member.options:
            assert o.flag in row[1]
    assert [r[0] for r in ext.objective_rows()] == list(objectives())
    text = (DOCS / "guide_design.md").read_text()
    assert "```{requirements-table}" in text and "```{objectives-table}" in text


def test_shipped_inventories_are_current_and_load():
    from sphinx.util.inventory import InventoryFile

    gen = _load(DOCS / "gen_inventories.py", "gen_inventories")
    for project, (base, _, entries) in gen.INVENTORIES.items():
        path = DOCS / "_inv" / f"{project}.inv"
        assert path.read_bytes() == gen.render(project), f"{path.name}: run python docs/gen_inventories.py"
        inv = InventoryFile.loads(path.read_bytes(), uri=base)
        data = getattr(inv, "data", inv)
        names = {name for by_name in data.values() for name in by_name}
        assert names == {e[0] for e in entries}, project
    conf = (DOCS / "conf.py").read_text()
    assert "sphinx.ext.intersphinx" in conf and "_inv" in conf
