"""The exported MJCF carries the dynamics' masses: MuJoCo's equations of motion of the
exported tree, with the loop closed by the constraint's force, give the motor efforts
of :mod:`mechopt.analysis.dynamics` along a motion (gravity on, in the plane).

MuJoCo's own inverse dynamics (``mj_inverse``) computes the loop's force from its soft
constraint model (a force that depends on the constraint's violation and velocity,
not the ideal one), so the test uses MuJoCo's exact parts instead: its joint-space
inertia ``M(q)`` (``mj_fullM``), its bias force ``C(q, q_dot) q_dot + g(q)``
(``qfrc_bias``, recursive Newton-Euler) and the closure sites' Jacobians
(``mj_jacSite``), and solves ``M q_ddot + bias = S^T tau + J_c^T lambda`` for the two
motor efforts ``tau`` and the loop force ``lambda`` (least squares; the system is
square for a 4-joint tree and its residual is checked below 1e-9 of the largest
term). The joints' rates and accelerations are central differences of mechopt's
inverse kinematics on a fine timing (step 1/4000 of the cycle, error about 1e-5
relative; measured 4e-8 of the peak), so the tolerance is 1e-6 of the peak effort.
"""
from __future__ import annotations

import numpy as np
import pytest

from mechopt.analysis import dynamics as dyn
from mechopt.core import motion as mo
from mechopt.export import export
from mechopt.export.source import load

mujoco = pytest.importorskip("mujoco")

from test_export import write_design  # noqa: E402  (the designs of the export tests)

#: fine timing of the motion (samples), the stride of the checked samples, the cycle [s]
FINE, STRIDE, CYCLE = 4001, 200, 0.5


def _si(tree, name, value, metres):
    return value * (metres if tree.joint(name).kind == "prismatic" else 1.0)


@pytest.mark.parametrize("name", ["five-bar", "biglide"])
def test_mujoco_equations_of_motion_give_mechopts_efforts(tmp_path, name):
    path = write_design(tmp_path / "design", name)
    export(path, tmp_path / "export", "mjcf", samples=20)
    src = load(path)
    tree = src.tree()
    m = mujoco.MjModel.from_xml_path(str(tmp_path / "export" / "robot.xml"))
    d = mujoco.MjData(m)
    m.opt.gravity[:] = (0.0, -dyn.STANDARD_GRAVITY, 0.0)  # mechopt's "down": -y in the plane
    # a straight cycloidal move across the task's box (shrunk to stay inside it)
    x0, x1, y0, y1 = src.task.bbox
    cx, cy, sx, sy = (x0 + x1) / 2, (y0 + y1) / 2, 0.4 * (x1 - x0), 0.4 * (y1 - y0)
    fine = mo.timed_motion(mo.segment_path((cx - sx, cy - sy), (cx + sx, cy + sy)), CYCLE, "cycloidal", FINE)
    conf = src.configuration(fine["x"], fine["y"])
    q = {j.name: np.unwrap(_si(tree, j.name, np.asarray(conf[j.name], float), src.metres)) for j in tree.joints}
    h = fine["t"][1] - fine["t"][0]
    ks = np.arange(STRIDE, FINE - 1, STRIDE)  # interior samples (central differences)
    # mechopt's efforts at those samples
    mx, my = src.spec.to_mech(src.mech, fine["x"][ks], fine["y"][ks])
    motion = {k: fine[k][ks] for k in ("xd", "yd", "xdd", "ydd")}
    model = dyn.mass_model(src.mech, length_unit=src.metres)
    tau_mechopt = dyn.inverse_dynamics(src.mech, dict(motion, x=mx, y=my), model, "down", src.metres)["tau"]
    # MuJoCo's equations of motion of the exported tree
    site_a, site_b = (m.site(c.name).id for c in tree.closure)
    act = [m.jnt_dofadr[m.joint(n).id] for n in tree.actuated]
    tau_mj, resid = [], []
    for k in ks:
        qacc = np.zeros(m.nv)
        for j in tree.joints:
            jid = m.joint(j.name).id
            v = q[j.name]
            d.qpos[m.jnt_qposadr[jid]] = v[k]
            d.qvel[m.jnt_dofadr[jid]] = (v[k + 1] - v[k - 1]) / (2 * h)
            qacc[m.jnt_dofadr[jid]] = (v[k + 1] - 2 * v[k] + v[k - 1]) / h ** 2
        mujoco.mj_forward(m, d)  # positions, inertia, bias (its own qacc is not used)
        M = np.zeros((m.nv, m.nv))
        mujoco.mj_fullM(m, d, M)
        rhs = M @ qacc + d.qfrc_bias
        ja, jb = np.zeros((3, m.nv)), np.zeros((3, m.nv))
        mujoco.mj_jacSite(m, d, ja, None, site_a)
        mujoco.mj_jacSite(m, d, jb, None, site_b)
        S = np.zeros((2, m.nv))
        S[0, act[0]] = S[1, act[1]] = 1.0
        A = np.vstack([S, (ja - jb)[:2]]).T  # columns: the two motors, the loop force (x, y)
        sol = np.linalg.lstsq(A, rhs, rcond=None)[0]
        resid.append(np.abs(A @ sol - rhs).max() / max(np.abs(rhs).max(), 1e-300))
        tau_mj.append(sol[:2])
    tau_mj = np.array(tau_mj)
    peak = np.abs(tau_mechopt).max()
    assert max(resid) < 1e-9
    assert peak > 0.05 * np.abs(tau_mj).max() > 0  # efforts that are not zero

    np.testing.assert_allclose(tau_mj, tau_mechopt, rtol=0, atol=1e-6 * peak)
