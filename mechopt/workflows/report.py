"""``mechopt report``: one self-contained HTML page of a reproduction.

:func:`write_report` reads a folder made by ``mechopt reproduce`` (``<paper>/table.csv``,
the figures ``<paper>/*.png``, the runs ``<paper>/<run>/front.png`` and ``sweep.png``)
and writes one HTML file that needs nothing else to be read: every image is embedded as
a ``data:`` URI, the style sheet and the small table sorter are inline, nothing is
fetched from the network. The page holds

* the summary counts of :func:`mechopt.workflows.reproduce.summary_table`;
* per paper: its table (columns :data:`mechopt.core.published.TABLE_COLUMNS` and any extra
  ones, e.g. ``design``, ``quadrature``) with the statuses coloured and every column
  sortable by a click on its header; each ``differs`` row with its reason (its note);
  every figure with a caption naming the paper figure it redraws (from the file name:
  ``fig5_a_max.png`` of ``le2013`` is "Le 2013 Fig. 5"); the fronts and weighting sweeps.

Every text taken from the results is escaped (:func:`html.escape`); the file is written
atomically (:func:`mechopt.run.io.write_text`) and is pure ASCII (other characters as
character references), whatever the locale.
"""
from __future__ import annotations

import base64
import math
import re
import struct
from html import escape
from pathlib import Path

import pandas as pd

from mechopt import __version__
from mechopt.run import io as _io
from mechopt.core.published import TABLE_COLUMNS
from mechopt.workflows.reproduce import PAPERS, TITLES, counts_line, summary_table

__all__ = ["build_report", "write_report", "figure_caption", "paper_name"]

#: how each status is coloured (CSS class ``st-<status>``)
STATUS_CLASSES = {"match": "good", "holds": "good", "differs": "bad", "fails": "bad",
                  "not-reported": "none"}

#: columns printed as numbers (sorted numerically, shown with 6 significant digits)
_NUMERIC = ("paper", "reproduced", "rel_error")

#: the names of the indices and quantities in the figure file names
_TERMS = {
    "gci": "GCI (global conditioning index)", "mci": "MCI (maximum conditioning index: the largest LCI over the MIC)",
    "gvi_max": "GVI max (global velocity index, largest)", "gvi_min": "GVI min (global velocity index, smallest)",
    "gpi_max": "GPI max (global payload index, largest)", "gpi_min": "GPI min (global payload index, smallest)",
    "gsi_max": "GSI max (global stiffness index, largest)", "gsi_min": "GSI min (global stiffness index, smallest)",
    "r_mic": "r_MIC (radius of the maximal inscribed circle)",
}

#: what each figure shows, by paper and file stem (the figure number is read from the stem)
_DESCRIPTIONS = {
    ("le2013", "fig5_a_max"): "a_MAX, the side of the largest square in the maximal inscribed circle with "
                              "LCI >= 0.5 and within the joint limits, over the link ratio rho = l2/l1",
    ("le2013", "fig6_lci_square"): "the local conditioning index LCI over the largest square of the design",
    ("liu2006", "figs08-16_examples"): "the example design of each optimum region (Figs. 8, 10, 12, 14, 16) "
                                      "with its maximal inscribed circle (MIC) and usable workspace",
    ("liu2006", "fig17_23_lci_usable"): "LCI on the usable workspace of the optimum design",
    ("liu2006", "figs18-19_usable"): "usable workspaces of two designs, coloured by LCI",
    ("liu2006", "fig20_lci_miw"): "LCI on the maximal inscribed workspace (MIW)",
    ("liu2006", "figs21-22_extremes_miw"): "extreme velocity, payload and stiffness indices on the maximal "
                                          "inscribed workspace (MIW)",
    ("liu2006", "fig24_d_miw"): "the stiffness indices |D|max and |D|min on the maximal inscribed workspace",
    ("liu2006", "figs25-28_gcw_square"): "the good-condition workspace (GCW, LCI >= 0.5) with its largest "
                                        "square, and |D|max, |D|min on the GCW",
    ("stan2008", "fig29_tqi_bipod"): "the transmission quality index TQI over the Bipod workspace",
    ("stan2008", "fig30_tqi_biglide"): "the transmission quality index TQI over the Biglide workspace",
    ("stan2008", "tradeoff_bipod"): "the normalised workspace W_n and the global TQI T of the Bipod over "
                                    "q1_min/b, and T against W_n, with the paper's Table 2 optima and ours",
    ("stan2008", "tradeoff_biglide"): "the normalised workspace W_n and the global TQI T of the Biglide over "
                                      "L2, and T against W_n, with the paper's Table 3 optima and ours",
    ("wu2008", "fig2_workspace"): "the workspace of the gantry and the task rectangle Q1Q2Q3Q4",
    ("wu2008", "fig4_driving_forces"): "the driving forces along the trajectory of Table 3 (Table 2 masses)",
    ("wu2008", "fig5_inertia_ellipses"): "the acceleration (dynamic manipulability) ellipses over the task",
    ("wu2008", "fig6_kappa_d_built"): "the dynamic manipulability kappa_D (eq. 43) of the built machine",
    ("wu2008", "fig7_kappa_d_symmetric"): "the dynamic manipulability kappa_D (eq. 43) of the symmetric "
                                          "variant (sec. 6.3)",
    ("wu2008", "k_av_vs_theta"): "readings of the global velocity output ratio k_av (eq. 6-7) over the "
                                 "design angle theta_1S",
}

