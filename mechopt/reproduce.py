"""``mechopt reproduce``: every paper's numbers side by side with the published ones.

Each paper has a thin script ``experiments/<paper>.py`` (installed as
``mechopt.experiments.<paper>``) with ``run(out: Path, quick: bool) -> DataFrame``
that computes its rows (columns :data:`mechopt.published.TABLE_COLUMNS`) and
writes its figures, front and sweep into ``out``. This module runs them, writes
``table.csv`` and ``table.md`` per paper and the summary ``README.md`` over all,
each file atomically (:mod:`mechopt.io`). A paper whose ``table.csv`` exists is
skipped unless ``force``.
"""
from __future__ import annotations

import importlib
import time
from pathlib import Path

import pandas as pd

from . import __version__
from . import io as _io
from . import validation as _v
from .published import KINDS, STATUSES, TABLE_COLUMNS, counts

__all__ = ["PAPERS", "reproduce", "markdown_table", "write_summary", "summary_table", "counts_line"]

PAPERS = ("le2013", "stan2008", "liu2006", "wu2008")
TITLES = {
    "le2013": "Le, Kang, Doan (2013), ICCAIS, doi:10.1109/ICCAIS.2013.6720521",
    "stan2008": "Stan, Maties, Balan (2008), Parallel Manipulators, Towards New Applications, I-Tech",
    "liu2006": "Liu, Wang, Pritschow (2006), Mech. Mach. Theory 41:119-144",
    "wu2008": "Wu, Wang, Wang, Shao (2008), Proc. IMechE C 222, doi:10.1243/09544062JMES830",
}


def _fmt(v):
    if isinstance(v, float):
        if v != v:
            return ""
        return f"{v:.6g}"
    return str(v).replace("|", "\\|")


def markdown_table(df: pd.DataFrame) -> str:
    """A GitHub-flavoured markdown table (no extra dependency)."""
    cols = list(df.columns)
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for row in df.itertuples(index=False):
        lines.append("| " + " | ".join(_fmt(v) for v in row) + " |")
    return "\n".join(lines) + "\n"


def _check_table(paper: str, df: pd.DataFrame):
    missing = [c for c in TABLE_COLUMNS if c not in df.columns]
    if missing:
        raise RuntimeError(f"experiments/{paper}.py returned a table without {missing}")
    bad = set(df["status"]) - set(STATUSES)
    if bad:
        raise RuntimeError(f"experiments/{paper}.py returned statuses {sorted(bad)}")
    bad = set(df["kind"]) - set(KINDS)
    if bad:
        raise RuntimeError(f"experiments/{paper}.py returned kinds {sorted(bad)}")


def reproduce(paper: str, out="results", quick: bool = False, force: bool = False,
              log=print) -> pd.DataFrame:
    """Reproduce one paper (or ``"all"``) into ``out/<paper>/``; returns the table(s)."""
    _v.choice("paper", paper, PAPERS + ("all",))
    out = _io.prepare_out_dir(out)
    papers = PAPERS if paper == "all" else (paper,)
    tables = []
    for i, name in enumerate(papers, 1):
        folder = out / name
        table_csv = folder / "table.csv"
        stamp = {"quick": bool(quick), "mechopt": __version__}
        if table_csv.exists() and not force:
            old = _read_stamp(folder)
            if old == stamp:
                log(f"[{i}/{len(papers)}] {name}: done before, skipped (use --force to redo)")
                tables.append(pd.read_csv(table_csv).assign(paper=name))
                continue
            log(f"[{i}/{len(papers)}] {name}: the finished run was "
                f"{_describe_stamp(old)}, this one is {_describe_stamp(stamp)}: recomputing")
        _io.prepare_out_dir(folder)
        log(f"[{i}/{len(papers)}] {name}: running{' (quick)' if quick else ''} ...")
        t0 = time.perf_counter()
        module = importlib.import_module(f"mechopt.experiments.{name}")
        df = module.run(folder, quick=quick)
        _check_table(name, df)
        cols = list(TABLE_COLUMNS) + [c for c in df.columns if c not in TABLE_COLUMNS]
        df = df[cols]
        _io.write_text(folder / "table.md", f"# {TITLES[name]}\n\n" + markdown_table(df))
        _io.write_json(stamp, folder / STAMP)
        _io.write_csv(df, table_csv)  # last: its presence marks the paper as finished
        log(f"[{i}/{len(papers)}] {name}: {counts_line(counts(df))} "
            f"({time.perf_counter() - t0:.1f} s)")
        tables.append(df.assign(paper=name))
    table = pd.concat(tables, ignore_index=True)
    write_summary(out)
    return table


#: how a paper's folder was produced (quick or full, mechopt version), written before
#: table.csv; a finished paper is reused only by a run of the same kind
STAMP = "reproduce.json"


def _read_stamp(folder) -> dict | None:
    import json

    try:
        return json.loads((folder / STAMP).read_text())
    except (OSError, ValueError):
        return None


def _describe_stamp(stamp) -> str:
    if not isinstance(stamp, dict):
        return "of unknown kind (no reproduce.json)"
    return f"{'quick' if stamp.get('quick') else 'full'} (mechopt {stamp.get('mechopt')})"


def counts_line(c: dict) -> str:
    """``"12 of 20 computed match, 8 differ; 5 readings (2 match), ..."``."""
    return (f"{c['match']} of {c['computed']} computed match, {c['differs']} differ; "
            f"{c['readings']} readings ({c['readings matching']} match), {c['settings']} settings, "
            f"{c['not-reported']} not reported, claims {c['claims hold']} hold / "
            f"{c['claims fail']} fail")


def summary_table(out) -> pd.DataFrame:
    """One row of :func:`mechopt.published.counts` per finished paper, and a total row."""
    rows = []
    for name in PAPERS:
        f = out / name / "table.csv"
        if f.exists():
            rows.append({"paper": TITLES[name], **counts(pd.read_csv(f))})
    if rows:
        total = {k: sum(r[k] for r in rows) for k in rows[0] if k != "paper"}
        rows.append({"paper": "total", **total})
    return pd.DataFrame(rows)


def write_summary(out) -> Path:
    """``out/README.md``: the honest counts over the papers finished so far, and why
    each computed quantity differs."""
    out = Path(out)
    reasons = []
    for name in PAPERS:
        f = out / name / "table.csv"
        if not f.exists():
            continue
        df = pd.read_csv(f)
        kind = df["kind"] if "kind" in df else "computed"
        for rec in df[(df["status"] == "differs") & (kind == "computed")].itertuples():
            reasons.append({"paper": name, "quantity": rec.quantity, "paper value": rec.paper,
                            "reproduced": rec.reproduced, "why": rec.note})
    summary = summary_table(out)
    text = "# Reproduced numbers of the four papers\n\n"
    text += "Generated by `mechopt reproduce`. Each paper's folder holds `table.csv`/`table.md` "
    text += "(columns: " + ", ".join(TABLE_COLUMNS) + "), its figures, front and sweep.\n\n"
    text += ("Counts: `match`/`differs` are over the quantities the paper computed and we "
             "recompute (`computed`); `readings` are rows shown on purpose under another "
             "reading of the paper or another quadrature (and how many of them match), "
             "`settings` inputs we echo, `claims` sentences of the paper checked true or false.\n\n")
    text += markdown_table(summary) if len(summary) else "Nothing reproduced yet.\n"
    if reasons:
        text += "\n## Where we differ, and why\n\n" + markdown_table(pd.DataFrame(reasons))
    return _io.write_text(out / "README.md", text)
