"""``mechopt export``: the exported models are the designed mechanism, checked in the
peer libraries (Pinocchio, MuJoCo, ezdxf, Pillow), not by re-running the exporter's
own forward kinematics.

The designs are hand-built design.json records, one per mechanism ``mechopt design``
sizes: the lengths a small design run found (``mechopt design ... --gen 5 --pop 12
--no-polish``, the tasks of tests/test_design.py), certified and written by the design
workflow's own record functions (``_design_record``, ``json_record``; the fine
certification sampling, as ``mechopt design`` writes design.json), with the run.json
settings of their evaluator. That costs about 0.1 s per mechanism instead of a design
run's 15 s.

Sample sizes: Pinocchio's forward kinematics at 1000 task points per mechanism (800
seeded uniform points inside the task, 200 on its boundary), its constraint projection
at 250 (200 + 50); MuJoCo's hold-and-settle at 100 task points per
mechanism (each a separate 0.05 s simulation from the passive joints perturbed by 0.02
rad, run as one batch by ``mujoco.rollout``), its drive along the path once for 1 s of
simulated time. The slow-marked test repeats the MuJoCo hold at 1000 points.
"""
from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path

import numpy as np
import pytest

# the export extra (make installs it: pip install -e '.[export]'); not skipped when missing
import ezdxf
import mujoco
import pinocchio as pin

from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.task import Task
from mechopt.requirements import Requirements
from mechopt.cli import main
from mechopt.export import drawings, export
from mechopt.export.source import load, path_samples
from mechopt.run.io import write_json

#: (mechanism, task, design variables, placement, max_length): the designs of small runs
DESIGNS = {
    "five-bar": (Task.rect(100, 60, (0, 180)), dict(r1=163.70023978471295, r2=183.68127688729854,
                                                    r3=1.2850765535874165, mode="+-"), 250.0),
    "asymmetric-five-bar": (Task.rect(40, 30, (0, 120)), dict(a1=73.216652861024, c1=82.13445565848563,
                                                              a2=102.13728123821787, c2=115.51246149935511,
                                                              r3=1.2187933153909878, mode="+-"), 250.0),
    "biglide": (Task.rect(60, 40, (0, 100)), dict(l1=20.697526493504693, l2=67.96359733903873, mode="--"), 200.0),
    "bipod": (Task.circle(20, (0, 80)), dict(b=115.91632764423595, mode="up"), 200.0),
    "gantry": (Task.rect(60, 40, (0, 100)), dict(d1=20.697526493504693, l=67.96359733903873, mode="--"), 200.0),
}
NAMES = tuple(DESIGNS)
#: the rigid links' pin distances [mm] as the mechanisms define them (DXF files)
LINK_LENGTHS = {
    "five-bar": lambda m: {"base": 2 * m.r3, "crank1": m.r1, "crank2": m.r1, "distal1": m.r2, "distal2": m.r2},
    "asymmetric-five-bar": lambda m: {"base": 2 * m.r3, "crank1": m.a1, "crank2": m.a2, "distal1": m.c1,
                                      "distal2": m.c2},
    "biglide": lambda m: {"link1": m.l2, "link2": m.l2},
    "bipod": lambda m: {"base": m.b},
    "gantry": lambda m: {"link1": m.l, "link2": m.l},
}
#: path samples of the five-bar's export, and the cap on the GIF's frames it runs with
#: (drawings.MAX_FRAMES, 60, patched): every 3rd sample, 0, 3, 6, 9 -> 4 frames
GIF_SAMPLES, GIF_MAX_FRAMES = 12, 5


