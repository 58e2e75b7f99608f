"""Tables of the documentation rendered from the package at build time (so that they
are always current): the ``{requirements-table}`` and ``{objectives-table}``
directives list every member of :func:`mechopt.requirements.registry`, with its
options, its margin and unit, and its certificate (how its value is established over
the whole task)."""
from __future__ import annotations

from docutils import nodes
from docutils.parsers.rst import Directive


def _table(header, rows, widths):
    table = nodes.table()
    group = nodes.tgroup(cols=len(header))
    table += group
    for w in widths:
        group += nodes.colspec(colwidth=w)
    head = nodes.thead()
    group += head
    body = nodes.tbody()
    group += body
    for target, cells in ((head, [header]), (body, rows)):
        for cells_row in cells:
            row = nodes.row()
            for text in cells_row:
                entry = nodes.entry()
                entry += nodes.paragraph(text=text)
                row += entry
            target += row
    return table


def _unit(template):
    return template.replace("{L}", "[L]").replace("{T}", "N m or N")


def requirement_rows():
    """``[name, options, margin [unit], certificate, proven]`` of every declared requirement."""
    from mechopt.requirements import requirements

    return [[r.name, ", ".join(o.flag for o in r.options) or "(always)",
             f"{r.margin_text} [{_unit(r.margin_unit)}]", r.certificate, "yes" if r.proven else "no"]
            for r in requirements()]


def objective_rows():
    """``[name, sense, unit, description, needs]`` of every declared objective."""
    from mechopt.requirements import objectives

    return [[o.name, "maximised" if o.sense < 0 else "minimised", _unit(o.unit), o.description,
             ", ".join("--" + n.replace("_", "-") for n in o.requires) or "-"]
            for o in objectives().values()]


class RequirementsTable(Directive):
    def run(self):
        return [_table(["requirement", "options", "margin [unit]", "certificate", "proven"],
                       requirement_rows(), [12, 18, 30, 40, 8])]


class ObjectivesTable(Directive):
    def run(self):
        return [_table(["objective", "sense", "unit", "meaning", "needs"], objective_rows(), [12, 10, 8, 50, 20])]


def setup(app):
    app.add_directive("requirements-table", RequirementsTable)
    app.add_directive("objectives-table", ObjectivesTable)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
