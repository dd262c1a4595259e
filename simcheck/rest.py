"""Does a scene file rest? Load it plainly (no robot, no collision filter of ours) in MuJoCo, PyBullet with
self-collision on or Drake, let gravity act for a while from q = 0, and report how far every movable joint
moved; and measure how deep its links interpenetrate at q = 0 (coal signed distance).

Gravity pulls against the scene's floor (:func:`scenes.description.read_scene_floor`: recon's graph.json beside
the file, else along -z), as in simcheck's world.

Each engine is imported only inside its function (MuJoCo and Drake are optional: ``pip install mujoco drake``).
Displacements are metres for a prismatic ("slide") joint and radians for a revolute ("hinge") one.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np

from scenes.description import read_scene_floor

__all__ = ["ENGINES", "rest_motion", "mujoco_rest", "pybullet_rest", "drake_rest", "link_overlaps", "moved_joints"]

ENGINES = ("mujoco", "pybullet", "drake")


def mujoco_rest(path: str | Path, seconds: float = 2.0) -> dict[str, tuple[str, float]]:
    """{joint: ("slide" | "hinge", displacement)} after ``seconds`` of gravity from q = 0 in MuJoCo
    (URDF or MJCF, ``MjModel.from_xml_path``, the model's own time step)."""
    import mujoco

    m = mujoco.MjModel.from_xml_path(str(path))
    floor = read_scene_floor(path)
    if not floor.level:
        m.opt.gravity[:] = floor.gravity(9.81)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    q0 = d.qpos.copy()
    for _ in range(int(round(seconds / m.opt.timestep))):
        mujoco.mj_step(m, d)
    slide, hinge = int(mujoco.mjtJoint.mjJNT_SLIDE), int(mujoco.mjtJoint.mjJNT_HINGE)
    out = {}
    for j in range(m.njnt):
        kind = int(m.jnt_type[j])
        if kind in (slide, hinge):
            a = m.jnt_qposadr[j]
            out[mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j)] = (
                "slide" if kind == slide else "hinge", float(d.qpos[a] - q0[a]))
    return out


def pybullet_rest(path: str | Path, seconds: float = 2.0, dt: float = 1 / 240) -> dict[str, tuple[str, float]]:
    """The same in PyBullet (DIRECT): fixed base, ``URDF_USE_SELF_COLLISION``, inertia from the file, the
    default joint motors off (free joints, as a user who wants the scene to move would load it)."""
    import pybullet as pb

    c = pb.connect(pb.DIRECT)
    try:
        pb.setGravity(*read_scene_floor(path).gravity(9.81).tolist(), physicsClientId=c)
        pb.setTimeStep(dt, physicsClientId=c)
        body = pb.loadURDF(str(path), useFixedBase=True, physicsClientId=c,
                           flags=pb.URDF_USE_SELF_COLLISION | pb.URDF_USE_INERTIA_FROM_FILE)
        joints = {}
        for j in range(pb.getNumJoints(body, physicsClientId=c)):
            info = pb.getJointInfo(body, j, physicsClientId=c)
            if info[2] in (pb.JOINT_REVOLUTE, pb.JOINT_PRISMATIC):
                pb.setJointMotorControl2(body, j, pb.VELOCITY_CONTROL, force=0, physicsClientId=c)
                joints[j] = (info[1].decode(), "slide" if info[2] == pb.JOINT_PRISMATIC else "hinge",
                             pb.getJointState(body, j, physicsClientId=c)[0])
        for _ in range(int(round(seconds / dt))):
            pb.stepSimulation(physicsClientId=c)
        return {name: (kind, pb.getJointState(body, j, physicsClientId=c)[0] - q0)
                for j, (name, kind, q0) in joints.items()}
    finally:
        pb.disconnect(c)


def drake_rest(path: str | Path, seconds: float = 2.0, dt: float = 0.001) -> dict[str, tuple[str, float]]:
    """The same in Drake: a discrete MultibodyPlant (``dt`` s steps) with its SceneGraph, the file parsed by
    ``Parser.AddModels`` (which raises on a file it cannot parse)."""
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.multibody.tree import PrismaticJoint
    from pydrake.systems.analysis import Simulator
    from pydrake.systems.framework import DiagramBuilder

    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, time_step=dt)
    Parser(plant).AddModels(str(path))
    floor = read_scene_floor(path)
    if not floor.level:
        plant.mutable_gravity_field().set_gravity_vector(floor.gravity(9.81))
    plant.Finalize()
    sim = Simulator(builder.Build())
    ctx = plant.GetMyContextFromRoot(sim.get_mutable_context())
    joints = [plant.get_joint(i) for i in plant.GetJointIndices() if plant.get_joint(i).num_positions() == 1]
    q0 = {j.name(): float(j.GetOnePosition(ctx)) for j in joints}
    sim.AdvanceTo(seconds)
    return {j.name(): ("slide" if isinstance(j, PrismaticJoint) else "hinge", float(j.GetOnePosition(ctx)) - q0[j.name()])
            for j in joints}


def rest_motion(path: str | Path, engine: str, seconds: float = 2.0) -> dict[str, tuple[str, float]]:
    """:func:`mujoco_rest`, :func:`pybullet_rest` or :func:`drake_rest` by ``engine`` name."""
    funcs = {"mujoco": mujoco_rest, "pybullet": pybullet_rest, "drake": drake_rest}
    if engine not in funcs:
        raise ValueError(f"unknown engine {engine!r}; expected one of {', '.join(ENGINES)}")
    return funcs[engine](path, seconds)


def moved_joints(motion: dict[str, tuple[str, float]], max_slide: float = 1e-3,
                 max_hinge: float = 0.01) -> dict[str, float]:
    """{joint: displacement} of the joints of ``motion`` that moved more than ``max_slide`` (m) /
    ``max_hinge`` (rad)."""
    return {n: v for n, (kind, v) in motion.items() if abs(v) > (max_slide if kind == "slide" else max_hinge)}


def link_overlaps(path: str | Path, tolerance: float = 5e-4) -> list[tuple[str, str, float]]:
    """[(link a, link b, depth m)] of the URDF's link pairs whose collision shapes (box, cylinder, sphere)
    interpenetrate deeper than ``tolerance`` at q = 0 (coal signed distance; meshes are not checked)."""
    import coal
    import yourdfpy

    u = yourdfpy.URDF.load(str(path), build_scene_graph=True, load_meshes=False, build_collision_scene_graph=False)
    shapes = {}
    for name, link in u.link_map.items():
        T_wl = u.get_transform(name, u.base_link)
        placed = []
        for c in link.collisions:
            g = c.geometry
            T = T_wl @ (c.origin if c.origin is not None else np.eye(4))
            if g.box is not None:
                s = coal.Box(*g.box.size)
            elif g.cylinder is not None:
                s = coal.Cylinder(g.cylinder.radius, g.cylinder.length)
            elif g.sphere is not None:
                s = coal.Sphere(g.sphere.radius)
            else:
                continue
            placed.append((s, coal.Transform3s(T[:3, :3].copy(), T[:3, 3].copy())))
        shapes[name] = placed
    out = []
    for a, b in itertools.combinations(shapes, 2):
        depth = 0.0
        for (sa, ta), (sb, tb) in itertools.product(shapes[a], shapes[b]):
            d = coal.distance(sa, ta, sb, tb, coal.DistanceRequest(), coal.DistanceResult())
            depth = max(depth, -d)
        if depth > tolerance:
            out.append((a, b, float(depth)))
    return out