#: ``fig5``, ``fig04a``, ``figs08-16``, ``fig17_23``; ``ref19_fig19`` is a figure of a cited paper
_FIG_RE = re.compile(r"^(?:ref(?P<ref>\d+)_)?figs?(?P<a>\d+)(?P<sa>[a-z])?"
                     r"(?:(?P<sep>[-_])(?P<b>\d+)(?P<sb>[a-z])?)?(?=_|$)")


def paper_name(paper: str) -> str:
    """``"le2013"`` -> ``"Le 2013"``.

    Parameters
    ----------
    paper : str
        The paper's key.

    Returns
    -------
    str
        Author and year.
    """
    if len(paper) > 4 and paper[-4:].isdigit():
        return f"{paper[:-4].capitalize()} {paper[-4:]}"
    return paper


def _fig_label(num: str, sub: str | None) -> str:
    return f"{int(num)}" + (f"({sub})" if sub else "")


def figure_caption(paper: str, filename: str) -> tuple[str | None, str]:
    """``(paper figure or None, what the file shows)`` from a figure's file name.

    ``figure_caption("le2013", "fig5_a_max.png")[0] == "Le 2013 Fig. 5"``; ``figs08-16``
    gives "Figs. 8-16", ``fig17_23`` "Figs. 17 and 23", ``fig04a`` "Fig. 4(a)",
    ``ref19_fig19`` "Fig. 19 of Liu 2006's Ref. [19]". A file without a figure number
    (a mechopt figure) gives ``None``.

    Parameters
    ----------
    paper : str
        The paper's key.
    filename : str
        The figure's file name.

    Returns
    -------
    figure : str or None
        The paper's figure (None for our own).
    shows : str
        What the file shows.
    """
    stem = Path(filename).stem
    name = paper_name(paper)
    m = _FIG_RE.match(stem)
    ref = None
    rest = stem
    if m:
        a = _fig_label(m["a"], m["sa"])
        if m["b"] is not None:
            b = _fig_label(m["b"], m["sb"])
            figs = f"Figs. {a}-{b}" if m["sep"] == "-" else f"Figs. {a} and {b}"
        else:
            figs = f"Fig. {a}"
        ref = f"{figs} of {name}'s Ref. [{int(m['ref'])}]" if m["ref"] else f"{name} {figs}"
        rest = stem[m.end():].lstrip("_")
    desc = _DESCRIPTIONS.get((paper, stem)) or _describe(rest)
    return ref, desc


def _describe(rest: str) -> str:
    """A description from the words of a file stem (``atlas_gvi_max`` -> "atlas of GVI max ...")."""
    for prefix, what in (("atlas_", "atlas of {} over the design plane (s, t) of r1 + r2 + r3 = 3"),
                         ("region_", "optimum region {} drawn in the GCI atlas (the red star: the example "
                                     "design of its section, where the paper gives one)")):
        if rest.startswith(prefix):
            term = rest[len(prefix):]
            label = _TERMS.get(term, term.upper() if prefix == "region_" else term)
            return what.format(label)
    words = rest.replace("_", " ").strip()
    return words or "figure"


# --------------------------------------------------------------------------- reading

def _png_size(data: bytes) -> tuple[int, int] | None:
    if data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR":
        return struct.unpack(">II", data[16:24])
    return None


_MIME = {".png": "image/png", ".svg": "image/svg+xml", ".jpg": "image/jpeg", ".jpeg": "image/jpeg"}


