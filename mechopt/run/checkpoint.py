"""Checkpoints that run no code they were not written with.

A checkpoint holds a pickled pymoo algorithm (its population, random generator,
termination and history): the only faithful way to continue a run byte for byte.
Unpickling runs code, so the file is authenticated before it is unpickled::

    MECHOPT-CHECKPOINT 2\\n
    <HMAC-SHA256 of the first line and the header, hex>\\n
    <header: one line of JSON (run id, problem, options, payload length and sha256)>\\n
    <payload: the pickle>

The HMAC is keyed by the user's secret (:mod:`mechopt.run.keys`: ``checkpoint.key``
in ``$MECHOPT_CONFIG_DIR``, else ``$XDG_CONFIG_HOME/mechopt``, else
``~/.config/mechopt``; made with mode 0600 on first use; an empty, short, linked or
group/world-readable key is refused). Reading is bounded and authenticated in
order: the file must be a regular file (no link, FIFO or device); the header line
(at most 1 MiB) is read and its HMAC checked; only then is the file's size compared
with the payload length the header states, the payload read and its sha256
compared. A file crafted or edited by anyone without the key fails before its
payload is read, and is never unpickled; to resume on another machine, copy the key
along. Every failure is one :class:`UnreadableCheckpoint` (a ValueError) naming the
cause.
"""
from __future__ import annotations

import hashlib
import hmac
import json
import os
import pickle
from pathlib import Path

from mechopt.core.reading import open_regular
from mechopt.run import io as _io
from mechopt.run import keys as _keys

__all__ = ["MAGIC", "UnreadableCheckpoint", "key_path", "write", "read", "read_header", "MAX_PAYLOAD"]

MAGIC = b"MECHOPT-CHECKPOINT 2\n"
_OLD_MAGIC = b"MECHOPT-CHECKPOINT 1\n"
#: a header line longer than this is not ours (read before anything is trusted) [bytes]
_MAX_HEADER = 1 << 20
#: the largest payload read [bytes] (a population of a million designs pickles to far less)
MAX_PAYLOAD = 8 << 30

key_path = _keys.key_path


class UnreadableCheckpoint(ValueError):
    """The checkpoint is missing a part, was edited, or was written with another key."""


def _mac(key: bytes, header: bytes) -> str:
    return _keys.mac(key, MAGIC, header)


def write(path, obj, header: dict) -> Path:
    """Pickle ``obj`` (with cloudpickle: pymoo's algorithms hold local functions that
    plain pickle refuses) and write it atomically with ``header`` and the HMAC.

    Parameters
    ----------
    path : str or Path
        The checkpoint file.
    obj : object
        What to save (the algorithm's state).
    header : dict
        The run's identification (plain JSON data).

    Returns
    -------
    Path
        The path written.
    """
    import cloudpickle

    key = _keys.load_key(create=True)
    payload = cloudpickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    head = json.dumps({**header, "payload_bytes": len(payload),
                       "payload_sha256": hashlib.sha256(payload).hexdigest()},
                      sort_keys=True, default=str).encode()
    mac = _mac(key, head)
    with _io.atomic_path(path) as tmp, open(tmp, "wb") as fh:
        fh.write(MAGIC + mac.encode() + b"\n" + head + b"\n" + payload)
    return Path(path)


def read_header(path) -> dict:
    """The checkpoint's header, authenticated (its payload is not read).

    Parameters
    ----------
    path : str or Path
        The checkpoint file.

    Returns
    -------
    dict
        The header.
    """
    return _read(path, payload=False)[0]


def _read(path, payload: bool = True):
    """``(header, payload bytes or None)``, authenticated as the module docstring says."""
    try:
        fd, size = open_regular(path, "it", MAX_PAYLOAD + _MAX_HEADER + 200)
    except FileNotFoundError:
        raise UnreadableCheckpoint("missing") from None
    except ValueError as exc:
        raise UnreadableCheckpoint(str(exc)) from None
    try:
        with os.fdopen(fd, "rb") as fh:
            first = fh.read(len(MAGIC) + 65)
            if first.startswith(_OLD_MAGIC):
                raise UnreadableCheckpoint("written by an older mechopt (format 1); start the run again")
            if not first.startswith(MAGIC):
                raise UnreadableCheckpoint("not a mechopt checkpoint")
            mac = first[len(MAGIC):]
            if len(mac) != 65 or mac[64:] != b"\n":
                raise UnreadableCheckpoint("truncated")
            head = fh.readline(_MAX_HEADER + 1)
            if not head.endswith(b"\n"):
                raise UnreadableCheckpoint("truncated" if len(head) <= _MAX_HEADER else "header too long")
            head = head[:-1]
            key = _keys.load_key(create=False)
            if key is None or not hmac.compare_digest(mac[:64].decode("ascii", "replace"), _mac(key, head)):
                raise UnreadableCheckpoint("authentication failed: edited, or written with another user's "
                                           f"checkpoint key ({key_path()})")
            try:
                header = json.loads(head)
            except (ValueError, RecursionError):
                raise UnreadableCheckpoint("bad header") from None
            n = header.get("payload_bytes") if isinstance(header, dict) else None
            if not isinstance(n, int) or isinstance(n, bool) or not 0 <= n <= MAX_PAYLOAD \
                    or not isinstance(header.get("payload_sha256"), str):
                raise UnreadableCheckpoint("bad header")
            if size != len(MAGIC) + 65 + len(head) + 1 + n:
                raise UnreadableCheckpoint("truncated" if size < len(MAGIC) + 65 + len(head) + 1 + n
                                           else "trailing bytes")
            if not payload:
                return header, None
            data = fh.read(n + 1)
    except OSError as exc:
        raise UnreadableCheckpoint(f"unreadable ({exc.strerror or type(exc).__name__})") from None
    if len(data) != n or not hmac.compare_digest(hashlib.sha256(data).hexdigest(), header["payload_sha256"]):
        raise UnreadableCheckpoint("the payload does not match its header (edited or truncated)")
    return header, data


def read(path):
    """``(header, object)`` of an authenticated checkpoint; anything else raises
    :class:`UnreadableCheckpoint` before a byte is unpickled.

    Parameters
    ----------
    path : str or Path
        The checkpoint file.

    Returns
    -------
    header : dict
        The header.
    obj : object
        The saved object.

    Raises
    ------
    UnreadableCheckpoint
        A ValueError, for a missing, foreign, altered or malformed file.
    """
    header, payload = _read(path)
    try:
        return header, pickle.loads(payload)
    except Exception as exc:  # authentic but unloadable: another version of a library
        raise UnreadableCheckpoint(f"written by other library versions ({type(exc).__name__})") from None
