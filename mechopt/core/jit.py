"""The one numba switch: whether mechopt's compiled kernels are used, and how they are compiled.

numba is optional (the ``fast`` extra). The environment variable ``MECHOPT_NO_NUMBA``
(any value but ``""`` and ``"0"``) forces the NumPy paths; it is read here only, once,
when this module is imported. Importing this module does not import numba (about
0.3 s): :func:`load_numba` does, the first time a kernel needs it.

A kernel's formula is written once, as a plain Python function of scalars:

* :func:`jitable` marks a formula that compiled kernels call. It stays a plain Python
  function (a NumPy path calls it with arrays, a one-design path with floats) and
  numba compiles it into each kernel that calls it. Formulas that both paths share
  are written with operators and NumPy functions that mean the same on floats and on
  arrays (``np.sqrt``, ``np.maximum``, ``abs``, ``&``) and :func:`select` for a
  choice; a NumPy caller wraps them in ``np.errstate``.
* :func:`njit` compiles a kernel called from Python (a loop over points or designs),
  or leaves it as plain Python without numba.

numba's on-disk cache knows only the source file of the function it compiles, while
a kernel calls formulas of other modules (the five-bar kernels call
:func:`mechopt.core.indices.lci_of_entries`, for example): a cache keyed on the
kernel's file alone would keep running an edited formula's old code. So the cache
lives in a directory named by a digest of every source file of the package
(:func:`cache_dir`): any edit, or another version, compiles into a fresh directory.
"""
from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import os
import time
from pathlib import Path

import numpy as np

__all__ = ["HAVE_NUMBA", "numba_wanted", "load_numba", "use_numba", "njit", "jitable", "select", "cache_dir",
           "Twin", "TWIN_AFTER_SECONDS", "objmode", "twin_params"]

#: the environment variable that disables numba
ENV_VAR = "MECHOPT_NO_NUMBA"
#: options of every compiled function: no GIL held, and NumPy's floating-point error
#: model (``x / 0`` gives inf or NaN as in the NumPy paths instead of raising)
OPTIONS = dict(nogil=True, error_model="numpy")


def numba_wanted() -> bool:
    """numba is installed (found, not imported) and ``MECHOPT_NO_NUMBA`` does not disable it.

    Returns
    -------
    bool
        Whether numba will be used.
    """
    if os.environ.get(ENV_VAR, "") not in ("", "0"):
        return False
    return importlib.util.find_spec("numba") is not None


#: the compiled kernels are used (:func:`numba_wanted` at import)
HAVE_NUMBA = numba_wanted()

_numba = None  # the numba module once loaded
_pending = []  # (function, options) marked jitable before numba was loaded


