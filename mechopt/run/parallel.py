"""The one place where mechopt maps work over processes: joblib or a Dask cluster.

:func:`parallel_map` preserves the order of its inputs whatever the backend, so
results (and everything seeded downstream) do not depend on ``n_jobs`` or on
the backend. Work should be coarse: map over *chunks* (lists of designs, slices
of a population), never over single points.
"""
from __future__ import annotations

import logging
import math
import os
import threading
import weakref
from typing import Callable, Iterable, Sequence

from mechopt.core import validation as _v

__all__ = ["parallel_map", "map_async", "start_workers", "chunks", "connect", "check_cluster",
           "kernel_path", "stop_workers", "DEFAULT_STALL_S", "close_client", "cluster_threads", "warm_up",
           "warm_workers", "WARMUP_S", "RunFailure"]


class RunFailure(ValueError):
    """A run that failed for a reason outside its input: the Dask cluster has no
    workers, cannot run mechopt, stalls or is lost. A ValueError (one line), which the
    command line ends with its own exit status (3, not the 2 of bad input)."""

#: most local worker processes (a typo such as --n-jobs 1e9 would overflow joblib)
MAX_JOBS = 1024
#: a Dask run that gets no result for this long ends (seconds), unless the client
#: came from :func:`connect`, whose ``timeout`` is used instead
DEFAULT_STALL_S = 300.0
_STALL = {}  # id(client) -> stall timeout of clients made by connect()
#: a Dask worker's start-up allowance [s]: compiling the kernels with an empty numba
#: cache (:func:`warm_up`; about 28 s of CPU, 100 s of wall time on a loaded 2-core
#: machine) or loading them from it (about 2 s), before the first chunk is sent. It
#: is not the stall timeout (``--dask-timeout``), which then covers only connecting
#: and a run that makes no progress
WARMUP_S = 900.0
_WARMED = weakref.WeakKeyDictionary()  # client -> {worker address: seconds of its warm-up}
#: idle local workers exit after this many seconds (and are started again when needed);
#: joblib's own default. A short one races loky's idle exit against a new map's first
#: submit, which loky reports as "A worker stopped while some jobs were given to the
#: executor" (joblib issue 869) although nothing is lost
WORKER_IDLE_S = 300
#: this process's pool of local workers: {"executor", "n_jobs", "pid"} (see _executor)
_POOL: dict = {}
_POOL_LOCK = threading.Lock()


def kernel_path() -> str:
    """``"numba"`` or ``"numpy"``: which implementation of the compiled kernels this
    process runs (the two agree to ~1e-14, not bit for bit, so a cached or
    distributed result records it and is never mixed with the other).

    Returns
    -------
    str
        ``"numba"`` or ``"numpy"``.
    """
    from mechopt.mechanisms.five_bar import kernels

    return "numba" if kernels.HAVE_NUMBA else "numpy"


def _worker_facts() -> dict:
    """Run on each Dask worker: the mechopt version and kernel path it would use."""
    from mechopt import __version__

    return {"mechopt": __version__, "kernel": kernel_path()}


class _NoAnswer(RunFailure):
    """A Dask call that did not return in time (:func:`_within`): a runtime failure."""


def _within(seconds: float, what: str, func, *args, **kw):
    """``func(*args, **kw)`` if it returns within ``seconds``, else a one-line ValueError:
    a Dask endpoint that accepts a connection and never answers would block a
    synchronous call for ever (the call goes on in a daemon thread, which does not keep
    the process alive)."""
    box = {}

    def call():
        try:
            box["value"] = func(*args, **kw)
        except BaseException as exc:  # noqa: BLE001 - handed to the caller
            box["error"] = exc

    t = threading.Thread(target=call, daemon=True, name="mechopt-dask-call")
    t.start()
    t.join(seconds)
    if t.is_alive():
        raise _NoAnswer(f"{what}: no answer within {seconds:g} s")
    if "error" in box:
        raise box["error"]
    return box["value"]


def close_client(client, timeout: float | None = None) -> None:
    """Close a Dask client, waiting at most ``timeout`` seconds (default: its
    :func:`connect` timeout); a scheduler that does not answer is left behind.

    Parameters
    ----------
    client : dask.distributed.Client
        The Dask client.
    timeout : float, optional
        Seconds to wait (default: the client's time-out).
    """
    seconds = timeout if timeout is not None else _STALL.get(id(client), DEFAULT_STALL_S)
    try:
        _within(seconds, "closing the Dask client", client.close, timeout=seconds)
    except Exception:  # noqa: BLE001 - the run's result or error matters, not the goodbye
        pass
    _STALL.pop(id(client), None)