def write_design(folder: Path, name: str) -> Path:
    """design.json and run.json of the design ``name`` in ``folder`` (module docstring)."""
    from mechopt.workflows.design import _design_record, json_record

    task, v, lmax = DESIGNS[name]
    ev = DesignEvaluator(name, task, Requirements(min_lci=0.3), ("size", "min-lci"), max_length=lmax)
    vv = {**v, "task_x": task.reference[0], "task_y": task.reference[1]}
    res = certify(ev, vv)
    assert res["feasible"], name
    folder.mkdir(parents=True, exist_ok=True)
    write_json(json_record(_design_record(ev, vv, res, 0)), folder / "design.json")
    write_json({"problem": "design", "design": ev.settings()}, folder / "run.json")
    return folder / "design.json"


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    """``{name: (design.json, export folder, info)}``: each design exported once (every
    format for the five-bar, the GIF's frames capped at GIF_MAX_FRAMES; the formats
    without drawing for the others)."""
    out = {}
    for name in NAMES:
        root = tmp_path_factory.mktemp(name)
        path = write_design(root / "design", name)
        if name == "five-bar":  # every format; the GIF with at most GIF_MAX_FRAMES frames
            with pytest.MonkeyPatch.context() as mp:
                mp.setattr(drawings, "MAX_FRAMES", GIF_MAX_FRAMES)
                info = export(path, root / "export", None, samples=GIF_SAMPLES)
        else:
            info = export(path, root / "export", "urdf,mjcf,dxf,csv", samples=200)
        out[name] = (path, root / "export", info)
    return out


def task_points(task, n_inside=800, n_boundary=200, seed=0):
    """Seeded uniform points inside the task and points on its boundary [task unit]."""
    rng = np.random.default_rng(seed)
    x0, x1, y0, y1 = task.bbox
    xs, ys = [], []
    while sum(len(a) for a in xs) < n_inside:
        x, y = rng.uniform(x0, x1, 4 * n_inside), rng.uniform(y0, y1, 4 * n_inside)
        keep = task.contains(x, y)
        xs.append(x[keep])
        ys.append(y[keep])
    bx, by = task.boundary_at(rng.uniform(0, 1, n_boundary))
    return np.r_[np.concatenate(xs)[:n_inside], bx], np.r_[np.concatenate(ys)[:n_inside], by]


def si(tree, name, value, metres):
    """A joint value in the simulators' units (prismatic: m)."""
    return value * metres if tree.joint(name).kind == "prismatic" else value


# ------------------------------------------------------------------ Pinocchio
class PinModel:
    """The exported URDF in Pinocchio, the loop as a RigidConstraintModel between the
    closure frames (as Gepetto's example-parallel-robots builds it)."""

    def __init__(self, urdf):
        self.model = pin.buildModelFromUrdf(str(urdf))
        self.data = self.model.createData()
        self.fa, self.fb = (self.model.getFrameId(n) for n in ("closedloop1_A", "closedloop1_B"))
        fa, fb = self.model.frames[self.fa], self.model.frames[self.fb]
        self.constraint = pin.RigidConstraintModel(pin.ContactType.CONTACT_3D, self.model, fa.parentJoint,
                                                   fa.placement, fb.parentJoint, fb.placement,
                                                   pin.ReferenceFrame.LOCAL)
        self.cdata = self.constraint.createData()

    def index(self, name):
        jid = self.model.getJointId(name)
        assert jid < self.model.njoints, name
        return self.model.joints[jid].idx_q

    def frames(self, q):
        pin.framesForwardKinematics(self.model, self.data, q)
        return self.data.oMf[self.fa].translation.copy(), self.data.oMf[self.fb].translation.copy()

    def project(self, q, passive, iters=10, tol=1e-14):
        """Passive joints ``passive`` (indices) solved by Gauss-Newton on the constraint's
        residual with Pinocchio's constraint Jacobian (until the residual is below ``tol``
        [m]); the actuated ones kept."""
        m, d, c, cd = self.model, self.data, self.constraint, self.cdata
        for _ in range(iters):
            pin.computeJointJacobians(m, d, q)
            c.calc(m, d, cd)
            r = cd.c1Mc2.translation
            if np.linalg.norm(r) < tol:
                break
            J = pin.getConstraintJacobian(m, d, c, cd)
            q = q.copy()
            q[passive] += np.linalg.lstsq(J[:, passive], r, rcond=None)[0]
        return q


