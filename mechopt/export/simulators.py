"""URDF (Pinocchio) and MJCF (MuJoCo) of a kinematic tree, lengths in metres.

Both files describe the tree of :mod:`mechopt.core.kinematic_tree` in the task frame
(the base midpoint at the origin, the mechanism in the world's x-y plane, revolute
axes along z), with the names of its convention: actuated joints named as the
mechanism's actuators (``theta1``, ``theta2`` or ``q1``, ``q2``), closure frames
``closedloop1_A`` (leg 1, the platform point) and ``closedloop1_B`` (leg 2).

* URDF describes a tree only: each closure frame is a massless link on a fixed joint
  (``closedloop1_A_joint``) of its leg's last body; the loop is closed by the user's
  constraint between the two frames: in Pinocchio a ``RigidConstraintModel`` of type
  ``CONTACT_3D`` between the frames' parent joints at the frames' placements
  (``tests/test_export.py`` builds it). ``robot.yaml`` states the loop and the motors
  in the format of Gepetto's example-parallel-robots (``closed_loop``, ``type``,
  ``name_mot``). The motors' limits are the design's (angle ranges or strokes); passive revolute joints
  are limited to ``[-pi, pi]``. Effort and velocity limits are placeholders (``1e6``:
  none stated) until the actuator limits of the dynamics work are known.
* MJCF closes the loop with ``<equality><connect site1="closedloop1_A"
  site2="closedloop1_B"/>``, drives the motors with position actuators (gains of
  :func:`servo_gains`), limits the motors to the design's ranges (``range`` and
  ``ctrlrange``) and leaves passive joints unlimited; geoms do not collide (the links of
  a planar mechanism overlap in the drawing plane). Gravity is ``-z``: normal to the
  plane, it does no work on the mechanism. The keyframe ``home`` holds the pose at the
  task's centre.

Masses and inertias are the mechanism's mass model on the tree's bodies
(:func:`mechopt.export.inertia.body_masses`), given as ``masses``.
"""
from __future__ import annotations

import math

from mechopt.core.kinematic_tree import BASE, CLOSURE_NAMES
from mechopt.export.inertia import link_width

__all__ = ["urdf", "robot_yaml", "mjcf", "body_length", "servo_gains", "MJCF_TIMESTEP", "SERVO_HZ",
           "CONSTRAINT_SOLREF", "CONSTRAINT_SOLIMP", "PLACEHOLDER_LIMIT"]

#: effort [N m or N] and velocity [rad/s or m/s] limits written where URDF needs one
PLACEHOLDER_LIMIT = 1e6
#: MuJoCo time step [s]
MJCF_TIMESTEP = 2e-4
#: natural frequency of the position servos [Hz] (critically damped)
SERVO_HZ = 20.0
#: the loop constraint's solref (time constant [s], damping ratio) and solimp
CONSTRAINT_SOLREF = (4 * MJCF_TIMESTEP, 1.0)
CONSTRAINT_SOLIMP = (0.99, 0.999, 0.001, 0.5, 2)


def _f(v) -> str:
    """A float with every digit (repr), as the files hold lengths."""
    return repr(float(v))


def _xyz(*v) -> str:
    return " ".join(_f(a) for a in v)


def body_length(tree, body) -> float:
    """Distance from the body's origin to its farthest pin [tree's unit].

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    body : str
        A body's name.

    Returns
    -------
    float
        The length [tree's unit].
    """
    return max((math.hypot(*p) for _, p in tree.pins()[body]), default=0.0)


def _digest_comment(digest) -> str:
    return f"<!-- mechopt design sha256 {digest} -->"


