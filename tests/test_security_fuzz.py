"""Fuzz of what a run reads back from a folder a stranger may have written (issue 27):
``manifest.json``, ``run.json`` and checkpoint headers. Whatever the bytes, the
readers end in a result or a one-line ValueError, nothing outside the folder is
removed or changed, the user's own files in it stay, and no checkpoint payload is
unpickled unless its header is authentic and matches it.

The parsing and validation functions are called directly (hundreds of examples in a
few seconds); ``tests/test_security.py`` has the end-to-end CLI runs."""
from __future__ import annotations

import hashlib
import json
import os
import pickle
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

from mechopt.run import checkpoint, keys  # noqa: E402
from mechopt.run import io as _io  # noqa: E402

OUTPUTS = ("front.csv", "history.csv", "run.json", "front.png", "checkpoint.pkl")
def FAST(n):
    """Settings of a fuzz of ``n`` examples: no deadline, derandomised (the same examples
    in every run: the suite stays fast and a failure repeats), no example database."""
    return settings(max_examples=n, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True,
                    database=None)


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    """A key, a folder outside every run with a sentinel, and its bytes. Files are not
    fsynced here (durability is not what is fuzzed; it made an example 50 ms)."""
    mp = pytest.MonkeyPatch()
    mp.setattr(_io, "_fsync", lambda path: None)
    base = tmp_path_factory.mktemp("fuzz")
    old = os.environ.get("MECHOPT_CONFIG_DIR")
    os.environ["MECHOPT_CONFIG_DIR"] = str(base / "config")
    keys.load_key(create=True)
    outside = base / "outside"
    outside.mkdir()
    data = os.urandom(32)
    (outside / "victim.txt").write_bytes(data)
    yield base, outside / "victim.txt", data
    mp.undo()
    if old is None:
        os.environ.pop("MECHOPT_CONFIG_DIR", None)
    else:
        os.environ["MECHOPT_CONFIG_DIR"] = old


def _names(victim: Path):
    """File names a crafted manifest may hold: plain, our outputs, escapes, odd types."""
    return st.one_of(st.sampled_from(["front.csv", "run.json", "checkpoint.pkl", "notes.txt", "..", ".", "",
                                      "../outside/victim.txt", str(victim), "/etc/passwd", "a/b",
                                      "front.csv\0x"]),
                     st.text(max_size=12), st.integers(), st.none(), st.lists(st.text(max_size=3), max_size=2))


def _json(leaves):
    return st.recursive(leaves, lambda kids: st.one_of(st.lists(kids, max_size=3),
                                                       st.dictionaries(st.text(max_size=6), kids, max_size=3)),
                        max_leaves=8)


def _manifests(victim: Path):
    name = _names(victim)
    digest = st.one_of(st.just(hashlib.sha256(victim.read_bytes()).hexdigest()), st.text(max_size=4),
                       st.integers())
    value = _json(st.one_of(st.none(), st.booleans(), st.integers(), st.floats(allow_nan=True), st.text(max_size=6)))
    fields = {"kind": st.one_of(st.sampled_from(["optimize", "atlas", "sweep"]), value),
              "key": st.one_of(st.just({}), value),
              "status": st.one_of(st.sampled_from(["running", "complete"]), value),
              "run_id": st.one_of(st.text(max_size=6), value),
              "files": st.one_of(st.dictionaries(name.filter(lambda n: isinstance(n, str)), digest, max_size=3),
                                 st.lists(name, max_size=3), value),
              "owned": st.one_of(st.lists(name, max_size=3), name, value),
              "mac": st.one_of(st.text(max_size=4), value)}
    doc = st.fixed_dictionaries({}, optional=fields).map(json.dumps)
    raw = st.one_of(st.binary(max_size=64), st.integers(1, 3000).map(lambda n: "[" * n + "]" * n),
                    st.just('{"kind": 1e999}'), st.just("\ufeff{}"))
    return st.one_of(doc, doc, doc, raw.map(lambda r: r if isinstance(r, str) else r.decode("latin-1")))


def _one_line(exc: BaseException) -> bool:
    return isinstance(exc, ValueError) and "\n" not in str(exc) and str(exc).strip() != ""