@pytest.mark.parametrize("name", NAMES)
def test_pinocchio_forward_kinematics_reaches_the_task(exported, name):
    """Every joint from mechopt (actuated: IK; passive: its elbows): Pinocchio's forward
    kinematics puts both closure frames on the task point, 1000 points, within 1e-9 m."""
    path, out, _ = exported[name]
    src = load(path)
    tree = src.tree()
    pm = PinModel(out / "robot.urdf")
    assert pm.model.nq == len(tree.joints)
    assert [pm.model.names[i] for i in range(1, pm.model.njoints)] == [j.name for j in tree.joints]
    x, y = task_points(src.task)
    conf = src.configuration(x, y)
    q = np.zeros((len(x), pm.model.nq))
    for j in tree.joints:
        q[:, pm.index(j.name)] = si(tree, j.name, conf[j.name], src.metres)
    assert np.isfinite(q).all()
    err, res = [], []
    for k in range(len(x)):
        a, b = pm.frames(q[k])
        err.append(max(np.hypot(a[0] - x[k] * src.metres, a[1] - y[k] * src.metres), abs(a[2])))
        res.append(np.linalg.norm(a - b))
    assert max(err) < 1e-9, max(err)
    assert max(res) < 1e-9, max(res)


@pytest.mark.parametrize("name", NAMES)
def test_pinocchio_constraint_projection_closes_the_loop(exported, name):
    """Actuated joints from mechopt's IK alone; the passive joints solved by Pinocchio's
    RigidConstraintModel (Gauss-Newton from a guess 0.05 rad off): the loop residual
    below 1e-9 m and the platform within 1e-9 m of the task point, at 250 points (a
    Python loop of Pinocchio calls: 1000 points cost 1.5 s a mechanism)."""
    path, out, _ = exported[name]
    src = load(path)
    tree = src.tree()
    pm = PinModel(out / "robot.urdf")
    x, y = task_points(src.task, 200, 50, seed=1)
    mx, my = src.spec.to_mech(src.mech, x, y)
    q1, q2, ok = src.mech.ik(mx, my)
    assert ok.all()
    guess = src.configuration(x, y)
    passive = [pm.model.joints[pm.model.getJointId(j.name)].idx_v for j in tree.joints if not j.actuated]
    err, res = [], []
    for k in range(len(x)):
        q = np.zeros(pm.model.nq)
        for j in tree.joints:
            q[pm.index(j.name)] = guess[j.name][k] + 0.05 if not j.actuated else 0.0
        for n, v in zip(tree.actuated, (q1[k], q2[k])):
            q[pm.index(n)] = si(tree, n, v, src.metres)
        q = pm.project(q, passive)
        a, b = pm.frames(q)
        err.append(np.hypot(a[0] - x[k] * src.metres, a[1] - y[k] * src.metres))
        res.append(np.linalg.norm(a - b))
    assert max(res) < 1e-9, max(res)
    assert max(err) < 1e-9, max(err)


# ------------------------------------------------------------------ MuJoCo
def mj_hold(xml, src, x, y, nstep=250, kick=0.02):
    """Motors held at mechopt's IK (position servos), passive joints started ``kick`` rad
    off, ``nstep`` steps, all points in one ``mujoco.rollout`` batch: ``(residual,
    platform error)`` [m] per point after settling."""
    from mujoco import rollout

    tree = src.tree()
    m = mujoco.MjModel.from_xml_path(str(xml))
    d = mujoco.MjData(m)
    conf = src.configuration(x, y)
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    init = np.zeros((len(x), mujoco.mj_stateSize(m, spec)))
    for i in range(len(x)):
        mujoco.mj_resetData(m, d)
        for j in tree.joints:
            d.qpos[m.jnt_qposadr[m.joint(j.name).id]] = si(tree, j.name, conf[j.name][i], src.metres) + (
                0.0 if j.actuated else kick)
        mujoco.mj_getState(m, d, init[i], spec)
    ctrl = np.stack([si(tree, n, conf[n], src.metres) for n in tree.actuated], -1)
    _, sens = rollout.rollout(m, d, init, np.repeat(ctrl[:, None, :], nstep, 1), nstep=nstep)
    a, b = sens[:, -1, :3], sens[:, -1, 3:6]
    return np.linalg.norm(a - b, axis=1), np.hypot(a[:, 0] - x * src.metres, a[:, 1] - y * src.metres)


