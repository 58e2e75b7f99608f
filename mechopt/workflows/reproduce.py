"""``mechopt reproduce``: every paper's numbers side by side with the published ones.

Each paper has a thin script ``experiments/<paper>.py`` (installed as
``mechopt.experiments.<paper>``) with ``run(out: Path, quick: bool) -> DataFrame``
that computes its rows (columns :data:`mechopt.core.published.TABLE_COLUMNS`) and
writes its figures, front and sweep into ``out``. This module runs them, writes
``table.csv`` and ``table.md`` per paper and the summary ``README.md`` over all,
each file atomically (:mod:`mechopt.run.io`). A paper whose ``table.csv`` exists is
skipped unless ``force``. The papers are independent: ``reproduce("all")`` runs them
side by side in worker processes (one per CPU, :func:`default_jobs`), with the same
files as one after the other.
"""
from __future__ import annotations

import importlib
import os
import time
from pathlib import Path

import pandas as pd

from mechopt import __version__
from mechopt.run import io as _io
from mechopt.core import validation as _v
from mechopt.core.published import KINDS, STATUSES, TABLE_COLUMNS, counts

__all__ = ["PAPERS", "reproduce", "default_jobs", "markdown_table", "write_summary", "summary_table", "counts_line"]

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
    """A GitHub-flavoured markdown table (no extra dependency).

    Parameters
    ----------
    df : DataFrame
        The table.

    Returns
    -------
    str
        The markdown.
    """
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


#: relative cost (CPU seconds on 2 cores, ``benchmarks/bench_pipeline.py``) of each
#: work unit of a parallel reproduction, full and quick: a paper's table (``None``)
#: and each of its independent parts (``experiments.<paper>.PARTS``). The units start
#: longest first, so that the workers finish together; no file depends on the order
COST = {
    False: {("le2013", None): 17, ("le2013", "sweep"): 35, ("stan2008", None): 36,
            ("liu2006", None): 22, ("liu2006", "figures"): 6, ("liu2006", "runs"): 31,
            ("wu2008", None): 7, ("wu2008", "runs"): 11},
    True: {("le2013", None): 3, ("le2013", "sweep"): 1, ("stan2008", None): 5,
           ("liu2006", None): 16, ("liu2006", "figures"): 6, ("liu2006", "runs"): 3,
           ("wu2008", None): 2, ("wu2008", "runs"): 1},
}


def default_jobs(n_units: int) -> int:
    """Worker processes for ``n_units`` work units: one per unit up to the CPU count (2
    on the 2-core machine the targets are measured on); 1 for a single unit.

    Parameters
    ----------
    n_units : int
        Work units.

    Returns
    -------
    int
        Processes.
    """
    return max(1, min(int(n_units), os.cpu_count() or 1))


def reproduce(paper: str, out="results", quick: bool = False, force: bool = False,
              log=print, n_jobs: int | None = None, progress: bool = False) -> pd.DataFrame:
    """Reproduce one paper (or ``"all"``) into ``out/<paper>/``; returns the table(s).

    The papers are independent, and so are the parts of a paper that only write files
    (``experiments.<paper>.PARTS``, e.g. a weighting sweep whose front no row uses):
    each paper's table and each of its parts is a work unit (a stage), mapped over
    ``n_jobs`` worker processes (:func:`mechopt.run.parallel.parallel_map`; default
    :func:`default_jobs` of the papers to run), longest first (:data:`COST`). Every
    file is the one a serial run writes, byte for byte (the units write disjoint files;
    ``tests/test_reproduce.py``); a paper's ``table.csv`` is written once all its units
    are done. ``n_jobs=1``, or a single paper, runs the units in this process. A
    paper's line is logged when it is done; with ``progress`` a
    :class:`mechopt.run.progress.Progress` over the stages (a bar on a terminal, one plain
    line per finished stage otherwise) goes to stderr. The returned table is in the
    order of :data:`PAPERS`.

    Parameters
    ----------
    paper : str
        A paper's key or ``"all"``.
    out : str or Path
        The results folder.
    quick : bool
        Smaller runs (minutes instead of an hour).
    force : bool
        Recompute what is already there.
    log : callable
        ``log(text)`` for progress lines.
    n_jobs : int, optional
        Worker processes (default :func:`default_jobs`).
    progress : bool
        Show a progress bar.

    Returns
    -------
    DataFrame
        The table (table.csv), all papers' concatenated for ``"all"``.
    """
    _v.choice("paper", paper, PAPERS + ("all",))
    if n_jobs is not None:
        n_jobs = _v.integer("n_jobs", n_jobs, 1)
    out = _io.prepare_out_dir(out)
    papers = PAPERS if paper == "all" else (paper,)
    # the folder is claimed like a run's (mechopt.run.io.claim_out): README.md and the
    # paper folders are written only where no other program's files of those names are
    with _io.run_in(out, "reproduce", {}, REPRODUCE_OUTPUTS) as manifest:
        for name in ("README.md", *papers):
            _io.own(out, manifest, name)
        return _reproduce(papers, out, quick, force, log, n_jobs, progress)