#: the largest image embedded [bytes]
_MAX_IMAGE = 64 << 20


def _image(path: Path, alt: str, root: Path) -> tuple[str, bool]:
    """The ``<img>`` tag of ``path`` as a data URI, and whether the image is wide. Only a
    regular file inside ``root`` (the results folder) is embedded: a link, a FIFO or a
    file reached through a linked folder is a one-line ValueError."""
    data = _io.read_bytes(path, _MAX_IMAGE, root=root)
    size = _png_size(data)
    dims = f' width="{size[0]}" height="{size[1]}"' if size else ""
    uri = f"data:{_MIME.get(path.suffix.lower(), 'image/png')};base64,{base64.b64encode(data).decode('ascii')}"
    return f'<img src="{uri}"{dims} alt="{escape(alt)}">', bool(size and size[0] > 1000)


def _natural(s: str):
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", s)]


def _fig_order(p: Path):
    m = _FIG_RE.match(p.stem)
    if m and not m["ref"]:
        return (0, int(m["a"]), _natural(p.stem))
    return (1 if m else 2, 0, _natural(p.stem))


def _read_json(path: Path) -> dict:
    try:
        obj = _io.read_json(path)
    except (OSError, ValueError):
        return {}
    return obj if isinstance(obj, dict) else {}


def _csv(path: Path, **kw) -> pd.DataFrame:
    """A CSV of the results read as a regular file of bounded size (no link, no FIFO)."""
    import io

    return pd.read_csv(io.BytesIO(_io.read_bytes(path, _io.MAX_JSON_BYTES * 8)), **kw)


def _rows(path: Path) -> int | None:
    try:
        return len(_csv(path))
    except (OSError, ValueError):
        return None


def _count(v) -> int | None:
    """``v`` as a whole number if it is one (run.json as written), else None."""
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v != int(v):
        return None
    return int(v)


def _check_dir(results_dir) -> Path:
    if results_dir is None or not str(results_dir).strip():
        raise ValueError("RESULTS_DIR must name a folder made by `mechopt reproduce`")
    d = Path(results_dir)
    if not d.exists():
        raise ValueError(f"RESULTS_DIR {str(d)!r} does not exist; make it with "
                         f"`mechopt reproduce all --out {d}`")
    if not d.is_dir():
        raise ValueError(f"RESULTS_DIR must be a folder made by `mechopt reproduce`, got the file {str(d)!r}")
    papers = [p for p in PAPERS if (d / p / "table.csv").is_file()]
    if not papers:
        raise ValueError(f"RESULTS_DIR {str(d)!r} holds no reproduced paper (no <paper>/table.csv); "
                         f"make it with `mechopt reproduce all --out {d}`")
    return d


def _read_table(d: Path, paper: str) -> pd.DataFrame:
    f = d / paper / "table.csv"
    try:
        df = _csv(f)
    except (OSError, ValueError) as exc:
        raise ValueError(f"cannot read {f}: {exc}") from None
    missing = [c for c in TABLE_COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"{f} is not a reproduction table: it has no column {', '.join(missing)}")
    # the extra columns (design, quadrature) before the long note, which comes last
    extra = [c for c in df.columns if c not in TABLE_COLUMNS]
    cols = [c for c in TABLE_COLUMNS if c != "note"] + extra + ["note"]
    return df[cols]


# --------------------------------------------------------------------------- rendering

def _is_missing(v) -> bool:
    return v is None or (isinstance(v, float) and math.isnan(v))


def _num(v, digits: int = 6) -> str:
    if _is_missing(v):
        return ""
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return f"{v:.{digits}g}"
    return str(v)


def _status_class(status, kind=None) -> str:
    """The colour class of a row's status: a setting (an input we echo) is neutral,
    whatever its status; the others by :data:`STATUS_CLASSES`."""
    if str(kind) == "setting":
        return "setting"
    return STATUS_CLASSES.get(str(status), "")


def _cell(col: str, v, kind=None) -> str:
    if _is_missing(v):
        return '<td data-sort=""></td>'
    if col in _NUMERIC and isinstance(v, (int, float)) and not isinstance(v, bool):
        shown = _num(v, 3 if col == "rel_error" else 6)
        return f'<td class="num" data-sort="{float(v)!r}">{escape(shown)}</td>'
    text = str(v)
    if col == "status":
        cls = _status_class(text, kind)
        return f'<td class="status st-{cls}" data-sort="{escape(text)}">{escape(text)}</td>'
    if col == "note" and len(text) > 140:
        head = text[:120].rsplit(" ", 1)[0]
        return (f'<td class="note" data-sort="{escape(text)}"><details><summary>{escape(head)} ...'
                f'</summary>{escape(text)}</details></td>')
    cls = {"note": ' class="note"', "source": ' class="src"', "quantity": ' class="qty"'}.get(col, "")
    return f'<td{cls}>{escape(text)}</td>'


