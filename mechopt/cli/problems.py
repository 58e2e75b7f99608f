"""``mechopt problems``: every registered problem, one line each (its name and summary).

The list is :func:`mechopt.problems.available`; the names are what ``mechopt optimize``
and ``mechopt sweep`` take.
"""
from __future__ import annotations

NAME = "problems"


def add_parser(subparsers):
    """Register ``problems``."""
    subparsers.add_parser(NAME, help="list every registered problem, one line each")


def run(args) -> int:
    """Print the names, aligned, and their summaries."""
    from mechopt.problems import available

    rows = available()
    w = max(len(n) for n, _ in rows)
    for name, summary in rows:
        print(f"{name:<{w}}  {summary}")
    return 0
