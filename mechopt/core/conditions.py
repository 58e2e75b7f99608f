"""Conditions on table columns, such as ``"r_mic > 0.8 and gci > 0.6"``.

A small grammar, parsed by recursive descent (never ``eval``)::

    condition  := or_expr
    or_expr    := and_expr ("or" and_expr)*
    and_expr   := not_expr ("and" not_expr)*
    not_expr   := "not" not_expr | primary
    primary    := "(" or_expr ")" | comparison
    comparison := operand OP operand (OP operand)*      # chained as in Python
    operand    := NAME | NUMBER | ("-" | "+") operand
    OP         := "<" | "<=" | ">" | ">=" | "==" | "!="

``and`` binds tighter than ``or``; ``a < b < c`` means ``a < b and b < c``.
NAME is a column name (letters, digits, ``_``); NUMBER a decimal number with an
optional exponent. A comparison involving NaN is False (including ``!=``), so a
design without a value never satisfies a comparison on it (``not`` negates that
False: ``not (gci > 0.6)`` holds for a design whose GCI is NaN).

Usage::

    cond = parse_condition("r_mic > 0.8 and gci > 0.6", names=df.columns)
    mask = cond.evaluate(df)          # boolean array, one entry per row
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Iterable, Mapping

import numpy as np

__all__ = ["Condition", "parse_condition"]

_TOKEN = re.compile(
    r"\s*(?:"
    r"(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
    r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op><=|>=|==|!=|<|>)"
    r"|(?P<paren>[()])"
    r"|(?P<sign>[+-])"
    r")"
)
_KEYWORDS = ("and", "or", "not")
_OPS = {
    "<": np.less,
    "<=": np.less_equal,
    ">": np.greater,
    ">=": np.greater_equal,
    "==": np.equal,
    "!=": np.not_equal,
}


@dataclass(frozen=True)
class _Tok:
    kind: str  # number, name, keyword, op, paren, sign, end
    text: str
    pos: int


def _tokenize(text: str, param: str) -> list[_Tok]:
    toks = []
    pos = 0
    n = len(text)
    while pos < n:
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            bad = text[pos:].lstrip()[:1]
            at = n - len(text[pos:].lstrip())
            raise ValueError(f"{param}: unexpected character {bad!r} at position {at} in {text!r}")
        kind = m.lastgroup
        value = m.group(kind)
        start = m.start(kind)
        if kind == "name" and value.lower() in _KEYWORDS:
            kind, value = "keyword", value.lower()
        toks.append(_Tok(kind, value, start))
        pos = m.end()
    toks.append(_Tok("end", "", n))
    return toks


# --- syntax tree -----------------------------------------------------------
@dataclass(frozen=True)
class _Num:
    value: float

    def eval(self, cols):
        return self.value

    def __str__(self):
        return repr(self.value)


@dataclass(frozen=True)
class _Name:
    name: str

    def eval(self, cols):
        return np.asarray(cols[self.name], dtype=float)

    def __str__(self):
        return self.name


@dataclass(frozen=True)
class _Neg:
    arg: object

    def eval(self, cols):
        return -self.arg.eval(cols)

    def __str__(self):
        return f"-{self.arg}"


@dataclass(frozen=True)
class _Cmp:
    operands: tuple
    ops: tuple

    def eval(self, cols):
        vals = [o.eval(cols) for o in self.operands]
        out = True
        for op, a, b in zip(self.ops, vals, vals[1:]):
            with np.errstate(invalid="ignore"):
                res = _OPS[op](a, b) & ~np.isnan(a) & ~np.isnan(b)
            out = out & res
        return out

    def __str__(self):
        parts = [str(self.operands[0])]
        for op, o in zip(self.ops, self.operands[1:]):
            parts += [op, str(o)]
        return " ".join(parts)


@dataclass(frozen=True)
class _BoolOp:
    op: str  # "and" | "or"
    args: tuple

    def eval(self, cols):
        vals = [a.eval(cols) for a in self.args]
        out = vals[0]
        for v in vals[1:]:
            out = (out & v) if self.op == "and" else (out | v)
        return out

    def __str__(self):
        return "(" + f" {self.op} ".join(str(a) for a in self.args) + ")"


@dataclass(frozen=True)
class _Not:
    arg: object

    def eval(self, cols):
        return ~np.asarray(self.arg.eval(cols), dtype=bool)

    def __str__(self):
        return f"not ({self.arg})"


#: deepest nesting of "not", parentheses and signs (recursive descent: Python's stack)
MAX_DEPTH = 100


class _Parser:
    def __init__(self, text: str, param: str):
        self.text = text
        self.param = param
        self.toks = _tokenize(text, param)
        self.i = 0
        self.depth = 0

    def _nested(self, parse):
        """``parse()`` one level deeper (after a "not", a "(" or a sign)."""
        if self.depth >= MAX_DEPTH:
            raise ValueError(f"{self.param}: the condition nests deeper than {MAX_DEPTH} levels "
                             f"(at position {self.tok.pos})")
        self.depth += 1
        try:
            return parse()
        finally:
            self.depth -= 1

    @property
    def tok(self) -> _Tok:
        return self.toks[self.i]

    def _fail(self, what: str):
        t = self.tok
        found = "the end" if t.kind == "end" else repr(t.text)
        raise ValueError(f"{self.param}: expected {what} at position {t.pos}, found {found}, in {self.text!r}")

    def _take(self, kind, text=None):
        t = self.tok
        if t.kind == kind and (text is None or t.text == text):
            self.i += 1
            return t
        return None

    def parse(self):
        if self.tok.kind == "end":
            raise ValueError(f"{self.param}: the condition is empty")
        node = self.or_expr()
        if self.tok.kind != "end":
            self._fail("'and', 'or' or the end")
        return node

    def or_expr(self):
        args = [self.and_expr()]
        while self._take("keyword", "or"):
            args.append(self.and_expr())
        return args[0] if len(args) == 1 else _BoolOp("or", tuple(args))

    def and_expr(self):
        args = [self.not_expr()]
        while self._take("keyword", "and"):
            args.append(self.not_expr())
        return args[0] if len(args) == 1 else _BoolOp("and", tuple(args))

    def not_expr(self):
        if self._take("keyword", "not"):
            return _Not(self._nested(self.not_expr))
        return self.primary()

    def primary(self):
        if self._take("paren", "("):
            node = self._nested(self.or_expr)
            if not self._take("paren", ")"):
                self._fail("')'")
            return node
        return self.comparison()

    def comparison(self):
        operands = [self.operand()]
        ops = []
        while self.tok.kind == "op":
            ops.append(self.tok.text)
            self.i += 1
            operands.append(self.operand())
        if not ops:
            self._fail("a comparison operator (<, <=, >, >=, ==, !=)")
        return _Cmp(tuple(operands), tuple(ops))

    def operand(self):
        t = self.tok
        if t.kind == "sign":
            self.i += 1
            arg = self._nested(self.operand)
            return _Neg(arg) if t.text == "-" else arg
        if t.kind == "number":
            self.i += 1
            return _Num(float(t.text))
        if t.kind == "name":
            self.i += 1
            return _Name(t.text)
        self._fail("a name or a number")


def _names(node) -> set:
    if isinstance(node, _Name):
        return {node.name}
    out = set()
    for attr in ("arg", "args", "operands"):
        sub = getattr(node, attr, None)
        if sub is None:
            continue
        for s in (sub if isinstance(sub, tuple) else (sub,)):
            out |= _names(s)
    return out


@dataclass(frozen=True)
class Condition:
    """A parsed condition: :meth:`evaluate` it on columns; ``names`` it uses.

    Parameters
    ----------
    text : str
        The condition as written.
    tree : object
        The parsed expression.
    names : frozenset of str
        The column names it uses.
    """

    text: str
    tree: object
    names: frozenset

    def evaluate(self, columns: Mapping) -> np.ndarray:
        """Boolean array over the rows of ``columns`` (a DataFrame or a dict of arrays).

        Parameters
        ----------
        columns : DataFrame or dict
            Columns by name (arrays of one length).

        Returns
        -------
        ndarray of bool
            One value per row.

        Raises
        ------
        ValueError
            One line naming a column the condition uses that ``columns`` lacks.
        """
        missing = sorted(n for n in self.names if n not in columns)
        if missing:
            raise ValueError(f"where: unknown name {missing[0]!r}")
        n = len(next(iter(columns.values())) if isinstance(columns, dict) else columns)
        out = np.asarray(self.tree.eval(columns), dtype=bool)
        return np.broadcast_to(out, (n,)).copy()

    def __str__(self):
        return str(self.tree)


def parse_condition(text, names: Iterable[str] | None = None, param: str = "where") -> Condition:
    """Parse ``text`` (grammar in the module docstring). With ``names``, every
    name in the condition must be one of them. Raises ValueError with one line
    naming ``param``, the position and what was expected.

    Parameters
    ----------
    text : str
        The condition (``"r_mic > 0.8 and gci > 0.6"``).
    names : iterable of str, optional
        The allowed column names.
    param : str
        The option's name, for the message.

    Returns
    -------
    Condition
        The parsed condition.

    Raises
    ------
    ValueError
        One line naming ``param``, the position and what was expected.
    """
    if not isinstance(text, str):
        raise ValueError(f"{param} must be a string, got {text!r}")
    tree = _Parser(text, param).parse()
    used = frozenset(_names(tree))
    if names is not None:
        allowed = list(names)
        for n in sorted(used):
            if n not in allowed:
                raise ValueError(
                    f"{param}: unknown name {n!r} in {text!r}; allowed: {', '.join(allowed)}")
    return Condition(text, tree, used)