@pytest.mark.parametrize("name", NAMES)
def test_mujoco_holds_the_designed_poses(exported, name):
    """The MJCF loads with its names; held at mechopt's IK at 100 task points, the loop
    residual settles below 1e-5 m and the platform within 1e-4 m of the task point."""
    path, out, _ = exported[name]
    src = load(path)
    tree = src.tree()
    m = mujoco.MjModel.from_xml_path(str(out / "robot.xml"))
    assert m.neq == 1 and m.nu == 2
    assert [m.actuator(i).name for i in range(m.nu)] == list(tree.actuated)
    assert sorted(m.joint(i).name for i in range(m.njnt)) == sorted(j.name for j in tree.joints)
    # the motors' ranges are the design's (crank ranges or strokes), in SI units
    ranges = src.record.get("joint_ranges_deg") or src.record["strokes"]
    for n, (lo, hi) in zip(tree.actuated, ranges):
        f = math.pi / 180 if "joint_ranges_deg" in src.record else src.metres
        assert np.allclose(m.jnt_range[m.joint(n).id], (lo * f, hi * f), rtol=1e-15, atol=0)
        assert m.jnt_limited[m.joint(n).id]
    x, y = task_points(src.task, 80, 20, seed=2)
    res, err = mj_hold(out / "robot.xml", src, x, y)
    assert res.max() < 1e-5, res.max()
    assert err.max() < 1e-4, err.max()


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_mujoco_holds_the_designed_poses_1000(exported, name):
    """:func:`test_mujoco_holds_the_designed_poses` at 1000 task points."""
    path, out, _ = exported[name]
    src = load(path)
    res, err = mj_hold(out / "robot.xml", src, *task_points(src.task, seed=3))
    assert res.max() < 1e-5 and err.max() < 1e-4, (res.max(), err.max())


@pytest.mark.parametrize("name", NAMES)
def test_mujoco_drive_along_the_path_keeps_the_loop_closed(exported, name):
    """Starting from the home keyframe's neighbour (the path's first sample, exact), the
    servos driven along the path's IK (linear in time, the path once in 1 s of simulated
    time): the loop residual stays below 1e-4 m at every step."""
    from mujoco import rollout

    path, out, _ = exported[name]
    src = load(path)
    tree = src.tree()
    m = mujoco.MjModel.from_xml_path(str(out / "robot.xml"))
    d = mujoco.MjData(m)
    t, px, py = path_samples(src.task, 200)
    conf = src.configuration(px, py)
    for j in tree.joints:
        d.qpos[m.jnt_qposadr[m.joint(j.name).id]] = si(tree, j.name, conf[j.name][0], src.metres)
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    init = np.zeros(mujoco.mj_stateSize(m, spec))
    mujoco.mj_getState(m, d, init, spec)
    nstep = int(round(1.0 / m.opt.timestep))
    ts = np.arange(1, nstep + 1) * m.opt.timestep
    ctrl = np.stack([np.interp(ts, np.r_[t, 1.0], si(tree, n, np.r_[conf[n], conf[n][0]], src.metres))
                     for n in tree.actuated], -1)
    _, sens = rollout.rollout(m, d, init[None], ctrl[None], nstep=nstep)
    res = np.linalg.norm(sens[0, :, :3] - sens[0, :, 3:6], axis=1)
    assert len(res) == nstep
    assert res.max() < 1e-4, res.max()
    # and it moved: the platform travelled the task's extent
    span = np.ptp(sens[0, :, 0]) / src.metres
    x0, x1, _, _ = src.task.bbox
    assert span > 0.9 * (x1 - x0)