def cluster_threads(client) -> int:
    """The number of worker threads of the cluster (at least 1), asked within the
    client's stall timeout (ValueError, one line, otherwise).

    Parameters
    ----------
    client : dask.distributed.Client
        The Dask client.

    Returns
    -------
    int
        The number of threads, at least 1.

    Raises
    ------
    ValueError
        One line, when the cluster does not answer in time.
    """
    seconds = _STALL.get(id(client), DEFAULT_STALL_S)
    return max(1, sum(_within(seconds, "the Dask scheduler", client.nthreads).values()))


#: the longest wait for the workers to import mechopt and report their version and
#: kernel path (:func:`check_cluster`) [s]: at least this, or 6 times the timeout (an
#: import on a loaded machine takes far longer than a scheduler's answer)
FACTS_MIN_S = 60.0


def check_cluster(client, timeout: float = 10.0) -> dict:
    """Before the first chunk: the cluster has workers, and each imports the same
    mechopt version and kernel path as this process. ValueError (one line) otherwise:
    no worker within ``timeout`` seconds, or no facts from the workers within
    ``max(FACTS_MIN_S, 6 timeout)`` seconds. Returns the common facts.

    Parameters
    ----------
    client : dask.distributed.Client
        The Dask client.
    timeout : float
        Seconds to wait.

    Returns
    -------
    dict
        The facts the workers share (version, kernel path).

    Raises
    ------
    ValueError
        One line, for no worker within ``timeout`` or workers that differ from this process.
    """
    seconds = max(FACTS_MIN_S, 6.0 * timeout)
    return _within(timeout + seconds + 1.0, "the Dask cluster", _check_cluster, client, timeout, seconds)


def _check_cluster(client, timeout, seconds):
    try:
        _within(timeout + 1.0, "the Dask cluster", client.wait_for_workers, 1, timeout=timeout)
    except Exception:  # noqa: BLE001 - distributed raises its own TimeoutError types
        raise RunFailure(f"the Dask cluster has no workers after {timeout:g} s") from None
    try:
        facts = _within(seconds, "the Dask workers", client.run, _worker_facts)
    except _NoAnswer:
        raise
    except Exception as exc:  # noqa: BLE001 - e.g. ModuleNotFoundError on a worker
        raise RunFailure(f"a Dask worker cannot run mechopt: {type(exc).__name__}: "
                         f"{str(exc).splitlines()[0] if str(exc) else ''}".rstrip(": ")) from None
    mine = _worker_facts()
    for addr, theirs in facts.items():
        if theirs != mine:
            raise RunFailure(f"Dask worker {addr} runs mechopt {theirs['mechopt']} with "
                             f"{theirs['kernel']} kernels, this process {mine['mechopt']} with "
                             f"{mine['kernel']}: results would not be reproducible")
    return mine


def warm_up(_=None) -> dict:
    """Compile (or load from numba's cache, :func:`mechopt.core.jit.cache_dir`) every
    compiled kernel in this process
    (:func:`mechopt.mechanisms.five_bar.kernels.compile_all`); nothing without numba. Sent to each Dask worker before its first chunk
    (:func:`warm_workers`).

    Returns
    -------
    dict
        ``{"kernel": "numba" or "numpy", "seconds": wall time [s]}``.

    Parameters
    ----------
    _ : object, optional
        Ignored (the signature of a mapped function).
    """
    import time

    from mechopt.mechanisms.five_bar.kernels import compile_all

    t0 = time.perf_counter()
    compile_all()
    return {"kernel": kernel_path(), "seconds": time.perf_counter() - t0}


def warm_workers(client, timeout: float = WARMUP_S) -> dict:
    """:func:`warm_up` on every worker of the Dask ``client``, all at once, within the
    start-up allowance ``timeout`` [s] (not the stall timeout): the first chunks then
    measure evaluation, not compilation. Done once per client; a worker that joins
    later compiles within its first chunk (which counts as progress, not as a stall:
    :func:`parallel_map`).

    Parameters
    ----------
    client : dask.distributed.Client
        A connected client.
    timeout : float
        Seconds allowed for every worker's warm-up.

    Returns
    -------
    dict
        ``{worker address: seconds of its warm-up}``.

    Raises
    ------
    ValueError
        One line, when a worker fails or the allowance runs out.
    """
    if client in _WARMED:
        return _WARMED[client]
    from dask.distributed import wait

    futures = []
    try:
        workers = sorted(client.scheduler_info()["workers"])
        futures = [client.submit(warm_up, i, workers=[w], allow_other_workers=False, pure=False)
                   for i, w in enumerate(workers)]
        wait(futures, timeout=timeout)
        seconds = {w: f.result()["seconds"] for w, f in zip(workers, futures)}
    except Exception as exc:  # noqa: BLE001 - TimeoutError, a worker's error, a lost cluster
        for f in futures:
            f.cancel()
        what = (f"did not compile the kernels within the start-up allowance of {timeout:g} s"
                if "Timeout" in type(exc).__name__ else f"failed to compile the kernels ({type(exc).__name__})")
        raise RunFailure(f"the Dask workers {what}") from None
    _WARMED[client] = seconds
    log = logging.getLogger("mechopt")
    for w, sec in seconds.items():
        log.debug("Dask worker %s: kernels compiled or loaded in %.1f s", w, sec)
    return seconds


