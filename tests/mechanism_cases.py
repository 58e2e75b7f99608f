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

from mechopt.mechanisms.five_bar.model import FiveBar, MODES


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


# --- Stan 2008: Bipod (RPRPR) and Biglide (PRRRP) --------------------------------
# Their reachable sets are bounded by actuator stroke limits (J regular there), by
# the type-II x axis (Bipod half-plane branches) and by type-I lines (Biglide).
from mechopt.mechanisms.biglide import MODES as BIGLIDE_MODES  # noqa: E402
from mechopt.mechanisms.biglide import Biglide  # noqa: E402
from mechopt.mechanisms.bipod import Bipod  # noqa: E402

# (label, b, q1_min, q1_max, q2_min, q2_max, branches): Stan sec. 5.1's design
# (two separate regions), and an asymmetric one whose region crosses the x axis
# (type-II line inside the "full" workspace).
_BIPOD_DESIGNS = [
    ("stan-b60-q80-130", 60.0, 80.0, 130.0, 80.0, 130.0, ("up", "down", "full")),
    ("asym-crossing", 60.0, 20.0, 70.0, 30.0, 80.0, ("up", "full")),
]
CASES += [
    (
        f"Bipod[{label},{branch}]",
        functools.partial(Bipod, b, q1lo, q1hi, q2lo, q2hi, branch),
        sample_away_from_singularities,
    )
    for label, b, q1lo, q1hi, q2lo, q2hi, branches in _BIPOD_DESIGNS
    for branch in branches
]

# (label, l1, l2, q1_min, q1_max, q2_min, q2_max, modes): equal strokes, and
# unequal strokes with l2 > 2 l1 (a guide inside the x range).
_BIGLIDE_DESIGNS = [
    ("l1=40,l2=100,q0-200", 40.0, 100.0, 0.0, 200.0, 0.0, 200.0, BIGLIDE_MODES),
    ("l1=20,l2=100,unequal", 20.0, 100.0, -50.0, 150.0, 0.0, 250.0, ("--", "+-")),
]
CASES += [
    (
        f"Biglide[{label},{mode}]",
        functools.partial(Biglide, l1, l2, q1lo, q1hi, q2lo, q2hi, mode),
        sample_away_from_singularities,
    )
    for label, l1, l2, q1lo, q1hi, q2lo, q2hi, modes in _BIGLIDE_DESIGNS
    for mode in modes
]


# --- Wu 2008: gantry (two vertical sliders, three equal links) ---------------------
# Reachable sets bounded by stroke-limit arcs (J regular there) and by the type-I
# sides x = +-(l - d1). Table 1's machine in the paper's mode "--" and its mirror
# "++", and a long-stroke one with l > 2 d1 in all four modes (the mixed ones contain
# the type-II pose x = 0).
from mechopt.mechanisms.gantry import MODES as GANTRY_MODES  # noqa: E402
from mechopt.mechanisms.gantry import Gantry, wu2008_gantry  # noqa: E402


def _wu2008_gantry_in_mode(mode):
    return wu2008_gantry(10.0).with_mode(mode)


CASES += [
    (f"Gantry[wu2008-table1,{mode}]", functools.partial(_wu2008_gantry_in_mode, mode),
     sample_away_from_singularities)
    for mode in ("--", "++")
] + [
    (f"Gantry[d1=100,l=616,stroke=1500,{mode}]",
     functools.partial(Gantry, 100.0, 616.0, 1500.0, -200.0, 150.0, 50.0, mode),
     sample_away_from_singularities)
    for mode in GANTRY_MODES
]


# --- a general 5R with unequal legs (mechopt.mechanisms.asymmetric_five_bar) -----------
# (label, a1, c1, a2, c2, r3): the new mechanism is this module plus these cases.
from mechopt.mechanisms.asymmetric_five_bar import MODES as ASYM_MODES  # noqa: E402
from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar  # noqa: E402

_ASYM_DESIGNS = [("a1=1,c1=1.5,a2=0.8,c2=1.7", 1.0, 1.5, 0.8, 1.7, 0.5)]
CASES += [
    (f"AsymmetricFiveBar[{label},{mode}]",
     functools.partial(AsymmetricFiveBar, a1, c1, a2, c2, r3, mode), sample_away_from_singularities)
    for label, a1, c1, a2, c2, r3 in _ASYM_DESIGNS
    for mode in ASYM_MODES
]
