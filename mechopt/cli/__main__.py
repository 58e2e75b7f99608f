"""``python -m mechopt.cli``: the ``mechopt`` command."""
from mechopt.cli import console

console()