def _still_working(client, pending) -> bool:
    """Whether the scheduler is reachable and one of the ``pending`` futures is being
    computed by a worker (a slow chunk, or a late worker compiling its kernels): then
    a wait without a result is no stall."""
    try:
        keys = {f.key for f in pending}
        return any(k in keys for ks in client.processing().values() for k in ks)
    except Exception:  # noqa: BLE001 - the scheduler is gone
        return False


def chunks(seq: Sequence, n_chunks: int) -> list:
    """Split ``seq`` into at most ``n_chunks`` contiguous, nearly equal slices.

    Parameters
    ----------
    seq : sequence
        The items.
    n_chunks : int
        The most slices.

    Returns
    -------
    list
        The slices.
    """
    n = len(seq)
    n_chunks = max(1, min(_v.integer("n_chunks", n_chunks), n)) if n else 1
    size = math.ceil(n / n_chunks) if n else 0
    return [seq[i:i + size] for i in range(0, n, size)] if n else []


def connect(address: str, timeout: float = 10.0):
    """A ``dask.distributed.Client`` for a scheduler address (``tcp://host:port``).

    Parameters
    ----------
    address : str
        The scheduler's address.
    timeout : float
        Seconds to wait for the scheduler.

    Returns
    -------
    dask.distributed.Client
        The client.

    Raises
    ------
    ValueError
        One line, when dask is not installed or the scheduler cannot be reached
        within ``timeout`` seconds.
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
        client = _within(timeout + 1.0, f"cannot reach the Dask scheduler at {address!r}", Client, address,
                         timeout=timeout)
    except _NoAnswer:
        raise
    except (OSError, TimeoutError) as exc:
        raise RunFailure(f"cannot reach the Dask scheduler at {address!r}: {type(exc).__name__}") from None
    except ValueError as exc:  # a malformed address
        raise ValueError(f"bad Dask scheduler address {address!r}: {exc}") from None
    except Exception as exc:  # noqa: BLE001 - e.g. an AssertionError inside distributed
        raise RunFailure(f"cannot reach the Dask scheduler at {address!r}: "
                         f"{type(exc).__name__} {exc}") from None
    _STALL[id(client)] = timeout
    try:
        check_cluster(client, timeout)
    except ValueError:
        close_client(client)
        raise
    return client


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

    Returns
    -------
    list
        The results, in input order.
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
        return _dask_map(func, items, client, _tick, out)
    n_jobs = _v.integer("n_jobs", n_jobs, 1, MAX_JOBS)
    if n_jobs == 1 or total <= 1:
        for i, item in enumerate(items):
            out.append(func(item))
            _tick(i, out[-1])
        return out
    pending = map_async(func, items, n_jobs=n_jobs)
    try:
        for i in range(total):  # in input order, as they finish
            out.append(pending.result(i))
            _tick(i, out[-1])
    except BaseException:  # an error, Ctrl-C or SIGTERM: no worker outlives the run
        pending.cancel()
        raise
    return out


class _Pending:
    """The results of :func:`map_async`, to collect in input order (``result(i)``,
    ``results()``); ``cancel()`` ends every local worker at once (:func:`stop_workers`)."""

    def __init__(self, func, items, futures):
        self._func, self._items, self._futures = func, items, futures
        self._done = {}

    def __len__(self):
        return len(self._items)

    def result(self, i):
        """The result of item ``i`` (waits for it; computed here when mapped with one job)."""
        if i not in self._done:
            self._done[i] = (self._func(self._items[i]) if self._futures is None
                             else self._futures[i].result())
        return self._done[i]

    def results(self) -> list:
        """Every result, in input order; any error (or an interrupt) ends every worker first."""
        try:
            return [self.result(i) for i in range(len(self._items))]
        except BaseException:
            self.cancel()
            raise

    def cancel(self):
        if self._futures is not None:
            for fut in self._futures:
                fut.cancel()
            stop_workers()


def map_async(func: Callable, items: Iterable, n_jobs: int = 2) -> _Pending:
    """Start ``[func(item) for item in items]`` on ``n_jobs`` local worker processes and
    return at once (this process may work meanwhile); ``.results()`` waits for them, in
    input order. With one job nothing starts: each item is evaluated in this process
    when its result is asked for. An error ends every worker (:func:`stop_workers`)
    before it is raised.

    Parameters
    ----------
    func : callable
        A picklable, module-level function.
    items : iterable
        Work units.
    n_jobs : int
        Worker processes.

    Returns
    -------
    object
        A pending result; ``.results()`` returns the list in input order.
    """
    items = list(items)
    n_jobs = _v.integer("n_jobs", n_jobs, 1, MAX_JOBS)
    if n_jobs == 1:
        return _Pending(func, items, None)
    executor = _executor(n_jobs)
    futures = []
    try:
        for item in items:
            futures.append(_submit(executor, func, item))
    except BaseException:
        for fut in futures:
            fut.cancel()
        stop_workers()
        raise
    return _Pending(func, items, futures)


def start_workers(n_jobs: int = 2, prepare: Callable | None = None) -> None:
    """Start the ``n_jobs`` local worker processes now, without waiting for them, so that
    their start-up (a fresh interpreter and its imports each) overlaps this process's
    own work before its first :func:`parallel_map`; nothing with one job.

    ``prepare`` (a picklable, module-level function of one ignored argument) is sent
    ``n_jobs`` times, so that each worker most likely runs it once: unpickling it
    imports its module there, before the first real work unit arrives.

    Parameters
    ----------
    n_jobs : int
        Worker processes.
    prepare : callable, optional
        Run once in each worker as it starts.
    """
    n_jobs = _v.integer("n_jobs", n_jobs, 1, MAX_JOBS)
    if n_jobs > 1:
        executor = _executor(n_jobs)
        for i in range(n_jobs if prepare is not None else 1):  # the first submit spawns every worker
            _submit(executor, prepare if prepare is not None else int, i)


def _usable(executor) -> bool:
    flags = getattr(executor, "_flags", None)
    return flags is None or not (flags.broken or flags.shutdown)


def _executor(n_jobs: int):
    """This process's pool of ``n_jobs`` loky worker processes, started on first use and
    reused by later maps (replaced when ``n_jobs`` changes or the pool broke).

    It is mechopt's own executor, not loky's process-wide reusable one: joblib.Parallel
    (which reuses that one and expects its own memmapping executor there) keeps working
    in the same process. Each worker gets this process's pid, so that one started
    just before this process died ends as soon as it runs (:func:`_die_with_parent`)."""
    from joblib.externals.loky import ProcessPoolExecutor

    with _POOL_LOCK:
        ex = _POOL.get("executor")
        if ex is not None and _POOL.get("pid") != os.getpid():  # inherited through a fork
            _POOL.clear()
            ex = None
        if ex is not None and (_POOL["n_jobs"] != n_jobs or not _usable(ex)):
            _POOL.clear()
            ex.shutdown(wait=True)
            ex = None
        if ex is None:
            ex = ProcessPoolExecutor(max_workers=n_jobs, timeout=WORKER_IDLE_S,
                                     initializer=_die_with_parent, initargs=(os.getpid(),))
            _POOL.update(executor=ex, n_jobs=n_jobs, pid=os.getpid())
        return ex


_AT_EXIT = {}  # pid -> True once _end_pool_at_exit is registered in that process


def _submit(executor, func, item):
    """``executor.submit(func, item)`` (through :func:`_run_item`); the first submit of a process also registers
    :func:`_end_pool_at_exit` (after loky's own exit hook, which that submit registers,
    so that it runs before it)."""
    fut = executor.submit(_run_item, func, item)
    if os.getpid() not in _AT_EXIT:
        _AT_EXIT[os.getpid()] = True
        try:  # the hook of concurrent.futures: runs before threads are joined, in reverse order
            threading._register_atexit(_end_pool_at_exit)
        except (AttributeError, RuntimeError):  # another Python, or already shutting down
            pass
    return fut


def _end_pool_at_exit():
    """At interpreter exit the pool's workers have nothing left to do: they are killed
    rather than asked to stop, since loky would wait for each one's own interpreter
    teardown (about a second with numba and matplotlib loaded), and the process with it."""
    with _POOL_LOCK:
        mine = _POOL.get("pid") == os.getpid()
    if mine:
        _kill_pool()


def stop_workers():
    """End every local worker process now (after an interrupt or a fatal error): this
    process's pool is killed before this returns (so that none writes a file after it),
    and loky's process-wide executor (joblib.Parallel's) is shut down."""
    from joblib.externals.loky import reusable_executor

    _kill_pool()
    ex = reusable_executor._executor
    if ex is not None:
        ex.shutdown(wait=False, kill_workers=True)


def _quiet_manager_threads():
    """Killing workers can race loky's manager thread, which then dies with a KeyError
    traceback on stderr: the run is already ending (with its one line, if any)."""
    previous = threading.excepthook
    if getattr(previous, "_mechopt_quiet", False):
        return

    def _quiet(args):
        if args.thread is not None and args.thread.name.startswith("ExecutorManagerThread"):
            return
        previous(args)

    _quiet._mechopt_quiet = True
    threading.excepthook = _quiet


def _kill_pool():
    """Kill the workers of this process's pool now (SIGKILL) and forget the pool."""
    _quiet_manager_threads()
    with _POOL_LOCK:
        ours = _POOL.get("executor") if _POOL.get("pid") == os.getpid() else None
        _POOL.clear()
    if ours is not None:
        import signal

        try:
            procs = list(getattr(ours, "_processes", {}).values())
        except RuntimeError:  # changed size under loky's manager thread
            procs = []
        for proc in procs:
            try:
                if proc.exitcode is None:  # alive (not reaped: its pid is still its own)
                    # SIGKILL now: loky's own kill runs later, in its manager thread
                    os.kill(proc.pid, signal.SIGKILL)
            except (OSError, AttributeError, ValueError):
                pass
        ours.shutdown(wait=False, kill_workers=True)