def test_mujoco_home_keyframe_is_closed(exported):
    """The ``home`` keyframe is a closed pose at the task's centre."""
    for name in NAMES:
        path, out, info = exported[name]
        src = load(path)
        m = mujoco.MjModel.from_xml_path(str(out / "robot.xml"))
        d = mujoco.MjData(m)
        mujoco.mj_resetDataKeyframe(m, d, m.keyframe("home").id)
        mujoco.mj_forward(m, d)
        a, b = d.site("closedloop1_A").xpos, d.site("closedloop1_B").xpos
        assert np.linalg.norm(a - b) < 1e-12
        hx, hy = info["home"]["x"], info["home"]["y"]
        assert np.hypot(a[0] - hx * src.metres, a[1] - hy * src.metres) < 1e-12


# ------------------------------------------------------------------ CAD, path, animation
@pytest.mark.parametrize("name", NAMES)
def test_dxf_hole_distances_are_the_link_lengths(exported, name):
    """Read back with ezdxf: one file per rigid link, two holes each, their centre
    distance the link length within 1 um, the unit and the digest in the header."""
    path, out, info = exported[name]
    src = load(path)
    want = LINK_LENGTHS[name](src.mech)
    files = sorted(p.name for p in out.glob("link-*.dxf"))
    assert files == sorted(f"link-{b}.dxf" for b in want)
    for body, length in want.items():
        doc = ezdxf.readfile(out / f"link-{body}.dxf")
        assert doc.header["$INSUNITS"] == 4  # mm
        assert dict(doc.header.custom_vars)["MECHOPT_DESIGN_SHA256"] == info["design_sha256"]
        holes = [e.dxf.center for e in doc.modelspace().query("CIRCLE[layer=='HOLES']")]
        assert len(holes) == 2
        assert abs((holes[0] - holes[1]).magnitude - length) < 1e-3  # 1 um in mm
        outline = doc.modelspace().query("LWPOLYLINE[layer=='OUTLINE']")
        if length > 0:
            (poly,) = outline
            pts = np.array([p[:2] for p in poly.get_points("xy")])
            # the capsule: its straight sides as long as the link, its width as stated
            assert abs(np.hypot(*(pts[1] - pts[0])) - length) < 1e-3
            assert abs(np.hypot(*(pts[2] - pts[1])) - info["link_width"]) < 1e-9


@pytest.mark.parametrize("name", NAMES)
def test_path_csv(exported, name):
    """path.csv: the digest line; ``t`` the arc-length fraction, uniform; the points on
    the task's boundary; ``q1, q2`` the actuators' values that place the platform there
    (the mechanism's forward kinematics, the other direction from the IK)."""
    import pandas as pd

    path, out, info = exported[name]
    src = load(path)
    text = (out / "path.csv").read_text()
    assert text.splitlines()[0] == f"# mechopt design sha256 {info['design_sha256']}"
    df = pd.read_csv(out / "path.csv", comment="#")
    assert list(df.columns) == ["t", "q1", "q2", "x", "y"]
    n = len(df)
    assert n == info["samples"]
    assert np.allclose(df.t, np.arange(n) / n, rtol=0, atol=1e-15)
    x, y = df.x.to_numpy(), df.y.to_numpy()
    assert np.abs(src.task.signed_distance(x, y)).max() < 1e-9 * src.task.diameter
    gaps = np.hypot(np.diff(np.r_[x, x[0]]), np.diff(np.r_[y, y[0]]))
    # uniform arc length: chords of equal arcs (a polygon's corners cut a chord short)
    assert np.median(gaps) == pytest.approx(src.task.perimeter / n, rel=1e-3)
    mx, my = src.spec.to_mech(src.mech, x, y)
    up = src.mech.assembly_of(mx, my) == "up"
    fk = [src.mech.fk(df.q1.to_numpy(), df.q2.to_numpy(), a) for a in ("up", "down")]
    fx, fy, ok = (np.where(up, u, w) for u, w in zip(*fk))
    assert ok.all()
    assert np.hypot(fx - mx, fy - my).max() < 1e-9 * src.task.diameter


