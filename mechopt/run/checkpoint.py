"""Checkpoints that run no code they were not written with.

A checkpoint holds a pickled pymoo algorithm (its population, random generator,
termination and history): the only faithful way to continue a run byte for byte.
Unpickling runs code, so the file is authenticated before it is unpickled::

    MECHOPT-CHECKPOINT 1\\n
    <HMAC-SHA256, hex>\\n
    <header: one line of JSON (run id, problem, options, payload length and sha256)>\\n
    <payload: the pickle>

The HMAC covers the header and the payload and is keyed by a secret kept in the
user's configuration folder (:func:`key_path`: ``$MECHOPT_CONFIG_DIR``, else
``$XDG_CONFIG_HOME/mechopt``, else ``~/.config/mechopt``; the file
``checkpoint.key`` is created with mode 0600 on first use). A file crafted or
edited by anyone without that key fails the check and is never unpickled; to
resume on another machine, copy the key along. Every failure is one
:class:`UnreadableCheckpoint` (a ValueError) naming the cause.
"""
from __future__ import annotations

import hashlib
import hmac
import json
import os
import pickle
import secrets
from pathlib import Path

from mechopt.run import io as _io

__all__ = ["MAGIC", "UnreadableCheckpoint", "key_path", "write", "read", "read_header"]

MAGIC = b"MECHOPT-CHECKPOINT 1\n"
#: a header line longer than this is not ours (read before anything is trusted)
_MAX_HEADER = 1 << 20
_KEY_NAME = "checkpoint.key"


class UnreadableCheckpoint(ValueError):
    """The checkpoint is missing a part, was edited, or was written with another key."""


def key_path() -> Path:
    """Where the checkpoint key lives (see the module docstring)."""
    base = os.environ.get("MECHOPT_CONFIG_DIR")
    if not base:
        xdg = os.environ.get("XDG_CONFIG_HOME")
        base = os.path.join(xdg, "mechopt") if xdg else os.path.join(os.path.expanduser("~"), ".config",
                                                                      "mechopt")
    return Path(base) / _KEY_NAME


def _key(create: bool) -> bytes | None:
    path = key_path()
    try:
        return bytes.fromhex(path.read_text().strip())
    except FileNotFoundError:
        if not create:
            return None
    except (OSError, ValueError) as exc:
        raise ValueError(f"the checkpoint key {str(path)!r} is unreadable ({type(exc).__name__}); "
                         f"remove it (existing checkpoints then cannot be resumed)") from None
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        fd = os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600)
    except FileExistsError:  # another run made it meanwhile
        return _key(create=False)
    except OSError as exc:
        raise ValueError(f"cannot create the checkpoint key {str(path)!r}: {exc.strerror}; set "
                         f"MECHOPT_CONFIG_DIR to a writable folder") from None
    key = secrets.token_bytes(32)
    with os.fdopen(fd, "w") as fh:
        fh.write(key.hex() + "\n")
    return key


def _mac(key: bytes, header: bytes, payload: bytes) -> str:
    return hmac.new(key, MAGIC + header + b"\n" + payload, hashlib.sha256).hexdigest()


def write(path, obj, header: dict) -> Path:
    """Pickle ``obj`` (with cloudpickle: pymoo's algorithms hold local functions that
    plain pickle refuses) and write it atomically with ``header`` and the HMAC."""
    import cloudpickle

    payload = cloudpickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    head = json.dumps({**header, "payload_bytes": len(payload),
                       "payload_sha256": hashlib.sha256(payload).hexdigest()},
                      sort_keys=True, default=str).encode()
    mac = _mac(_key(create=True), head, payload)
    with _io.atomic_path(path) as tmp, open(tmp, "wb") as fh:
        fh.write(MAGIC + mac.encode() + b"\n" + head + b"\n" + payload)
    return Path(path)


def _split(data: bytes):
    if not data.startswith(MAGIC):
        raise UnreadableCheckpoint("not a mechopt checkpoint")
    rest = data[len(MAGIC):]
    mac, sep, rest = rest.partition(b"\n")
    if not sep or len(mac) != 64:
        raise UnreadableCheckpoint("truncated")
    end = rest.find(b"\n", 0, _MAX_HEADER)
    if end < 0:
        raise UnreadableCheckpoint("truncated")
    return mac.decode("ascii", "replace"), rest[:end], rest[end + 1:]


def read_header(path) -> dict:
    """The checkpoint's header, authenticated (its payload is not unpickled)."""
    return _read(path)[0]


def _read(path):
    try:
        data = Path(path).read_bytes()
    except IsADirectoryError:
        raise UnreadableCheckpoint("a folder, not a file") from None
    mac, head, payload = _split(data)
    key = _key(create=False)
    if key is None or not hmac.compare_digest(mac, _mac(key, head, payload)):
        raise UnreadableCheckpoint("authentication failed: edited, or written with another user's "
                                   f"checkpoint key ({key_path()})")
    try:
        header = json.loads(head)
    except ValueError:
        raise UnreadableCheckpoint("bad header") from None
    if not isinstance(header, dict) or header.get("payload_bytes") != len(payload):
        raise UnreadableCheckpoint("truncated")
    return header, payload


def read(path):
    """``(header, object)`` of an authenticated checkpoint; anything else raises
    :class:`UnreadableCheckpoint` before a byte is unpickled."""
    header, payload = _read(path)
    try:
        return header, pickle.loads(payload)
    except Exception as exc:  # authentic but unloadable: another version of a library
        raise UnreadableCheckpoint(f"written by other library versions ({type(exc).__name__})") from None
