"""Published numbers of the source papers and their side-by-side comparison.

Each paper's printed values live in ``mechopt/data/<paper>.csv``, one row per printed
number, with the columns ``design, quantity, value, unit, digits, source, accuracy``:
the value in the unit the paper prints it in, its printed decimals, where the paper
prints it (section, table, figure or equation; the plain-text extractions have no
page numbers) and its accuracy class (:data:`ACCURACY`). The experiments
(``experiments/<paper>.py``) take every printed number from there, through this
module only:

* :func:`lookup` ``(paper, quantity, design)`` gives the :class:`Record` of one printed
  number (``value``, ``unit``, ``digits``, ``source``, ``accuracy``); :func:`records`
  all of a paper's, in the order of its file;
* :func:`compare` ``(record, reproduced)`` gives the table row (columns
  :data:`TABLE_COLUMNS`) that sets our value beside it; :func:`not_reported` and
  :func:`claim_row` the rows of quantities the paper prints no number for.

A reproduced value *matches* when it lies within the tolerance of its record, in the
printed unit::

    tol = max(half a unit of the last printed digit,
              rel * |published|,          # a relative accuracy of the quantity's class
              abs + of_span * span)       # an absolute accuracy in the printed unit

``rel``, ``abs`` and ``of_span`` are those of the record's accuracy class, one of
:data:`ACCURACY`: the one place where a tolerance beyond the printed digits is set,
each with its reason, per class of quantity and never tuned per row. ``printed`` (only
the printed digits) is the class of inputs, settings and closed forms. ``of_span``
serves classes whose error scales with a length of the problem rather than with the
value (the design range of a GA optimum; the crank angle per unit length of an
actuator angle): the comparison passes that ``span``.

Every row has a ``kind`` (:data:`KINDS`), so that the counts are honest:

``computed``  a quantity the paper computed and we recompute: the only rows
              whose ``match``/``differs`` are counted as reproduction results;
``setting``   an input or algorithm setting we echo (population, generations):
              its agreement shows nothing;
``reading``   a value shown on purpose under another reading of the paper or
              another quadrature, beside the literal row;
``claim``     a checkable sentence of the paper, ``holds`` or ``fails`` with the
              computed evidence in the note.

``status`` is one of :data:`STATUSES`; ``not-reported`` when the paper prints no value.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np
import pandas as pd

__all__ = ["TABLE_COLUMNS", "STATUSES", "KINDS", "Accuracy", "ACCURACY", "Record", "cite", "load",
           "records", "lookup", "printed_half_unit", "tolerance", "compare", "not_reported",
           "claim_row", "counts"]

TABLE_COLUMNS = ("quantity", "source", "paper", "reproduced", "unit", "rel_error", "status",
                 "kind", "note")
STATUSES = ("match", "differs", "not-reported", "holds", "fails")
KINDS = ("computed", "setting", "reading", "claim")


@dataclass(frozen=True)
class Accuracy:
    """An accuracy class: how far a reproduction may lie from a printed value beyond
    half a unit of its last printed digit (module docstring).

    Parameters
    ----------
    rel : float
        Relative accuracy, a fraction of ``|published|`` [-].
    abs : float
        Absolute accuracy, in the record's unit.
    of_span : float
        Absolute accuracy as a fraction of a ``span`` the comparison passes (in the
        record's unit): the design range of an optimum, the crank angle of a unit length.
    reason : str
        Why the class has this accuracy (shown nowhere but here: the note of a row names
        the resulting tolerance).
    """

    rel: float = 0.0
    abs: float = 0.0
    of_span: float = 0.0
    reason: str = ""

    def absolute(self, span: float | None = None) -> float:
        """The absolute part ``abs + of_span * span`` [record's unit]; ``span`` is
        required when ``of_span`` is set (ValueError otherwise).

        Parameters
        ----------
        span : float, optional
            The span [record's unit] (required with ``of_span``).

        Returns
        -------
        float
            The absolute part [record's unit].

        Raises
        ------
        ValueError
            When ``of_span`` is set and ``span`` is not given.
        """
        if not self.of_span:
            return self.abs
        if span is None:
            raise ValueError("this accuracy class is a fraction of a span: pass span=")
        return self.abs + self.of_span * float(span)


#: the accuracy classes, named in the ``accuracy`` column of the data files
ACCURACY = {
    "printed": Accuracy(reason=(
        "the printed digits alone: inputs, settings, closed forms and exact readings, whose "
        "only uncertainty is the paper's rounding")),
    "mic_radius": Accuracy(rel=0.005, reason=(
        "radius of the maximal inscribed circle of a workspace (Liu 2006 sec. 3.1): a distance "
        "to the workspace's boundary, found on a grid whose resolution the paper does not state")),
    "global_mean": Accuracy(rel=0.01, reason=(
        "a global mean over a workspace (Liu 2006's GCI, GVI, GPI, GSI over the MIW or the GCW; "
        "Wu 2008's k_av, eq. 6-7) whose quadrature or resolution the paper does not state: its "
        "own numerical error is of this order")),
    "raster": Accuracy(rel=0.01, reason=(
        "an area or a size read off a raster of unstated resolution (Liu 2006's usable "
        "workspace, GCW and largest square, and the D, R_i the paper derives from them; Stan "
        "2008's workspace area, if a raster count, eq. 1-3): a raster count's error scales "
        "with the workspace")),
    "crank_angle": Accuracy(of_span=0.01, reason=(
        "an actuator angle [deg] at the boundary of a raster workspace (Liu 2006 sec. 3.2.3): "
        "an error of the raster class, 1 % of the length unit L, moves a boundary pose by "
        "0.01 L, which turns a crank of length r1 by 0.01 L / r1 rad; span = degrees(L / r1). "
        "Absolute: the same for 36 deg as for 276 deg (1 % of 276 deg would be 2.8 deg)")),
    "ga_optimum": Accuracy(of_span=0.01, reason=(
        "the optimum of a one-variable design range found by a GA (Stan 2008 Tables 2-3): 1 % "
        "of the range (span = upper - lower bound), absolute in the variable. The paper's GAOT "
        "run, its unstated normalisation of W and aggregation of T make its optima no more "
        "precise than that; the location error of an optimum does not scale with its value")),
    "propagated": Accuracy(of_span=1.0, reason=(
        "a reading that recomputes a printed value from other printed values by the paper's own "
        "formula: span = half a unit of the last printed digit of an input times the formula's "
        "sensitivity to it (Liu 2006 sec. 3.2.3: D^2 for eta_D of the scaled mechanism)")),
    "square_search": Accuracy(abs=1e-5, reason=(
        "our accuracy of a square side [l1] (Le 2013): the square search bisects to 1e-6 "
        "relative on 257 points per edge (corners included, where the LCI binds) and agrees "
        "with the exact corner roots to about 1e-6; finer than the printed half digit (5e-5), "
        "which therefore sets the tolerance")),
}


def cite(paper: str, where: str) -> str:
    """``"<Author> <year> <where>"``, e.g. ``cite("liu2006", "sec. 2.2")`` is
    ``"Liu 2006 sec. 2.2"``: the source of a row of ``paper``.

    Parameters
    ----------
    paper : str
        The paper's key.
    where : str
        The place in it (``"sec. 2.2"``).

    Returns
    -------
    str
        The citation.
    """
    name, year = paper[:-4], paper[-4:]
    return f"{name.capitalize()} {year} {where}"


@dataclass(frozen=True)
class Record:
    """One printed number of a data file: ``value`` [``unit``] printed with ``digits``
    decimals at ``source`` of ``paper``, for ``design``; ``accuracy`` names its class
    in :data:`ACCURACY`.

    Parameters
    ----------
    paper : str
        The paper's key (``"liu2006"``).
    design : str
        The design the number belongs to.
    quantity : str
        What the number is.
    value : float
        The printed number [unit].
    unit : str
        Its unit.
    digits : int
        Printed decimals.
    source : str
        Where the paper prints it.
    accuracy : str
        A key of :data:`ACCURACY`.
    """

    paper: str
    design: str
    quantity: str
    value: float
    unit: str
    digits: int
    source: str
    accuracy: str = "printed"

    @property
    def citation(self) -> str:
        """``"<Author> <year> <source>"``, e.g. ``"Liu 2006 sec. 3.1.1, text of Fig. 8"``."""
        return cite(self.paper, self.source)

    @property
    def printed(self) -> str:
        """The value as printed: ``digits`` decimals (``"4693.33"``; decimal points)."""
        return f"{self.value:.{self.digits}f}"


def _open(paper: str):
    try:
        return resources.files("mechopt.data").joinpath(f"{paper}.csv").open("r")
    except FileNotFoundError:
        raise ValueError(f"paper must name a data file of mechopt/data, got {paper!r}") from None


def load(paper: str) -> pd.DataFrame:
    """The published values of ``paper`` (e.g. ``"liu2006"``) as a DataFrame (the
    columns of the data file).

    Parameters
    ----------
    paper : str
        The paper's key.

    Returns
    -------
    DataFrame
        The data file's rows.
    """
    with _open(paper) as fh:
        return pd.read_csv(fh, comment="#", dtype={"design": str})


@lru_cache(maxsize=None)
def records(paper: str) -> tuple:
    """Every :class:`Record` of ``mechopt/data/<paper>.csv``, in the order of the file
    (read once).

    Parameters
    ----------
    paper : str
        The paper's key.

    Returns
    -------
    tuple of Record
        The records.
    """
    with _open(paper) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    return tuple(Record(paper, r["design"], r["quantity"], float(r["value"]), r["unit"],
                        int(r["digits"]), r["source"], r.get("accuracy") or "printed")
                 for r in rows)


def lookup(paper: str, quantity: str, design: str | None = None) -> Record:
    """The :class:`Record` of one printed number.

    Parameters
    ----------
    paper : str
        The data file, e.g. ``"le2013"`` (``mechopt/data/le2013.csv``).
    quantity : str
        The ``quantity`` column, e.g. ``"a_max"``.
    design : str, optional
        The ``design`` column, when the paper prints ``quantity`` for several designs.

    Returns
    -------
    Record
        ``value`` [``unit``], printed ``digits``, ``source``, ``accuracy``.

    Raises
    ------
    ValueError
        If no row or more than one row fits.
    """
    sel = [r for r in records(paper)
           if r.quantity == quantity and (design is None or r.design == design)]
    if len(sel) != 1:
        where = f" for design {design!r}" if design is not None else ""
        raise ValueError(f"{paper}: {len(sel)} rows of {quantity!r}{where} (need exactly one)")
    return sel[0]


def printed_half_unit(digits: int) -> float:
    """Half a unit of the last printed decimal: 0.00005 for 4 decimals.

    Parameters
    ----------
    digits : int
        Printed decimals.

    Returns
    -------
    float
        ``0.5 * 10**-digits``.
    """
    return 0.5 * 10.0 ** (-int(digits))


def _accuracy(record: Record, accuracy) -> Accuracy:
    if isinstance(accuracy, Accuracy):
        return accuracy
    name = record.accuracy if accuracy is None else accuracy
    if name not in ACCURACY:
        raise ValueError(f"accuracy must be one of {tuple(ACCURACY)} or an Accuracy, got {name!r}")
    return ACCURACY[name]


def tolerance(record: Record, *, accuracy=None, span: float | None = None) -> float:
    """The acceptance tolerance of ``record`` [``record.unit``] (module docstring).

    Parameters
    ----------
    record : Record
        The printed number.
    accuracy : str or Accuracy, optional
        Its class; default ``record.accuracy``. ``"printed"`` for a reading whose only
        uncertainty is the paper's rounding, an :class:`Accuracy` for one that follows
        from printed digits propagated through a formula.
    span : float, optional
        The span of a class with ``of_span`` [``record.unit``].

    Returns
    -------
    float
        The tolerance [``record.unit``].
    """
    acc = _accuracy(record, accuracy)
    return max(printed_half_unit(record.digits), acc.rel * abs(record.value), acc.absolute(span))


def _check_kind(kind):
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")


def compare(record: Record, reproduced, *, note: str = "", kind: str = "computed",
            quantity: str | None = None, accuracy=None, span: float | None = None) -> dict:
    """One table row setting ``reproduced`` beside ``record``.

    Parameters
    ----------
    record : Record
        The printed number (:func:`lookup`): value, unit, digits, source.
    reproduced : float
        Our value, in ``record.unit``.
    note : str
        How ours was computed and why it differs; the tolerance is appended.
    kind : str
        One of :data:`KINDS`.
    quantity : str, optional
        The row's name; default ``record.quantity`` (e.g. ``"workspace_area[b=62mm]"``
        for a reading).
    accuracy, span
        As in :func:`tolerance`.

    Returns
    -------
    dict
        The row (keys :data:`TABLE_COLUMNS`): ``status`` ``match`` within the tolerance,
        else ``differs``; the note ends with ``tol <t> <unit> (max of ...)``.
    """
    _check_kind(kind)
    acc = _accuracy(record, accuracy)
    paper, unit = record.value, record.unit
    half = printed_half_unit(record.digits)
    abs_tol = acc.absolute(span)
    tol = max(half, abs_tol, acc.rel * abs(paper))
    err = reproduced - paper
    rel = err / abs(paper) if paper != 0 else np.inf
    parts = [f"half last digit {half:.3g}"]
    if abs_tol:
        parts.append(f"{abs_tol:.3g} {unit}")
    if acc.rel:
        parts.append(f"{acc.rel:.1%}")
    tol_note = f"tol {tol:.3g} {unit} (max of {', '.join(parts)})"
    return dict(quantity=quantity or record.quantity, source=record.citation, paper=float(paper),
                reproduced=float(reproduced), unit=unit, rel_error=float(rel),
                status="match" if abs(err) <= tol else "differs", kind=kind,
                note=f"{note}; {tol_note}" if note else tol_note)


def not_reported(quantity: str, source: str, reproduced, unit: str, note: str = "",
                 kind: str = "computed") -> dict:
    """A row of a quantity the paper prints no number for (only a map or a curve):
    status ``not-reported``, ``paper`` and ``rel_error`` NaN.

    Parameters
    ----------
    quantity, source : str
        The row's name and where the paper defines or shows the quantity (:func:`cite`).
    reproduced : float
        Our value [``unit``].
    unit : str
        Our unit.
    note, kind : str
        As in :func:`compare`.

    Returns
    -------
    dict
        The row (the columns of table.csv).
    """
    _check_kind(kind)
    return dict(quantity=quantity, source=source, paper=np.nan, reproduced=reproduced, unit=unit,
                rel_error=np.nan, status="not-reported", kind=kind, note=note)


def claim_row(quantity: str, source: str, holds: bool, evidence: str) -> dict:
    """A checked claim of the paper: status ``holds``/``fails``, the evidence in the note
    (``reproduced`` is 1.0 or 0.0 so that the column stays numeric).

    Parameters
    ----------
    quantity : str
        The claim's name.
    source : str
        Where the paper states it.
    holds : bool
        Whether it holds.
    evidence : str
        What shows it.

    Returns
    -------
    dict
        The row.
    """
    return dict(quantity=quantity, source=source, paper=np.nan, reproduced=float(bool(holds)),
                unit="-", rel_error=np.nan, status="holds" if holds else "fails", kind="claim",
                note=evidence)


def counts(table: pd.DataFrame) -> dict:
    """The honest counts of a table: ``match``/``differs`` over the ``computed`` rows
    only; the other kinds and ``not-reported`` rows counted on their own.

    Parameters
    ----------
    table : DataFrame
        A reproduction table (table.csv).

    Returns
    -------
    dict
        Counts by kind and status.
    """
    kind = table["kind"] if "kind" in table else pd.Series("computed", index=table.index)
    status = table["status"]
    comp = kind == "computed"
    return {
        "computed": int((comp & status.isin(["match", "differs"])).sum()),
        "match": int((comp & (status == "match")).sum()),
        "differs": int((comp & (status == "differs")).sum()),
        "readings": int((kind == "reading").sum()),
        "readings matching": int(((kind == "reading") & (status == "match")).sum()),
        "settings": int((kind == "setting").sum()),
        "not-reported": int((status == "not-reported").sum()),
        "claims hold": int((status == "holds").sum()),
        "claims fail": int((status == "fails").sum()),
    }
