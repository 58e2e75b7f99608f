"""Every mechanism implementation the contract suite (tests/test_contract.py) runs on.

``CASES`` is a list of ``(id, factory, sample_points_fn)``:

* ``factory()`` returns a fresh mechanism instance;
* ``sample_points_fn(mech, rng, n)`` returns ``(x, y)``, two float arrays of ``n``
  reachable points well away from every singularity (``rng`` is a
  ``numpy.random.Generator``).

To add a mechanism, append its cases at the end of this file, e.g.::

    CASES += [("mymech-default", lambda: MyMech(...), sample_away_from_singularities)]

``sample_away_from_singularities`` works for any implementation of the protocol
(it only uses ``bounding_box``, ``reachable``, ``serial_clearance``, ``lci`` and
``type2_function``); pass a custom function when a mechanism needs one.
"""
from __future__ import annotations

import functools

import numpy as np

from mechopt.mechanisms.five_bar import FiveBar, MODES


def sample_away_from_singularities(
    mech, rng, n, lci_min=0.05, clearance=0.02, type2_min=0.05, max_rounds=200
):
    """Rejection-sample ``n`` points in ``mech.bounding_box()`` with LCI > ``lci_min``,
    serial clearance > ``clearance * length_scale`` and ``|type2_function|`` > ``type2_min``."""
    xmin, xmax, ymin, ymax = mech.bounding_box()
    xs, ys, have = [], [], 0
    batch = max(256, 8 * n)
    for _ in range(max_rounds):
        x = rng.uniform(xmin, xmax, batch)
        y = rng.uniform(ymin, ymax, batch)
        with np.errstate(invalid="ignore", divide="ignore"):
            keep = (
                np.asarray(mech.reachable(x, y), dtype=bool)
                & (np.asarray(mech.serial_clearance(x, y)) > clearance * mech.length_scale)
                & (np.asarray(mech.lci(x, y)) > lci_min)
                & (np.abs(np.asarray(mech.type2_function(x, y))) > type2_min)
            )
        xs.append(x[keep])
        ys.append(y[keep])
        have += int(keep.sum())
        if have >= n:
            return np.concatenate(xs)[:n], np.concatenate(ys)[:n]
    raise RuntimeError(f"could not sample {n} well-conditioned points of {mech!r}")


# (label, r1, r2, r3, modes): r1 < r2, r1 > r2 (workspace with holes), r3 = 0, and
# one of Liu 2006's examples (r1 + r2 + r3 = 3). With r3 = 0 the modes "++" and "--"
# put both elbows on the same point (B1 = B2, det A = 0 everywhere): they have no
# regular pose, so only "+-" and "-+" are contract cases there.
_FIVE_BAR_LENGTHS = [
    ("r1<r2", 1.0, 1.5, 0.5, MODES),
    ("r1>r2", 1.6, 0.9, 0.5, MODES),
    ("r3=0", 1.2, 1.8, 0.0, ("+-", "-+")),
    ("liu-0.7-1.7-0.6", 0.7, 1.7, 0.6, MODES),
]

CASES = [
    (
        f"FiveBar[{label},{mode}]",
        functools.partial(FiveBar, r1, r2, r3, mode),
        sample_away_from_singularities,
    )
    for label, r1, r2, r3, modes in _FIVE_BAR_LENGTHS
    for mode in modes
]