#: the names ``reproduce`` writes into its folder (refused where no manifest of a
#: reproduction accounts for them)
REPRODUCE_OUTPUTS = ("README.md", *PAPERS)


def _reproduce(papers, out, quick, force, log, n_jobs, progress) -> pd.DataFrame:
    """The papers of :func:`reproduce` into the claimed folder ``out``."""
    n = len(papers)
    stamp = {"quick": bool(quick), "mechopt": __version__}
    tables = {}
    todo = []
    for i, name in enumerate(papers, 1):
        folder = out / name
        table_csv = folder / "table.csv"
        if table_csv.exists() and not force:
            old = _read_stamp(folder)
            if old == stamp:
                log(f"[{i}/{n}] {name}: done before, skipped (use --force to redo)")
                tables[name] = _read_csv(table_csv).assign(paper=name)
                continue
            log(f"[{i}/{n}] {name}: the finished run was "
                f"{_describe_stamp(old)}, this one is {_describe_stamp(stamp)}: recomputing")
        todo.append((i, name))
    workers = default_jobs(len(todo)) if n_jobs is None else min(n_jobs, max(len(todo), 1))
    if todo:
        _run_units(todo, n, out, quick, stamp, workers, tables, log, progress)
    table = pd.concat([tables[name] for name in papers], ignore_index=True)
    write_summary(out)
    return table


def _read_csv(path) -> pd.DataFrame:
    """A table written by a reproduction, read as a regular file of bounded size
    (:func:`mechopt.run.io.read_bytes`)."""
    import io

    return pd.read_csv(io.BytesIO(_io.read_bytes(path, _io.MAX_JSON_BYTES)))


#: the work unit of a paper's table without its parts (parallel reproduction)
TABLE = "table"


def _units(name):
    """The work units of a paper: its table (:data:`TABLE`) and its independent parts."""
    module = importlib.import_module(f"mechopt.experiments.{name}")
    return [TABLE, *getattr(module, "PARTS", ())]


def _run_units(todo, n, out, quick, stamp, workers, tables, log, progress):
    """Run the work units of the papers ``todo`` on ``workers`` processes (1: here)."""
    from mechopt.run.parallel import parallel_map
    from mechopt.run.progress import Progress

    cost = COST[bool(quick)]
    units = [(i, name, part) for i, name in todo for part in _units(name)]
    units.sort(key=lambda u: -cost.get((u[1], None if u[2] == TABLE else u[2]), 0))  # stable
    left = {name: sum(1 for u in units if u[1] == name) for _, name in todo}
    seconds = dict.fromkeys(left, 0.0)
    result = {}
    where = f"{workers} processes" if workers > 1 else "this process"
    log(f"running {', '.join(name for _, name in todo)}{' (quick)' if quick else ''} as "
        f"{len(units)} work units on {where} ...")
    bar = Progress(len(units), "reproduce", min_interval=0.0) if progress else None
    finished = 0

    def _done(k, res):
        nonlocal finished
        i, name, part = units[k]
        value, sec = res
        seconds[name] += sec
        finished += 1
        if bar is not None:
            bar.update(finished, f"{name} {part} done ({sec:.1f} s)")
        if part == TABLE:
            result[name] = value
        left[name] -= 1
        if left[name] == 0:  # every unit of the paper is done: its table, written last
            df = _finish_paper(name, out / name, stamp, result.pop(name))
            line = (f"[{i}/{n}] {name}: {counts_line(counts(df))} ({seconds[name]:.1f} s in "
                    f"{sum(1 for u in units if u[1] == name)} work units)")
            bar.message(log, line) if bar is not None else log(line)
            tables[name] = df.assign(paper=name)

    jobs = [(name, str(out / name), bool(quick), part) for _, name, part in units]
    try:
        parallel_map(_timed_unit, jobs, n_jobs=workers, on_item=_done)
    finally:
        if bar is not None:
            bar.close()