def test_fuzz_manifests_never_remove_anything_outside_or_foreign(world):
    base, victim, data = world
    counter = iter(range(10**9))

    @FAST(240)
    @given(doc=_manifests(victim), overwrite=st.booleans(), kind=st.sampled_from(["optimize", "atlas"]),
           signed=st.booleans())
    def check(doc, overwrite, kind, signed):
        out = base / f"run{next(counter)}"
        out.mkdir()
        (out / "front.csv").write_text("the user's\n")  # an output name no authentic manifest lists
        (out / "notes.txt").write_text("the user's\n")  # not an output name
        try:
            parsed = json.loads(doc)
        except (ValueError, RecursionError):
            parsed = None
        # signed with the user's own key: as if this user's mechopt had written the names
        # (a stranger cannot); even then nothing outside the folder, and no non-output, goes
        signed = signed and isinstance(parsed, dict)
        if signed:
            parsed["mac"] = _io._manifest_mac(parsed, keys.load_key(create=False))
            doc = json.dumps(parsed)
        (out / "manifest.json").write_text(doc, encoding="utf-8", errors="surrogatepass")
        for call in (lambda: _io.read_manifest(out),
                     lambda: _io.claim_out(out, kind, {"seed": 1}, OUTPUTS, overwrite=overwrite)):
            try:
                call()
            except Exception as exc:  # noqa: BLE001 - the property: only one-line ValueErrors
                assert _one_line(exc), repr(exc)
        assert victim.read_bytes() == data
        assert signed or (out / "front.csv").read_text() == "the user's\n"
        assert (out / "notes.txt").read_text() == "the user's\n"

    check()


def test_fuzz_run_json_for_the_report_and_resume(world):
    from mechopt.workflows.report import _run_caption

    base, victim, data = world
    folder = base / "runjson"
    folder.mkdir()
    value = _json(st.one_of(st.none(), st.booleans(), st.integers(), st.floats(allow_nan=True),
                            st.text(max_size=6)))
    doc = st.fixed_dictionaries({}, optional={
        "problem": value, "summary": value, "single_optimum": value, "seed": value,
        "algorithm": st.one_of(st.fixed_dictionaries({}, optional={"name": value, "pop": value, "gen": value}),
                               value)}).map(json.dumps)

    @FAST(80)
    @given(doc=st.one_of(doc, st.just("1e999"), st.integers(1, 3000).map(lambda n: "{\"a\":" * n + "1" + "}" * n)))
    def check(doc):
        (folder / "run.json").write_text(doc)
        title, desc = _run_caption(folder, folder / "front.png")
        assert isinstance(title, str) and isinstance(desc, str)
        try:
            got = _io.read_json(folder / "run.json")
        except ValueError as exc:
            assert _one_line(exc)
        else:
            assert got == json.loads(doc) or doc == "1e999" or got != got

    check()


class _Marker:
    """Unpickling it creates ``path``: proof that a payload was loaded."""

    def __init__(self, path):
        self.path = str(path)

    def __reduce__(self):
        return (Path.touch, (Path(self.path),))


def test_fuzz_checkpoint_headers(world):
    base, victim, data = world
    key = keys.load_key(create=False)
    folder = base / "ck"
    folder.mkdir()
    marker = base / "loaded"
    payload = pickle.dumps(_Marker(marker))
    sha = hashlib.sha256(payload).hexdigest()
    value = _json(st.one_of(st.none(), st.booleans(), st.integers(), st.floats(allow_nan=True), st.text(max_size=6)))
    header = st.one_of(
        st.fixed_dictionaries({}, optional={"payload_bytes": st.one_of(st.just(len(payload)), st.integers(), value),
                                            "payload_sha256": st.one_of(st.just(sha), value),
                                            "run_id": value}).map(lambda d: json.dumps(d).encode()),
        st.binary(max_size=40).filter(lambda b: b"\n" not in b),
        st.integers(1, 2000).map(lambda n: b"[" * n + b"]" * n))

    @FAST(180)
    @given(head=header, signed=st.booleans(), magic=st.sampled_from([checkpoint.MAGIC, b"MECHOPT-CHECKPOINT 1\n", b"X"]),
           tail=st.sampled_from([b"", b"\x00", b"cut"]))
    def check(head, signed, magic, tail):
        mac = keys.mac(key, checkpoint.MAGIC, head) if signed else "0" * 64
        body = payload + tail if tail != b"cut" else payload[:-3]
        path = folder / "checkpoint.pkl"
        path.write_bytes(magic + mac.encode() + b"\n" + head + b"\n" + body)
        if marker.exists():
            marker.unlink()
        try:
            checkpoint.read(path)
        except Exception as exc:  # noqa: BLE001 - the property: only one-line ValueErrors
            assert _one_line(exc), repr(exc)
            assert not marker.exists()
        else:  # loaded: only an authentic header that states this very payload
            parsed = json.loads(head)
            assert signed and magic == checkpoint.MAGIC and tail == b""
            assert parsed["payload_bytes"] == len(payload) and parsed["payload_sha256"] == sha
        assert victim.read_bytes() == data

    check()
