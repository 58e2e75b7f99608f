"""The one place where mechopt maps work over processes: joblib or a Dask cluster.

:func:`parallel_map` preserves the order of its inputs whatever the backend, so
results (and everything seeded downstream) do not depend on ``n_jobs`` or on
the backend. Work should be coarse: map over *chunks* (lists of designs, slices
of a population), never over single points.
"""
from __future__ import annotations

import math
from typing import Callable, Iterable, Sequence

from . import validation as _v

__all__ = ["parallel_map", "chunks", "connect"]

#: most local worker processes (a typo such as --n-jobs 1e9 would overflow joblib)
MAX_JOBS = 1024


def chunks(seq: Sequence, n_chunks: int) -> list:
    """Split ``seq`` into at most ``n_chunks`` contiguous, nearly equal slices."""
    n = len(seq)
    n_chunks = max(1, min(_v.integer("n_chunks", n_chunks), n)) if n else 1
    size = math.ceil(n / n_chunks) if n else 0
    return [seq[i:i + size] for i in range(0, n, size)] if n else []


def connect(address: str, timeout: float = 10.0):
    """A ``dask.distributed.Client`` for a scheduler address (``tcp://host:port``).

    Raises ValueError with one line when dask is not installed or the scheduler
    cannot be reached within ``timeout`` seconds.
    """
    if not isinstance(address, str) or not address.strip():
        raise ValueError(f"the Dask scheduler address must be a string such as tcp://host:8786, "
                         f"got {_v.show(address)}")
    timeout = _v.finite_number("dask_timeout", timeout)
    if not timeout > 0:
        raise ValueError(f"dask_timeout must be a positive number of seconds, got {_v.show(timeout)}")
    try:
        from dask.distributed import Client
    except ImportError:
        raise ValueError("--dask needs the 'dask' extra: pip install 'mechopt[dask]'") from None
    try:
        return Client(address, timeout=timeout)
    except (OSError, TimeoutError) as exc:
        raise ValueError(f"cannot reach the Dask scheduler at {address!r}: {type(exc).__name__}") from None
    except ValueError as exc:  # a malformed address
        raise ValueError(f"bad Dask scheduler address {address!r}: {exc}") from None
    except Exception as exc:  # noqa: BLE001 - e.g. an AssertionError inside distributed
        raise ValueError(f"cannot reach the Dask scheduler at {address!r}: "
                         f"{type(exc).__name__} {exc}") from None


def parallel_map(func: Callable, items: Iterable, n_jobs: int = 2, client=None,
                 on_result: Callable[[int, int], None] | None = None,
                 on_item: Callable[[int, object], None] | None = None) -> list:
    """``[func(item) for item in items]``, evaluated in parallel, in input order.

    Parameters
    ----------
    func : callable
        A picklable, module-level function.
    items : iterable
        Work units (chunks).
    n_jobs : int
        joblib worker processes (``loky``); 1 runs in this process.
    client : dask.distributed.Client, optional
        When given, the items are mapped on the Dask cluster instead.
    on_result : callable, optional
        Called as ``on_result(done, total)`` after each result arrives (progress).
    on_item : callable, optional
        Called as ``on_item(index, result)`` in this process as each result
        arrives (e.g. to save it, so that a killed run can resume).
    """
    items = list(items)
    total = len(items)
    out = []

    def _tick(i, res):
        if on_item is not None:
            on_item(i, res)
        if on_result is not None:
            on_result(len(out), total)

    if client is not None:
        from dask.distributed import as_completed

        futures = client.map(func, items, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results = [None] * total
        for fut in as_completed(futures):
            i = index[fut.key]
            results[i] = fut.result()
            out.append(None)
            _tick(i, results[i])
        return results
    n_jobs = _v.integer("n_jobs", n_jobs, 1, MAX_JOBS)
    if n_jobs == 1 or total <= 1:
        for i, item in enumerate(items):
            out.append(func(item))
            _tick(i, out[-1])
        return out
    from joblib import Parallel, delayed

    gen = Parallel(n_jobs=n_jobs, backend="loky", return_as="generator")(
        delayed(func)(item) for item in items
    )
    for i, res in enumerate(gen):
        out.append(res)
        _tick(i, res)
    return out