def _table_html(df: pd.DataFrame, table_id: str) -> str:
    head = "".join(f'<th scope="col" title="click to sort">{escape(str(c))}</th>' for c in df.columns)
    body = []
    for rec in df.itertuples(index=False):
        status, kind = getattr(rec, "status", ""), getattr(rec, "kind", None)
        cls = _status_class(status, kind)
        cells = "".join(_cell(c, v, kind) for c, v in zip(df.columns, rec))
        body.append(f'<tr class="row-{cls}">{cells}</tr>' if cls else f"<tr>{cells}</tr>")
    long = " long" if len(df) > 25 else ""
    return (f'<div class="scroll{long}"><table class="sortable results" id="{escape(table_id)}">'
            f"<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table></div>")


_COUNT_CLASS = {"match": "good", "claims hold": "good", "readings matching": "good",
                "differs": "bad", "claims fail": "bad", "not-reported": "none"}


def _summary_html(summary: pd.DataFrame) -> str:
    by_title = {v: k for k, v in TITLES.items()}
    cols = list(summary.columns)
    head = "".join(f'<th scope="col" title="click to sort">{escape(c)}</th>' for c in cols)

    def row(rec, tag="td"):
        out = []
        for c in cols:
            v = rec[c]
            if c == "paper":
                key = by_title.get(v)
                if key:
                    out.append(f'<{tag} data-sort="{escape(key)}"><a href="#{escape(key)}">'
                               f'{escape(paper_name(key))}</a><br><small>{escape(str(v))}</small></{tag}>')
                else:
                    out.append(f"<{tag}>{escape(str(v))}</{tag}>")
            else:
                n = int(v)
                cls = _COUNT_CLASS.get(c) if n else None
                klass = f' class="num cnt-{cls}"' if cls else ' class="num"'
                out.append(f'<{tag}{klass} data-sort="{n}">{n}</{tag}>')
        return "<tr>" + "".join(out) + "</tr>"

    body = [row(r) for _, r in summary.iterrows() if r["paper"] != "total"]
    total = [row(r) for _, r in summary.iterrows() if r["paper"] == "total"]
    foot = f"<tfoot>{''.join(total)}</tfoot>" if total else ""
    return (f'<div class="scroll"><table class="sortable summary" id="summary"><thead><tr>{head}</tr>'
            f"</thead><tbody>{''.join(body)}</tbody>{foot}</table></div>")


#: the tolerance a note names (``tol 5e-05 l1 (max of half last digit ...)``): the check a status rests on
_TOL_RE = re.compile(r"(?:^|;\s*)(tol [^;]*)$")


def _reason(note: str, limit: int = 180) -> tuple[str, str]:
    """``(short reason, check)`` of a note: its first clause (up to the first ``;`` or
    sentence end, at most ``limit`` characters, cut at a word) and the tolerance it
    names (empty when none)."""
    note = " ".join(note.split())
    m = _TOL_RE.search(note)
    check = m.group(1) if m else ""
    body = note[:m.start()] if m else note
    clauses = [c.strip() for c in re.split(r";\s|\.\s(?=[A-Z])", body) if c.strip()]
    first = ""
    for c in clauses:  # whole clauses while the reason is short (a bare "GA (seed 1) on le2013" says little)
        first = f"{first}; {c}" if first else c
        if len(first) >= limit // 2:
            break
    if len(first) > limit:
        first = first[:limit].rsplit(" ", 1)[0] + " ..."
    return first, check


