"""Cached atlas chunks cannot lie: every way of corrupting them gives the clean atlas
again (the chunk is recomputed, with one line saying why) or a one-line refusal,
never a wrong atlas."""
import json
import shutil
import zipfile

import numpy as np
import pytest

from mechopt.run.atlas import compute_atlas
from mechopt.cli import main

STEP, CHUNK = 0.1, 64  # 344 designs, 6 chunks


@pytest.fixture(scope="module")
def clean(tmp_path_factory):
    folder = tmp_path_factory.mktemp("clean") / "chunks"
    table = compute_atlas(STEP, quadrature="polar", n_jobs=1, chunk_size=CHUNK, chunk_dir=folder)
    return table, folder


def _rerun(folder):
    msgs = []
    table = compute_atlas(STEP, quadrature="polar", n_jobs=1, chunk_size=CHUNK, chunk_dir=folder,
                          warn=msgs.append)
    return table, msgs


def _copy(clean, tmp_path):
    dst = tmp_path / "chunks"
    shutil.copytree(clean[1], dst)
    return dst


def _rewrite(path, values=None, header=None):
    with np.load(path, allow_pickle=False) as z:
        v, h = z["values"], json.loads(str(z["header"][()]))
    v = v if values is None else values(v)
    h = h if header is None else header(h)
    with open(path, "wb") as fh:
        np.savez(fh, values=v, header=np.array(json.dumps(h)))


def _edit_value(v):
    v = v.copy()
    v[3, 2] += 1e-3
    return v


CORRUPTIONS = {
    "edited value": lambda d: _rewrite(d / "chunk_000001.npz", values=_edit_value),
    "integer dtype": lambda d: _rewrite(d / "chunk_000002.npz", values=lambda v: v.astype(np.int64)),
    "wrong row count": lambda d: _rewrite(d / "chunk_000003.npz", values=lambda v: v[:-5]),
    "zero bytes": lambda d: (d / "chunk_000004.npz").write_bytes(b""),
    "garbage": lambda d: (d / "chunk_000000.npz").write_bytes(b"PK\x03\x04 not a zip"),
    "other kernel path": lambda d: _rewrite(
        d / "chunk_000005.npz", header=lambda h: {**h, "settings": {**h["settings"], "kernel": "other"}}),
}


@pytest.mark.parametrize("how", list(CORRUPTIONS))
def test_a_corrupted_chunk_is_recomputed(clean, tmp_path, how):
    folder = _copy(clean, tmp_path)
    CORRUPTIONS[how](folder)
    table, msgs = _rerun(folder)
    assert table.equals(clean[0])
    assert len(msgs) == 1 and "recomputed" in msgs[0] and "\n" not in msgs[0]


def test_swapped_chunk_files_are_recomputed(clean, tmp_path):
    folder = _copy(clean, tmp_path)
    a, b = folder / "chunk_000001.npz", folder / "chunk_000002.npz"
    tmp = folder / "x"
    a.rename(tmp)
    b.rename(a)
    tmp.rename(b)
    table, msgs = _rerun(folder)
    assert table.equals(clean[0])
    assert len(msgs) == 2 and all("other designs" in m for m in msgs)


def test_untouched_chunks_are_reused_without_a_word(clean, tmp_path):
    folder = _copy(clean, tmp_path)
    table, msgs = _rerun(folder)
    assert table.equals(clean[0]) and msgs == []
    with zipfile.ZipFile(folder / "chunk_000000.npz") as z:
        assert {"values.npy", "header.npy"} <= set(z.namelist())


def test_a_folder_of_another_kernel_path_or_version_is_refused(clean, tmp_path, capsys):
    out = tmp_path / "atlas"
    folder = out / ".atlas_chunks"
    shutil.copytree(clean[1], folder)
    meta = json.loads((folder / "settings.json").read_text())
    other = "numpy" if meta["kernel"] == "numba" else "numba"
    (folder / "settings.json").write_text(json.dumps({**meta, "kernel": other}))
    assert main(["atlas", "five-bar", "--step", str(STEP), "--quadrature", "polar", "--no-figures",
                 "--chunk-size", str(CHUNK), "--n-jobs", "1", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "kernel" in err and "other settings" in err
    assert not (out / "atlas.csv").exists()