def test_gif_decodes_with_the_stated_frames(exported):
    """path.gif decodes (Pillow) with one frame per k-th path sample, k = ceil(n /
    MAX_FRAMES) (12 samples, at most 5 frames: k = 3, samples 0, 3, 6, 9), the digest as
    its comment; the SVG carries the digest too."""
    from PIL import Image

    _, out, info = exported["five-bar"]
    assert info["frame_step"] == 3 and info["frames"] == 4
    with Image.open(out / "path.gif") as im:
        assert im.n_frames == len(range(0, GIF_SAMPLES, 3)) == 4
        assert im.info["comment"].decode() == f"mechopt design sha256 {info['design_sha256']}"
        for k in range(im.n_frames):
            im.seek(k)
            im.load()
    assert drawings.frame_step(60) == 1 and drawings.frame_step(61) == 2 and drawings.frame_step(200) == 4
    assert info["design_sha256"] in (out / "mechanism.svg").read_text()


# ------------------------------------------------------------------ digest and names
def test_every_file_carries_the_design_digest(exported):
    """The digest is the sha256 of design.json's canonical JSON (sorted keys, no
    spaces): the same for the file re-indented, another for a changed value; every
    file names it."""
    path, out, info = exported["five-bar"]
    rec = json.loads(path.read_text())
    canon = json.dumps(rec, sort_keys=True, separators=(",", ":"))
    digest = hashlib.sha256(canon.encode()).hexdigest()
    assert info["design_sha256"] == digest
    assert json.loads((out / "export.json").read_text())["design_sha256"] == digest
    for f in ("robot.urdf", "robot.yaml", "robot.xml", "mechanism.svg", "path.csv"):
        assert digest in (out / f).read_text(), f
    m = mujoco.MjModel.from_xml_path(str(out / "robot.xml"))
    tid = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_TEXT, "mechopt_design_sha256")
    adr, size = m.text_adr[tid], m.text_size[tid]
    assert bytes(m.text_data[adr:adr + size]).rstrip(b"\0").decode() == digest
    # re-indented: the same digest; a changed number: another
    other = path.parent.parent / "reindented"
    other.mkdir()
    (other / "design.json").write_text(json.dumps(rec, indent=7))
    (other / "run.json").write_text((path.parent / "run.json").read_text())
    assert load(other / "design.json").digest == digest
    rec["objectives"]["size"] += 1e-9
    (other / "design.json").write_text(json.dumps(rec))
    assert load(other / "design.json").digest != digest


def test_naming_convention(exported):
    """Actuated joints carry the mechanism's actuator names, the closure frames are
    closedloop1_A/B, robot.yaml states the loop and motors; URDF limits of the motors
    are the design's."""
    import xml.etree.ElementTree as ET

    for name in NAMES:
        path, out, _ = exported[name]
        src = load(path)
        tree = src.tree()
        assert tree.actuated == tuple(src.mech.joint_names)
        yaml = (out / "robot.yaml").read_text()
        assert "closed_loop: [['closedloop1_A', 'closedloop1_B']]" in yaml
        assert f"name_mot: ['{tree.actuated[0]}', '{tree.actuated[1]}']" in yaml
        root = ET.parse(out / "robot.urdf").getroot()
        joints = {j.get("name"): j for j in root.iter("joint")}
        assert {"closedloop1_A_joint", "closedloop1_B_joint"} <= set(joints)
        for n in tree.actuated:
            lim = joints[n].find("limit")
            lo, hi = float(lim.get("lower")), float(lim.get("upper"))
            if "joint_ranges_deg" in src.record:
                want = src.record["joint_ranges_deg"][tree.actuated.index(n)]
                assert (math.degrees(lo), math.degrees(hi)) == pytest.approx(want, rel=1e-14)
            else:
                want = src.record["strokes"][tree.actuated.index(n)]
                assert (lo / src.metres, hi / src.metres) == pytest.approx(want, rel=1e-14)