def _differs_html(df: pd.DataFrame) -> str:
    rows = df[df["status"] == "differs"]
    if not len(rows):
        return "<p>No row differs.</p>"
    order = {"computed": 0, "reading": 1, "setting": 2, "claim": 3}
    rows = rows.assign(_o=rows["kind"].map(order).fillna(9)).sort_values("_o", kind="stable")
    items = []
    for rec in rows.to_dict("records"):
        unit = "" if _is_missing(rec.get("unit")) or str(rec["unit"]) in ("-", "") else f" {rec['unit']}"
        rel = rec.get("rel_error")
        rel_txt = "" if _is_missing(rel) else f", relative error {_num(100 * float(rel), 3)} %"
        extra = "".join(f", {c} {rec[c]}" for c in df.columns
                        if c not in TABLE_COLUMNS and not _is_missing(rec.get(c)))
        vals = (f"paper <strong>{escape(_num(rec['paper']) + unit)}</strong>, reproduced "
                f"<strong>{escape(_num(rec['reproduced']) + unit)}</strong>{escape(rel_txt + extra)}")
        note = "" if _is_missing(rec.get("note")) else str(rec["note"])
        short, check = _reason(note)
        check_html = f'<p class="why-check">check: {escape(check)}</p>' if check else ""
        more = (f'<details><summary>the whole note</summary><p class="why">{escape(note)}</p></details>'
                if note and short != note else "")
        items.append(f'<li><p class="why-head"><code>{escape(str(rec["quantity"]))}</code> '
                     f'<span class="kind">{escape(str(rec["kind"]))}</span> {vals}</p>'
                     f'<p class="why-short">{escape(short) or "(no note)"}</p>{check_html}{more}'
                     f'<p class="why-src">{escape(str(rec["source"]))}</p></li>')
    return f'<ol class="reasons">{"".join(items)}</ol>'


def _figure_html(path: Path, ref: str | None, desc: str, rel: str) -> str:
    title = f"{ref} redrawn" if ref else "mechopt figure (not a figure of the paper)"
    img, wide = _image(path, f"{title}: {desc}", path.parent.parent)
    cls = ' class="wide"' if wide else ""
    return (f"<figure{cls}>{img}<figcaption><strong>{escape(title)}</strong>: {escape(desc)}. "
            f"<code>{escape(rel)}</code></figcaption></figure>")


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _objectives(folder: Path) -> list[str]:
    """The objective names of a run, from the ``best_<objective>`` columns of its history.csv."""
    try:
        cols = _csv(folder / "history.csv", nrows=0).columns
    except (OSError, ValueError):
        return []
    return [c[len("best_"):] for c in cols if c.startswith("best_")]


def _run_caption(folder: Path, png: Path) -> tuple[str, str]:
    """(title, description) of a run's ``front.png`` or ``sweep.png`` from its run.json."""
    info = _read_json(folder / "run.json")
    problem = info.get("problem") or folder.name
    alg = info.get("algorithm") if isinstance(info.get("algorithm"), dict) else {}
    objectives = _objectives(folder)
    bits = []
    if alg.get("name"):
        bits.append(str(alg["name"]).upper())
    if alg.get("pop") is not None:
        bits.append(f"population {alg['pop']}")
    if _count(alg.get("gen")) is not None:
        bits.append(_plural(_count(alg["gen"]), "generation"))
    if info.get("seed") is not None:
        bits.append(f"seed {info['seed']}")
    if png.stem == "sweep":
        title = f"Weighted-sum sweep of problem {problem}"
        n = _rows(folder / "sweep.csv")
        what = "the optimum of each weighting of the two objectives beside the front"
        if n is not None:
            what += f" ({_plural(n, 'weight')})"
    elif len(objectives) == 1:
        title = f"Convergence of problem {problem}"
        what = f"single objective: the best {objectives[0]} per generation"
    else:
        title = f"Pareto front of problem {problem}"
        n = _rows(folder / "front.csv")
        what = f"objectives {', '.join(objectives)}" if objectives else "the non-dominated designs"
        if n is not None:
            what += f"; {_plural(n, 'design')} on the front"
    desc = f"{what}; mechopt run ({', '.join(bits)})" if bits else what
    if info.get("summary"):
        desc += f". {info['summary']}"
    if isinstance(info.get("single_optimum"), str):
        desc += f" (single optimum: {info['single_optimum']})"
    return title, desc