def _timed_unit(job):
    """One work unit of a parallel reproduction (module level, so that it pickles):
    ``(table or None, seconds)``."""
    t0 = time.perf_counter()
    return _run_paper(job), time.perf_counter() - t0


def _run_paper(job):
    """``job = (name, folder, quick, part)``: :data:`TABLE` the paper's table without
    its parts (``experiments.<name>.run(..., parts=False)``), else one of its parts
    (``run_part``, returns None)."""
    name, folder, quick, part = job
    folder = _io.prepare_out_dir(Path(folder))
    module = importlib.import_module(f"mechopt.experiments.{name}")
    if part == TABLE:
        if getattr(module, "PARTS", ()):
            return module.run(folder, quick=quick, parts=False)
        return module.run(folder, quick=quick)
    module.run_part(folder, quick, part)
    return None


def _finish_paper(name, folder, stamp, df):
    """Check a paper's table and write ``table.md``, the stamp and ``table.csv`` (last:
    its presence marks the paper as finished); returns the table with its columns in
    order."""
    _check_table(name, df)
    cols = list(TABLE_COLUMNS) + [c for c in df.columns if c not in TABLE_COLUMNS]
    df = df[cols]
    _io.write_text(folder / "table.md", f"# {TITLES[name]}\n\n" + markdown_table(df))
    _io.write_json(stamp, folder / STAMP)
    _io.write_csv(df, folder / "table.csv")
    return df


#: how a paper's folder was produced (quick or full, mechopt version), written before
#: table.csv; a finished paper is reused only by a run of the same kind
STAMP = "reproduce.json"


def _read_stamp(folder) -> dict | None:
    try:
        return _io.read_json(folder / STAMP)
    except (OSError, ValueError):
        return None


def _describe_stamp(stamp) -> str:
    if not isinstance(stamp, dict):
        return "of unknown kind (no reproduce.json)"
    return f"{'quick' if stamp.get('quick') else 'full'} (mechopt {stamp.get('mechopt')})"


def counts_line(c: dict) -> str:
    """``"12 of 20 computed match, 8 differ; 5 readings (2 match), ..."``.

    Parameters
    ----------
    c : dict
        Counts (:func:`mechopt.core.published.counts`).

    Returns
    -------
    str
        The line.
    """
    return (f"{c['match']} of {c['computed']} computed match, {c['differs']} differ; "
            f"{c['readings']} readings ({c['readings matching']} match), {c['settings']} settings, "
            f"{c['not-reported']} not reported, claims {c['claims hold']} hold / "
            f"{c['claims fail']} fail")


def summary_table(out) -> pd.DataFrame:
    """One row of :func:`mechopt.core.published.counts` per finished paper, and a total row.

    Parameters
    ----------
    out : str or Path
        The results folder.

    Returns
    -------
    DataFrame
        The counts.
    """
    rows = []
    for name in PAPERS:
        f = out / name / "table.csv"
        if f.exists():
            rows.append({"paper": TITLES[name], **counts(_read_csv(f))})
    if rows:
        total = {k: sum(r[k] for r in rows) for k in rows[0] if k != "paper"}
        rows.append({"paper": "total", **total})
    return pd.DataFrame(rows)


def write_summary(out) -> Path:
    """``out/README.md``: the honest counts over the papers finished so far, and why
    each computed quantity differs.

    Parameters
    ----------
    out : str or Path
        The results folder.

    Returns
    -------
    Path
        README.md.
    """
    out = Path(out)
    reasons = []
    for name in PAPERS:
        f = out / name / "table.csv"
        if not f.exists():
            continue
        df = _read_csv(f)
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