def test_export_package_names_no_mechanism():
    """The writers are generic: no module of mechopt/export names a mechanism (each
    declares its tree in its own module)."""
    import mechopt.export as pkg

    for f in Path(pkg.__file__).parent.glob("*.py"):
        text = f.read_text().lower()
        for word in ("five-bar", "five_bar", "fivebar", "biglide", "bipod", "gantry", "crank", "slider"):
            assert word not in text, (f.name, word)


# ------------------------------------------------------------------ bad input
def _one_line_exit_2(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechopt: error: ") and err.count("\n") == 1, err
    return err


def test_bad_input_writes_nothing(tmp_path, exported, capsys):
    """A JSON of another tool, a design.json without its run.json, one whose numbers do
    not build its mechanism, an unknown format, an unwritable folder: one line, exit
    status 2, nothing written (the folder not created, an existing one unchanged)."""
    path, _, _ = exported["biglide"]
    foreign = tmp_path / "foreign.json"
    foreign.write_text(json.dumps({"name": "some other tool", "version": 3}))
    err = _one_line_exit_2(["export", str(foreign), "--to", str(tmp_path / "o1")], capsys)
    assert "not a design.json" in err and not (tmp_path / "o1").exists()

    lone = tmp_path / "lone"
    lone.mkdir()
    (lone / "design.json").write_text(path.read_text())
    err = _one_line_exit_2(["export", str(lone / "design.json"), "--to", str(tmp_path / "o2")], capsys)
    assert "run.json" in err and not (tmp_path / "o2").exists()

    bent = tmp_path / "bent"
    bent.mkdir()
    rec = json.loads(path.read_text())
    rec["variables"]["l2"] *= 1.01
    (bent / "design.json").write_text(json.dumps(rec))
    (bent / "run.json").write_text((path.parent / "run.json").read_text())
    err = _one_line_exit_2(["export", str(bent / "design.json"), "--to", str(tmp_path / "o3")], capsys)
    assert "build" in err and not (tmp_path / "o3").exists()

    err = _one_line_exit_2(["export", str(path), "--to", str(tmp_path / "o4"), "--format", "urdf,step"], capsys)
    assert "--format" in err and not (tmp_path / "o4").exists()

    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    err = _one_line_exit_2(["export", str(path), "--to", str(blocker / "sub")], capsys)
    assert "not writable" in err or "cannot write" in err

    kept = tmp_path / "kept"
    kept.mkdir()
    (kept / "notes.txt").write_text("mine")
    _one_line_exit_2(["export", str(foreign), "--to", str(kept)], capsys)
    assert sorted(p.name for p in kept.iterdir()) == ["notes.txt"]


def test_cli_export_writes_the_set(tmp_path, exported, capsys):
    """``mechopt export`` writes the formats asked for, export.json and the manifest,
    and lists them on one line."""
    path, _, _ = exported["bipod"]
    assert main(["export", str(path), "--to", str(tmp_path / "o"), "--format", "urdf,dxf"]) == 0
    line = capsys.readouterr().out
    assert line.count("\n") == 1 and "bipod" in line
    names = sorted(p.name for p in (tmp_path / "o").iterdir())
    assert names == [".mechopt.lock", "export.json", "link-base.dxf", "manifest.json", "robot.urdf",
                     "robot.yaml"] or names == ["export.json", "link-base.dxf", "manifest.json", "robot.urdf",
                                                "robot.yaml"]
    info = json.loads((tmp_path / "o" / "export.json").read_text())
    assert set(info["files"]) == {"link-base.dxf", "robot.urdf", "robot.yaml"}


# ------------------------------------------------------------------ the tree itself
@pytest.mark.parametrize("name", NAMES)
def test_planar_forward_kinematics_agrees_with_pinocchio(exported, name):
    """KinematicTree.forward (what the drawings use) at 50 random, not closed, joint
    values: every body frame and closure frame where Pinocchio puts it (1e-12 m)."""
    path, out, _ = exported[name]
    tree = load(path).tree().scaled(load(path).metres)
    pm = PinModel(out / "robot.urdf")
    rng = np.random.default_rng(4)
    q = {j.name: rng.uniform(-3, 3, 50) if j.kind == "revolute" else rng.uniform(-0.2, 0.2, 50) for j in tree.joints}
    pose = tree.forward(q)
    for k in range(50):
        qk = np.zeros(pm.model.nq)
        for j in tree.joints:
            qk[pm.index(j.name)] = q[j.name][k]
        a, b = pm.frames(qk)
        for j in tree.joints:
            p = pm.data.oMi[pm.model.getJointId(j.name)]
            assert np.hypot(p.translation[0] - pose[j.child][0][k], p.translation[1] - pose[j.child][1][k]) < 1e-12
            ang = math.atan2(p.rotation[1, 0], p.rotation[0, 0])
            assert abs(math.remainder(ang - pose[j.child][2][k], 2 * math.pi)) < 1e-12
        for c, pt in zip(("closedloop1_A", "closedloop1_B"), (a, b)):
            assert np.hypot(pt[0] - pose[c][0][k], pt[1] - pose[c][1][k]) < 1e-12


def test_a_malformed_tree_is_refused():
    """The tree's own checks: a parent that comes later, a non-unit prismatic axis,
    closure frames not named by the convention: one-line ValueErrors."""
    from mechopt.core.kinematic_tree import ClosureFrame, KinematicTree, TreeJoint

    cl = (ClosureFrame("closedloop1_A", "a", (1.0, 0.0)), ClosureFrame("closedloop1_B", "b", (1.0, 0.0)))
    ok = (TreeJoint("j1", "revolute", "base", "a", actuated=True), TreeJoint("j2", "revolute", "base", "b"))
    assert KinematicTree("toy", ok, cl).actuated == ("j1",)
    with pytest.raises(ValueError, match="not an earlier body"):
        KinematicTree("toy", (TreeJoint("j2", "revolute", "a", "b"), TreeJoint("j1", "revolute", "base", "a")), cl)
    with pytest.raises(ValueError, match="unit vector"):
        KinematicTree("toy", (ok[0], TreeJoint("j2", "prismatic", "base", "b", axis=(1.0, 1.0))), cl)
    with pytest.raises(ValueError, match="closure frames must be"):
        KinematicTree("toy", ok, (cl[1], cl[0]))


def test_point_task_path_is_its_points(tmp_path):
    """A point task (a trajectory): path.csv holds its points in their order, ``t`` the
    fraction of the polyline's length (``--samples`` ignored); a polygon task's path is
    its boundary, through every vertex when the samples fall on them."""
    import pandas as pd

    from mechopt.workflows.design import _design_record, json_record

    pts = np.array([[-20.0, 170.0], [0.0, 180.0], [30.0, 180.0], [30.0, 200.0]])
    for task, n in ((Task.points(pts), 7), (Task.polygon([(-30, 160), (30, 160), (0, 200)]), 12)):
        ev = DesignEvaluator("five-bar", task, Requirements(), ("size",), max_length=250)
        v = {**DESIGNS["five-bar"][1], "task_x": task.reference[0], "task_y": task.reference[1]}
        folder = tmp_path / task.kind
        folder.mkdir()
        write_json(json_record(_design_record(ev, v, certify(ev, v), 0)), folder / "design.json")
        write_json({"problem": "design", "design": ev.settings()}, folder / "run.json")
        export(folder / "design.json", folder / "out", "csv", samples=n)
        df = pd.read_csv(folder / "out" / "path.csv", comment="#")
        if task.kind == "points":
            assert np.array_equal(df[["x", "y"]].to_numpy(), pts)
            seg = np.hypot(*np.diff(pts, axis=0).T)
            assert np.allclose(df.t, np.r_[0, np.cumsum(seg)] / seg.sum(), rtol=0, atol=1e-15)
        else:  # perimeter 60 + 2 * 50 = 160, 12 samples: every 13.33, vertices at 0 and 60/160 = 4.5/12
            assert len(df) == 12 and (df.x.iloc[0], df.y.iloc[0]) == (-30.0, 160.0)
            assert np.abs(task.signed_distance(df.x, df.y)).max() < 1e-12