def _runs_html(d: Path, paper: str, shown: dict) -> str:
    """The fronts and sweeps of ``paper``; ``shown`` maps the sha256 of each image already
    on the page to its path: an identical image (a sweep run's copy of its front) is
    named, not shown twice."""
    import hashlib

    figs, same = [], []
    for sub in sorted((p for p in (d / paper).iterdir() if p.is_dir()), key=lambda p: _natural(p.name)):
        for png in sorted(sub.glob("*.png"), key=lambda p: (p.stem != "front", p.name)):
            rel = f"{paper}/{sub.name}/{png.name}"
            digest = hashlib.sha256(_io.read_bytes(png, _MAX_IMAGE, root=png.parents[2])).hexdigest()
            if digest in shown:
                same.append(f"<code>{escape(rel)}</code> is the same image as <code>{escape(shown[digest])}</code>")
                continue
            shown[digest] = rel
            head, desc = _run_caption(sub, png)
            img, wide = _image(png, f"{head}: {desc}", png.parents[2])
            cls = ' class="wide"' if wide else ""
            figs.append(f"<figure{cls}>{img}<figcaption><strong>{escape(head)}</strong>: {escape(desc)}. "
                        f"<code>{escape(rel)}</code></figcaption></figure>")
    note = f'<p class="same">{"; ".join(same)} (not repeated).</p>' if same else ""
    return (f'<div class="figs">{"".join(figs)}</div>' if figs else "<p>No front or sweep was written.</p>") + note


def _paper_html(d: Path, paper: str) -> tuple[str, int]:
    df = _read_table(d, paper)
    from mechopt.core.published import counts

    stamp = _read_json(d / paper / "reproduce.json")
    kind = ""
    if stamp:
        kind = (f" {'Quick' if stamp.get('quick') else 'Full'} run, mechopt {stamp.get('mechopt', '?')}.")
    import hashlib

    pngs = sorted((d / paper).glob("*.png"), key=_fig_order)
    figs, shown = [], {}
    for png in pngs:
        shown.setdefault(hashlib.sha256(_io.read_bytes(png, _MAX_IMAGE, root=png.parent.parent)).hexdigest(),
                         f"{paper}/{png.name}")
        ref, desc = figure_caption(paper, png.name)
        figs.append(_figure_html(png, ref, desc, f"{paper}/{png.name}"))
    runs = _runs_html(d, paper, shown)
    n_fronts = runs.count("<figure")  # each image once: a copy of another is named, not counted
    html = [f'<section id="{escape(paper)}"><h2>{escape(paper_name(paper))}</h2>',
            f'<p class="title">{escape(TITLES.get(paper, paper))}</p>',
            f'<p class="counts">{escape(counts_line(counts(df)))}.{escape(kind)} '
            f'<code>{escape(paper)}/table.csv</code></p>',
            f'<h3 id="{escape(paper)}-table">Table ({len(df)} rows)</h3>',
            _table_html(df, f"table-{paper}"),
            f'<h3 id="{escape(paper)}-differs">Where we differ, and why</h3>', _differs_html(df),
            f'<h3 id="{escape(paper)}-figures">Figures ({len(pngs)})</h3>',
            f'<div class="figs">{"".join(figs)}</div>' if figs else "<p>No figure was written.</p>",
            f'<h3 id="{escape(paper)}-fronts">Fronts and sweeps ({n_fronts})</h3>',
            runs, "</section>"]
    return "\n".join(html), len(figs) + n_fronts