def urdf(tree, digest: str, masses: dict) -> str:
    """The URDF of ``tree`` (lengths in m; module docstring); ``masses``: ``{body: (mass
    [kg], com [m], (Ixx, Iyy, Izz) [kg m^2])}`` (:func:`mechopt.export.inertia.body_masses`).

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree, lengths [m].
    digest : str
        The design's digest (:func:`mechopt.export.source.design_digest`), written into the
        file.
    masses : dict
        ``{body: (mass, com, (Ixx, Iyy, Izz))}`` of every moving body [kg, m, kg m^2].

    Returns
    -------
    str
        The URDF text.
    """
    w = link_width(tree)
    lines = ['<?xml version="1.0"?>', _digest_comment(digest), f'<robot name="{tree.name}">',
             f'  <link name="{BASE}"/>']
    for j in tree.joints:
        L = body_length(tree, j.child)
        m, com, (ixx, iyy, izz) = masses[j.child]
        lines += [f'  <link name="{j.child}">',
                  '    <inertial>',
                  f'      <origin xyz="{_xyz(*com)}" rpy="0 0 0"/>',
                  f'      <mass value="{_f(m)}"/>',
                  f'      <inertia ixx="{_f(ixx)}" ixy="0" ixz="0" iyy="{_f(iyy)}" iyz="0" izz="{_f(izz)}"/>',
                  '    </inertial>']
        if L > 0:
            lines += ['    <visual>',
                      f'      <origin xyz="{_xyz(L / 2, 0.0, 0.0)}" rpy="0 {_f(math.pi / 2)} 0"/>',
                      f'      <geometry><cylinder radius="{_f(w / 2)}" length="{_f(L)}"/></geometry>',
                      '    </visual>']
        lines.append('  </link>')
        if j.kind == "revolute":
            axis, (lo, hi) = "0 0 1", (j.limits or (-math.pi, math.pi))
        else:
            axis, (lo, hi) = _xyz(*j.axis, 0.0), j.limits
        lines += [f'  <joint name="{j.name}" type="{j.kind}">',
                  f'    <parent link="{j.parent}"/>',
                  f'    <child link="{j.child}"/>',
                  f'    <origin xyz="{_xyz(*j.origin, 0.0)}" rpy="0 0 0"/>',
                  f'    <axis xyz="{axis}"/>',
                  f'    <limit lower="{_f(lo)}" upper="{_f(hi)}" effort="{_f(PLACEHOLDER_LIMIT)}" '
                  f'velocity="{_f(PLACEHOLDER_LIMIT)}"/>',
                  '  </joint>']
    for c in tree.closure:
        lines += [f'  <link name="{c.name}"/>',
                  f'  <joint name="{c.name}_joint" type="fixed">',
                  f'    <parent link="{c.body}"/>',
                  f'    <child link="{c.name}"/>',
                  f'    <origin xyz="{_xyz(*c.point, 0.0)}" rpy="0 0 0"/>',
                  '  </joint>']
    lines.append('</robot>')
    return "\n".join(lines) + "\n"


def robot_yaml(tree, digest: str) -> str:
    """The loop and the motors in the format of Gepetto's example-parallel-robots.

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    digest : str
        The design's digest (:func:`mechopt.export.source.design_digest`), written into the
        file.

    Returns
    -------
    str
        The YAML text.
    """
    a, b = CLOSURE_NAMES
    motors = ", ".join(f"'{n}'" for n in tree.actuated)
    return (f"# mechopt design sha256 {digest}\n"
            f"closed_loop: [['{a}', '{b}']]\n"
            "type: ['3d']\n"
            f"name_mot: [{motors}]\n")


def servo_gains(tree, kind: str, masses: dict):
    """``(kp, kv)`` of a position servo on a joint of ``kind``: critically damped at
    :data:`SERVO_HZ` for a reference inertia that bounds what the motor moves: for a
    prismatic joint the bodies' masses plus their moments over the shortest body length
    squared, ``sum m + sum Izz / L_min^2`` [kg] (a link turned by a prismatic joint's travel); for
    a revolute one ``sum m L_max^2 + sum Izz`` [kg m^2] (``masses`` of :func:`urdf`,
    tree lengths in m).

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree, lengths [m].
    kind : str
        The joint's kind, ``"revolute"`` or ``"prismatic"``.
    masses : dict
        ``{body: (mass, com, (Ixx, Iyy, Izz))}`` [kg, m, kg m^2], as for :func:`urdf`.

    Returns
    -------
    tuple of float
        ``(kp, kv)``: stiffness [N m/rad or N/m] and damping [N m s/rad or N s/m].
    """
    lengths = [L for L in (body_length(tree, b) for b in tree.bodies) if L > 0] or [1.0]
    mass = sum(m for m, _, _ in masses.values())
    izz = sum(i[2] for _, _, i in masses.values())
    ref = mass + izz / min(lengths) ** 2 if kind == "prismatic" else mass * max(lengths) ** 2 + izz
    w = 2.0 * math.pi * SERVO_HZ
    return ref * w * w, 2.0 * ref * w