def _run_item(func, item):
    """``func(item)`` in a worker, then the end of any pool it started there.

    A work unit may map its own items on a pool of its worker (a paper of ``reproduce``
    running its optimisations on two processes): that pool is closed when the unit
    ends, since the worker is killed when its parent exits, which would leave the
    pool's semaphores to the resource tracker ("leaked semlock objects" on stderr)."""
    try:
        return func(item)
    finally:
        _close_pool()


def _close_pool():
    """Shut this process's pool down, if it has one, and wait for its workers to end."""
    with _POOL_LOCK:
        ours = _POOL.get("executor") if _POOL.get("pid") == os.getpid() else None
        _POOL.clear()
    if ours is not None:
        ours.shutdown(wait=True)


def _die_with_parent(parent: int | None = None):
    """Worker initializer: the worker ends when the process that started it (pid
    ``parent``, given by that process) dies, even by SIGKILL (which runs no cleanup):
    PR_SET_PDEATHSIG on Linux, and everywhere a daemon thread that exits once the parent
    pid changes. A worker whose parent died while it was starting (before this ran) ends
    here at once: its parent pid is no longer ``parent``."""
    import os
    import signal
    import threading
    import time

    if parent is None:
        parent = os.getppid()
    try:
        import ctypes

        libc = ctypes.CDLL("libc.so.6", use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass
    if os.getppid() != parent:  # the parent died before the death signal was set
        os._exit(1)

    def watch():
        while True:
            if os.getppid() != parent:
                os._exit(1)
            time.sleep(0.5)

    threading.Thread(target=watch, daemon=True, name="mechopt-parent-watch").start()


def _dask_map(func, items, client, tick, out):
    """Map on a Dask cluster, its workers warmed first (:func:`warm_workers`, with its own
    allowance); a run that gets no result for the stall timeout while no worker
    computes one of its items (or that loses its scheduler) ends with one line, after
    the finished results were handed to ``tick`` (so that an atlas keeps its finished
    chunks)."""
    from dask.distributed import wait

    stall = _STALL.get(id(client), DEFAULT_STALL_S)
    total = len(items)
    warm_workers(client)
    try:
        futures = client.map(func, items, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results = [None] * total
        pending = set(futures)
        while pending:
            try:
                done, pending = wait(pending, timeout=stall, return_when="FIRST_COMPLETED")
            except Exception as exc:  # noqa: BLE001 - asyncio's or distributed's TimeoutError
                if "Timeout" in type(exc).__name__ and _still_working(client, pending):
                    continue  # a long chunk: progress, not a stall
                raise
            for fut in sorted(done, key=lambda f: index[f.key]):
                i = index[fut.key]
                results[i] = fut.result()
                out.append(None)
                tick(i, results[i])
    except ValueError:
        raise
    except Exception as exc:  # noqa: BLE001 - TimeoutError, CommClosedError, CancelledError ...
        name = type(exc).__name__
        what = (f"no result for {stall:g} s" if "Timeout" in name
                else f"the Dask cluster failed ({name})")
        raise RunFailure(f"{what}: {len(out)} of {total} work units finished") from None
    return results