_CSS = """
:root { --good-bg: #dcf2e0; --good-fg: #11561f; --bad-bg: #fadcda; --bad-fg: #8c1d18;
        --none-bg: #e8e8e8; --none-fg: #4a4a4a; --setting-bg: #e6ebf2; --setting-fg: #34495e;
        --line: #d0d4da; }
* { box-sizing: border-box; }
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif;
       color: #1d2228; background: #fff; margin: 0; }
main { max-width: 1400px; margin: 0 auto; padding: 0 24px 48px; }
header { background: #22303f; color: #fff; padding: 18px 24px; }
header h1 { margin: 0 0 4px; font-size: 24px; }
header p { margin: 0; color: #d6dde6; }
header code { background: rgba(255, 255, 255, 0.14); color: #fff; }
nav { position: sticky; top: 0; z-index: 2; background: #f4f6f8; border-bottom: 1px solid var(--line);
      padding: 8px 24px; font-size: 14px; }
nav a { margin-right: 14px; color: #1f4f8a; text-decoration: none; white-space: nowrap; }
nav a:hover { text-decoration: underline; }
h2 { font-size: 22px; margin: 36px 0 4px; padding-top: 8px; border-top: 3px solid #22303f; }
h3 { font-size: 17px; margin: 24px 0 8px; }
section, h3 { scroll-margin-top: 48px; }
p.title { margin: 0 0 4px; color: #4a5563; font-style: italic; }
p.counts { margin: 4px 0 12px; }
code { font-family: ui-monospace, "DejaVu Sans Mono", monospace; font-size: 0.9em; background: #f1f3f5;
       padding: 0 3px; border-radius: 3px; }
.scroll { overflow: auto; border: 1px solid var(--line); border-radius: 4px; }
.scroll.long { max-height: 80vh; }
table { border-collapse: collapse; width: 100%; font-size: 13px; }
th, td { padding: 4px 8px; border-bottom: 1px solid var(--line); text-align: left; vertical-align: top; }
thead th { position: sticky; top: 0; background: #e9edf2; cursor: pointer; white-space: nowrap;
           user-select: none; }
thead th:hover { background: #dbe2ea; }
thead th::after { content: " \\2195"; color: #8a96a3; font-size: 11px; }
thead th[aria-sort="ascending"]::after { content: " \\25B2"; color: #1d2228; }
thead th[aria-sort="descending"]::after { content: " \\25BC"; color: #1d2228; }
tbody tr:nth-child(even) { background: #fafbfc; }
tfoot td { font-weight: bold; background: #f1f3f5; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.src, td.qty, td.note { overflow-wrap: anywhere; }
td.src { min-width: 8em; }
td.qty { min-width: 8em; }
td.note { min-width: 14em; max-width: 36em; color: #39424d; }
td.note summary { cursor: pointer; }
td.status { font-weight: 600; white-space: nowrap; text-align: center; }
.st-good { background: var(--good-bg); color: var(--good-fg); }
.st-bad { background: var(--bad-bg); color: var(--bad-fg); }
.st-none { background: var(--none-bg); color: var(--none-fg); }
.st-setting { background: var(--setting-bg); color: var(--setting-fg); font-weight: normal; }
.cnt-good { color: var(--good-fg); font-weight: 600; }
.cnt-bad { color: var(--bad-fg); font-weight: 600; }
.cnt-none { color: var(--none-fg); }
.legend span { display: inline-block; padding: 0 8px; margin-right: 6px; border-radius: 3px; font-weight: 600; }
ol.reasons { padding-left: 24px; }
ol.reasons li { margin-bottom: 10px; }
ol.reasons p { margin: 0; }
p.why-src { font-size: 13px; color: #5a6573; font-style: italic; }
p.why, p.why-short { color: #39424d; font-size: 14px; max-width: 70em; }
p.why-check { font-size: 13px; color: #1f4f8a; }
ol.reasons details summary { cursor: pointer; font-size: 13px; color: #5a6573; }
p.same { font-size: 13px; color: #5a6573; }
span.kind { font-weight: normal; font-size: 12px; background: var(--bad-bg); color: var(--bad-fg);
            padding: 0 6px; border-radius: 3px; }
.figs { display: grid; grid-template-columns: repeat(auto-fill, minmax(560px, 1fr)); gap: 18px; }
figure { margin: 0; padding: 8px; border: 1px solid var(--line); border-radius: 4px; background: #fff; }
figure.wide { grid-column: 1 / -1; }
figure img { display: block; max-width: 100%; height: auto; margin: 0 auto; }
figcaption { font-size: 13px; margin-top: 6px; color: #39424d; }
footer { margin-top: 40px; color: #6a7582; font-size: 13px; }
@media print { nav { position: static; } thead th { position: static; } }
"""

#: click a header to sort its table (numbers numerically, empty cells last), again to reverse
_JS = """
(function () {
  "use strict";
  function key(cell) {
    if (!cell) { return ""; }
    var v = cell.getAttribute("data-sort");
    return v === null ? cell.textContent.trim() : v;
  }
  function sortBy(table, col, th) {
    var body = table.tBodies[0];
    var rows = Array.prototype.slice.call(body.rows);
    var keys = rows.map(function (r) { return key(r.cells[col]); });
    var filled = keys.filter(function (k) { return k !== ""; });
    var numeric = filled.length > 0 && filled.every(function (k) { return isFinite(Number(k)); });
    var dir = th.getAttribute("aria-sort") === "ascending" ? -1 : 1;
    var idx = rows.map(function (r, i) { return i; });
    idx.sort(function (a, b) {
      var x = keys[a], y = keys[b];
      if (x === "" || y === "") { return (x === "") - (y === "") || a - b; }
      var c = numeric ? Number(x) - Number(y) : x.localeCompare(y, undefined, {numeric: true});
      return c !== 0 ? dir * c : a - b;
    });
    idx.forEach(function (i) { body.appendChild(rows[i]); });
    Array.prototype.forEach.call(th.parentNode.cells, function (h) { h.removeAttribute("aria-sort"); });
    th.setAttribute("aria-sort", dir === 1 ? "ascending" : "descending");
  }
  Array.prototype.forEach.call(document.querySelectorAll("table.sortable"), function (table) {
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th, col) {
      th.tabIndex = 0;
      th.addEventListener("click", function () { sortBy(table, col, th); });
      th.addEventListener("keydown", function (e) {
        if (e.key === "Enter" || e.key === " ") { e.preventDefault(); sortBy(table, col, th); }
      });
    });
  });
}());
"""