def mjcf(tree, digest: str, home: dict, masses: dict) -> str:
    """The MJCF of ``tree`` (lengths in m; module docstring); ``home``: every joint's
    value at the task's centre (the keyframe ``home`` and its controls); ``masses`` as
    for :func:`urdf`.

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree, lengths [m].
    digest : str
        The design's digest (:func:`mechopt.export.source.design_digest`), written into the
        file.
    home : dict
        ``{joint: value}`` of every joint at the task's centre [rad or m].
    masses : dict
        ``{body: (mass, com, (Ixx, Iyy, Izz))}`` [kg, m, kg m^2], as for :func:`urdf`.

    Returns
    -------
    str
        The MJCF text.
    """
    w = link_width(tree)
    children = {}
    for j in tree.joints:
        children.setdefault(j.parent, []).append(j)
    closure = {c.body: c for c in tree.closure}
    order = []  # the joints in MuJoCo's order (depth first, as written): qpos of the keyframe

    def body(j, depth):
        order.append(j.name)
        pad = "  " * depth
        L = body_length(tree, j.child)
        m, com, (ixx, iyy, izz) = masses[j.child]
        out = [f'{pad}<body name="{j.child}" pos="{_xyz(*j.origin, 0.0)}">']
        if j.kind == "revolute":
            jt = f'{pad}  <joint name="{j.name}" type="hinge" axis="0 0 1"'
        else:
            jt = f'{pad}  <joint name="{j.name}" type="slide" axis="{_xyz(*j.axis, 0.0)}"'
        if j.limits is not None and j.actuated:
            jt += f' range="{_xyz(*j.limits)}"'
        out.append(jt + "/>")
        out.append(f'{pad}  <inertial pos="{_xyz(*com)}" mass="{_f(m)}" diaginertia="{_xyz(ixx, iyy, izz)}"/>')
        if L > 0:
            out.append(f'{pad}  <geom type="capsule" fromto="0 0 0 {_f(L)} 0 0" size="{_f(w / 2)}"/>')
        else:
            out.append(f'{pad}  <geom type="sphere" size="{_f(w / 2)}"/>')
        if j.child in closure:
            c = closure[j.child]
            out.append(f'{pad}  <site name="{c.name}" pos="{_xyz(*c.point, 0.0)}" size="{_f(w / 4)}"/>')
        for k in children.get(j.child, []):
            out += body(k, depth + 1)
        out.append(f"{pad}</body>")
        return out

    world = []
    for j in children.get(BASE, []):
        world += body(j, 2)
    qpos = " ".join(_f(home[n]) for n in order)
    ctrl = " ".join(_f(home[n]) for n in tree.actuated)
    a, b = CLOSURE_NAMES
    lines = [f'<mujoco model="{tree.name}">', f"  {_digest_comment(digest)}",
             '  <compiler angle="radian" autolimits="true" inertiafromgeom="false"/>',
             f'  <option timestep="{_f(MJCF_TIMESTEP)}" gravity="0 0 -9.81" integrator="implicitfast"/>',
             f'  <custom><text name="mechopt_design_sha256" data="{digest}"/></custom>',
             '  <default><geom contype="0" conaffinity="0" rgba="0.5 0.5 0.6 1"/></default>',
             '  <worldbody>', *world]
    lines += ['  </worldbody>', '  <equality>',
              f'    <connect name="closedloop1" site1="{a}" site2="{b}" solref="{_xyz(*CONSTRAINT_SOLREF)}" '
              f'solimp="{_xyz(*CONSTRAINT_SOLIMP)}"/>',
              '  </equality>', '  <actuator>']
    for n in tree.actuated:
        j = tree.joint(n)
        kp, kv = servo_gains(tree, j.kind, masses)
        rng = f' ctrlrange="{_xyz(*j.limits)}"' if j.limits is not None else ""
        lines.append(f'    <position name="{n}" joint="{n}" kp="{_f(kp)}" kv="{_f(kv)}"{rng}/>')
    lines += ['  </actuator>', '  <sensor>']
    lines += [f'    <framepos name="{c}" objtype="site" objname="{c}"/>' for c in CLOSURE_NAMES]
    lines += ['  </sensor>', '  <keyframe>', f'    <key name="home" qpos="{qpos}" ctrl="{ctrl}"/>',
              '  </keyframe>', '</mujoco>']
    return "\n".join(lines) + "\n"