def _source_digest() -> str:
    """sha256 (16 hex digits) of the package's source files, paths and bytes."""
    root = Path(__file__).resolve().parents[1]
    h = hashlib.sha256()
    for f in sorted(root.rglob("*.py")):
        h.update(f.relative_to(root).as_posix().encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()[:16]


def cache_dir() -> Path:
    """Where the compiled kernels are cached: ``numba-<digest>`` (:func:`_source_digest`)
    under ``$NUMBA_CACHE_DIR`` when it is set, else under ``$XDG_CACHE_HOME/mechopt``
    (``~/.cache/mechopt``).

    Returns
    -------
    Path
        The folder.
    """
    base = os.environ.get("NUMBA_CACHE_DIR") or (
        Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "mechopt")
    return Path(base) / f"numba-{_source_digest()}"


def load_numba():
    """The numba module, imported on the first call (None when :data:`HAVE_NUMBA` is
    False). Registers the formulas marked :func:`jitable` so far.

    Returns
    -------
    module or None
        numba.
    """
    global _numba
    if _numba is None and HAVE_NUMBA:
        import numba
        from numba.extending import overload, register_jitable

        # read by numba when each cached kernel is made (njit below), not at its import
        numba.config.CACHE_DIR = str(cache_dir())

        # compiled as a function that LLVM inlines (numba's IR inliner warns about the branch)
        @overload(select, jit_options=dict(error_model=OPTIONS["error_model"]))
        def _select(cond, a, b):  # in compiled code a branch on a scalar condition
            def impl(cond, a, b):
                return a if cond else b
            return impl

        _numba = numba
        global objmode
        objmode = numba.objmode
        for fn, options in _pending:
            register_jitable(**options)(fn)
        _pending.clear()
    return _numba


def use_numba(flag=None) -> bool:
    """Whether a kernel's compiled path runs: ``flag=None`` when numba is available,
    else ``flag`` (True without numba is an error naming the extra to install).

    Parameters
    ----------
    flag : bool, optional
        Force the compiled path on (True) or off (False).

    Returns
    -------
    bool
        Whether the compiled path runs.

    Raises
    ------
    ValueError
        For ``flag=True`` without numba (naming the ``fast`` extra).
    """
    if flag is None:
        return HAVE_NUMBA
    if flag and not HAVE_NUMBA:
        raise ValueError("numba is not installed: pip install 'mechopt[fast]'")
    return bool(flag)


def select(cond, a, b):
    """``a`` where ``cond``, else ``b``: ``np.where`` for arrays; in compiled code the
    branch ``a if cond else b`` on scalars (both are evaluated first in either case).

    Parameters
    ----------
    cond : bool or ndarray
        The condition.
    a, b : float or ndarray
        The two choices.

    Returns
    -------
    float or ndarray
        The selection.
    """
    return np.where(cond, a, b)


def objmode(**types):
    """A block of a compiled kernel that the interpreter runs (numba's ``objmode``,
    the variables it assigns typed by ``types``, e.g. ``a="float64[:]"``): where a
    kernel needs NumPy's own functions (its ``arccos`` and ``arctan2`` differ from the
    C library's in the last bit, :class:`Twin`). Before numba is loaded, and in plain
    Python, an empty context. Compiled code refers to it as ``jit.objmode`` (the name is
    looked up when a kernel compiles, after :func:`load_numba`).

    Parameters
    ----------
    **types
        numba type strings of the variables the block assigns.

    Returns
    -------
    contextlib.AbstractContextManager
        An empty context.
    """
    return contextlib.nullcontext()


def jitable(fn):
    """Mark the plain Python function ``fn`` as callable from compiled kernels and
    return it unchanged (Python callers, with floats or arrays, run it as Python).

    numba compiles it, with :data:`OPTIONS`, for the kernels that call it and links it
    into them, where LLVM inlines the small ones (numba's own IR inlining,
    ``inline="always"``, is not used: it multiplies the compile time of kernels that
    call many formulas). Nothing is imported before numba is loaded (:func:`load_numba`).

    Parameters
    ----------
    fn : callable
        A plain Python function of scalars or arrays.

    Returns
    -------
    callable
        ``fn`` unchanged.
    """
    options = dict(error_model=OPTIONS["error_model"])
    if _numba is not None:
        from numba.extending import register_jitable

        register_jitable(**options)(fn)
    elif HAVE_NUMBA:
        _pending.append((fn, options))
    return fn


def njit(fn=None, *, signature=None):
    """``fn`` compiled by numba (cached on disk, :data:`OPTIONS`), or ``fn`` itself when
    :data:`HAVE_NUMBA` is False.

    Loads numba. Without ``signature`` it compiles on the first call, for the argument
    types of that call; with one, now. Where no cache can be written (e.g. a read-only
    installation) it compiles without the cache.

    Parameters
    ----------
    fn : callable, optional
        The function (omitted when used as ``@njit(signature=...)``).
    signature : str or tuple, optional
        numba signature(s) to compile eagerly.

    Returns
    -------
    callable
        The compiled function, ``fn``, or a decorator.
    """
    def wrap(f):
        nb = load_numba()
        if nb is None:
            return f
        args = () if signature is None else (signature,)
        try:
            return nb.njit(*args, cache=True, **OPTIONS)(f)
        except Exception:  # e.g. no writable cache location: compile without caching
            return nb.njit(*args, **OPTIONS)(f)

    return wrap if fn is None else wrap(fn)


#: seconds of NumPy work in the paths that have a compiled :class:`Twin` after which a
#: process switches them to their twins: loading numba (about 0.3 s) and the kernels
#: from the cache (or compiling them once) pays only for a process that evaluates for
#: longer than that (a command's single evaluation does not)
TWIN_AFTER_SECONDS = 0.5
_twin_numpy_seconds = 0.0


class Twin:
    """A NumPy path and the compiled loop that computes the same values bit for bit
    (``+ - * /`` and ``sqrt`` are correctly rounded in both, and the loop performs each
    point's operations in the NumPy path's order; tests compare the two), compiled on
    first use (:func:`njit`). Transcendental functions (``arccos``, ``arctan2``, ...)
    stay outside the loop, with NumPy on both paths: NumPy's vectorised versions (SIMD,
    on CPUs that have it) and the C library's, which a compiled loop calls, differ in the
    last bit.

    :meth:`compiled` says which to run: the loop once numba is loaded in this process
    (by any kernel) or once the twins' NumPy paths have spent :data:`TWIN_AFTER_SECONDS`
    (timed by :meth:`numpy_timer`), the NumPy path before and without numba; results do
    not depend on the choice.

    Parameters
    ----------
    loop : callable
        The loop, a plain Python function of arrays (it runs as Python only in tests).
    """

    def __init__(self, loop):
        self.loop = loop
        self._fn = None

    @staticmethod
    def compiled() -> bool:
        """Whether the compiled loops run (the class docstring).

        Returns
        -------
        bool
            True to call the twin.
        """
        return HAVE_NUMBA and (_numba is not None or _twin_numpy_seconds >= TWIN_AFTER_SECONDS)

    def __call__(self, *args):
        if self._fn is None:
            self._fn = njit(self.loop)
        return self._fn(*args)

    @staticmethod
    def numpy_timer():
        """A context that adds its duration to the twins' NumPy time.

        Returns
        -------
        contextlib.AbstractContextManager
            The timer.
        """
        return _NumpyTimer()


def twin_params(values):
    """``values`` as the float array a compiled twin takes, when the twins run
    (:meth:`Twin.compiled`) and every value is a number; None otherwise (lengths as
    arrays, a caller broadcasting designs: the NumPy path).

    Parameters
    ----------
    values : sequence
        Numbers (lengths, signs), or some arrays.

    Returns
    -------
    ndarray or None
        The 1-d float array, or None.
    """
    if not Twin.compiled():
        return None
    try:  # an array among them makes a 2-d array, or a ragged one (ValueError)
        p = np.array(values, float)
    except ValueError:
        return None
    return p if p.ndim == 1 else None


class _NumpyTimer:
    def __enter__(self):
        self.t0 = time.perf_counter()

    def __exit__(self, *exc):
        global _twin_numpy_seconds
        _twin_numpy_seconds += time.perf_counter() - self.t0
        return False