_LEGEND = ('<p class="legend">Status: <span class="st-good">match</span><span class="st-good">holds</span>'
           '<span class="st-bad">differs</span><span class="st-bad">fails</span>'
           '<span class="st-none">not-reported</span><span class="st-setting">setting</span> (an input we '
           'echo, whatever its status) Click a column header to sort its table, again to reverse.</p>')

_COUNTS_TEXT = ("Counts: match and differs are over the quantities the paper computed and we recompute "
                "(computed); readings are rows shown on purpose under another reading of the paper or "
                "another quadrature (and how many of them match), settings inputs we echo, claims "
                "sentences of the paper checked true or false; not-reported rows are quantities the "
                "paper prints no value for.")


def build_report(results_dir) -> str:
    """The HTML text of the report of ``results_dir`` (see the module docstring).

    ValueError (one line) when ``results_dir`` is missing, not a folder, or holds no
    reproduced paper.

    Parameters
    ----------
    results_dir : str or Path
        The folder of ``mechopt reproduce``.

    Returns
    -------
    str
        The HTML page.

    Raises
    ------
    ValueError
        One line, for a missing folder or one without a reproduced paper.
    """
    d = _check_dir(results_dir)
    papers = [p for p in PAPERS if (d / p / "table.csv").is_file()]
    for p in papers:
        _read_table(d, p)  # every table is readable before counting
    summary = summary_table(d)
    sections, n_images = [], 0
    for p in papers:
        html, n = _paper_html(d, p)
        sections.append(html)
        n_images += n
    nav = ['<a href="#summary-section">Summary</a>']
    for p in papers:
        nav.append(f'<a href="#{escape(p)}">{escape(paper_name(p))}</a>')
    missing = [p for p in PAPERS if p not in papers]
    missing_txt = (f"<p>Not reproduced in this folder: {escape(', '.join(paper_name(p) for p in missing))}.</p>"
                   if missing else "")
    total = summary[summary["paper"] == "total"]
    headline = ""
    if len(total):
        t = total.iloc[0].to_dict()
        headline = f"<p><strong>{escape(counts_line(t))}.</strong></p>"
    text = f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>mechopt reproduction report: {escape(d.name or str(d))}</title>
<link rel="icon" href="data:,">
<style>{_CSS}</style>
</head>
<body>
<header><h1>Reproduction of {len(papers)} paper{'s' if len(papers) != 1 else ''}</h1>
<p>mechopt {escape(__version__)} &middot; results folder <code>{escape(str(d))}</code> &middot;
{n_images} figures, fronts and sweeps</p></header>
<nav>{''.join(nav)}</nav>
<main>
<section id="summary-section"><h2>Summary</h2>
{headline}
<p>{escape(_COUNTS_TEXT)}</p>
{_LEGEND}
{_summary_html(summary)}
{missing_txt}
</section>
{''.join(sections)}
<footer>Written by <code>mechopt report</code> from <code>{escape(str(d))}</code>; self-contained
(images embedded, no network access needed).</footer>
</main>
<script>{_JS}</script>
</body>
</html>
"""
    return text.encode("ascii", "xmlcharrefreplace").decode("ascii")


def write_report(results_dir="results", out=None) -> Path:
    """Write the report of ``results_dir`` to ``out`` (default ``<results_dir>/report.html``)
    atomically; returns its path.

    Parameters
    ----------
    results_dir : str or Path
        The folder of ``mechopt reproduce``.
    out : str or Path, optional
        The page (default ``<results_dir>/report.html``).

    Returns
    -------
    Path
        The page written.

    Raises
    ------
    ValueError
        One line, for a missing folder or one without a reproduced paper.
    """
    html = build_report(results_dir)
    out = Path(results_dir) / "report.html" if out is None else Path(out)
    if not str(out).strip() or out.is_dir():
        raise ValueError(f"--out must name an HTML file, got the folder {str(out)!r}")
    return _io.write_text(out, html)
