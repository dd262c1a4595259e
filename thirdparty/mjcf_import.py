"""An articulated object given as MJCF (MuJoCo's format: Franka Kitchen, LIBERO, robosuite assets) as a URDF
that partscene certifies, read from MuJoCo's own compiled model (``mujoco.MjModel``), not from the XML.

What is read, at the model's reference configuration (``qpos0``): body poses; each hinge / slide joint
(anchor, axis, range, damping, frictionloss; a joint's value is counted from its ``ref``, so the file's
rest state is 0); every geom with its pose, its kind (box, cylinder, sphere; a capsule as a cylinder and
two spheres; an ellipsoid or mesh as a triangle mesh, written as OBJ with trimesh) and whether it collides
(``contype`` or ``conaffinity`` non-zero: a URDF collision; the others are visuals); each body's mass and
inertia as MuJoCo computed them.

What is made of it: one link per moving part (a body with a joint, with every jointless body below it
merged in) and one ``body`` link holding everything that does not move; the object turned about the
vertical so that its front (the side its moving parts stand out of) faces -x, i.e. the robot standing at
the origin; its lowest collision point at ``elevation`` (m) and its front plane at ``x = front_x``,
centred on y = 0; optionally on a counter (a box under it, its own link ``counter`` fixed to ``body``, its
front edge ``COUNTER_LIP`` m ahead of the object); optionally scaled (``scale``: lengths, masses x scale^3, inertias
x scale^5; joint damping and friction as given) -- for assets modelled at tabletop size.

Repairs, each recorded in :attr:`ImportedObject.repairs`: textures are dropped (not needed, and assets
reference texture files they do not ship); elements MuJoCo's schema does not know (robosuite's ``<region>``)
are left out; an asset whose moving bodies get no mass because its compiler
takes inertia from another geom group than its collision geoms (LIBERO's templates; robosuite computes
them in its merged scene) is compiled with inertia from the collision geoms' groups.

Refused (:class:`MjcfImportError`, naming the file and the body or joint): ball and free joints, a body
with more than one joint, a file MuJoCo cannot compile.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from scenes.description import (Dynamics, Inertial, InputError, Joint, JointType, Limit, Link, SceneModel, Shape,
                                ShapeKind, write_urdf)

__all__ = ["MjcfImportError", "ImportedObject", "load_mjcf", "import_mjcf", "COUNTER_HEIGHT", "COUNTER_LIP"]

COUNTER_HEIGHT = 0.9     # m, a kitchen counter's top
COUNTER_LIP = 0.05       # m, how far the counter's front edge stands ahead of an object on it
COUNTER_DEPTH = 0.62     # m, at least; deeper when the object is deeper
MIN_MASS = 1e-3          # kg, a moving part with less (a visual-only body) gets this, as a 1 cm cube


class MjcfImportError(InputError):
    """An MJCF file the importer cannot turn into a URDF (the message names the file and the element)."""


@dataclass
class ImportedObject:
    """The written URDF and what it holds.

    Attributes:
        urdf: path of the URDF.
        body_link: the link that does not move (the carcass).
        joints: {URDF joint name: (kind "drawer" | "door", moving link)} of every hinge / slide joint.
        size: (3,) extents (m) of the object's collision geometry as placed (x depth, y width, z height).
        scale: the scale applied.
        repairs: what had to be changed to compile the file (empty when it compiled as given).
        counter_link: the counter's link (fixed to ``body_link``), or None.
    """

    urdf: Path
    body_link: str
    joints: dict
    size: np.ndarray
    scale: float = 1.0
    repairs: list = field(default_factory=list)
    counter_link: str | None = None


def _mujoco():
    import mujoco
    return mujoco


def load_mjcf(path) -> tuple[object, list]:
    """(the compiled ``mujoco.MjModel``, the repairs made) of the MJCF file ``path``."""
    mujoco = _mujoco()
    path = Path(path)
    repairs: list = []

    dropped: list = []

    def spec_of():
        try:
            spec = _spec_without(mujoco, path, dropped)
        except Exception as e:           # mujoco raises ValueError for XML errors
            raise MjcfImportError(f"{path}: MuJoCo cannot read the file: {str(e).strip()}") from e
        for t in list(spec.textures):    # textures only colour the visuals
            spec.delete(t)
        for mat in spec.materials:
            mat.textures = [""] * len(mat.textures)
        return spec

    spec = spec_of()
    if dropped:
        repairs.append(f"elements MuJoCo does not know left out (a simulator's own extensions): {dropped}")
    try:
        return spec.compile(), repairs
    except Exception as e:
        msg = str(e).strip()
    if "mass and inertia" in msg:
        spec = spec_of()
        groups = sorted({int(g.group) for g in spec.geoms if g.contype or g.conaffinity})
        if groups:
            spec.compiler.inertiagrouprange = [groups[0], groups[-1]]
            repairs.append(f"inertia from the collision geoms (groups {groups[0]}-{groups[-1]}): {msg.splitlines()[0]}")
            try:
                return spec.compile(), repairs
            except Exception as e2:
                msg = str(e2).strip()
    raise MjcfImportError(f"{path}: MuJoCo cannot compile the file: {msg}")


def _spec_without(mujoco, path: Path, dropped: list):
    """``mujoco.MjSpec`` of ``path``; when MuJoCo's schema refuses an element it does not know (robosuite's
    ``<region>``), that element is left out (its tag appended to ``dropped``) and the file read again, with its
    mesh and texture folders made absolute so that its relative file names still resolve."""
    import re
    from xml.etree import ElementTree as ET
    try:
        return mujoco.MjSpec.from_file(str(path))
    except ValueError as e:
        found = re.search(r"unrecognized element\s+Element '([^']+)'", str(e))
        if not found:
            raise
    tree = ET.parse(path)
    root = tree.getroot()
    while found:
        tag = found.group(1)
        dropped.append(tag)
        for parent in list(root.iter()):
            for el in [c for c in parent if c.tag == tag]:
                parent.remove(el)
        compiler = root.find("compiler")
        if compiler is None:
            compiler = ET.SubElement(root, "compiler")
        for key in ("meshdir", "texturedir"):
            compiler.set(key, str((path.parent / compiler.get(key, ".")).resolve()) + "/")
        try:
            return mujoco.MjSpec.from_string(ET.tostring(root, encoding="unicode"))
        except ValueError as e:
            found = re.search(r"unrecognized element\s+Element '([^']+)'", str(e))
            if not found or found.group(1) in dropped:
                raise


def _T(R=None, p=None) -> np.ndarray:
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    if p is not None:
        T[:3, 3] = p
    return T


def _quat_R(q) -> np.ndarray:
    from scipy.spatial.transform import Rotation
    w, x, y, z = q
    return Rotation.from_quat([x, y, z, w]).as_matrix()


def _geom_shapes(m, g: int, T_link_geom: np.ndarray, scale: float, mesh_file) -> list[Shape]:
    """The shapes of geom ``g`` at ``T_link_geom`` (already scaled); ``mesh_file(vertices, faces, tag)`` writes
    a mesh and returns its file name."""
    mujoco = _mujoco()
    t, size = int(m.geom_type[g]), np.asarray(m.geom_size[g], float) * scale
    G = {k: int(getattr(mujoco.mjtGeom, k)) for k in ("mjGEOM_BOX", "mjGEOM_CYLINDER", "mjGEOM_SPHERE",
                                                    "mjGEOM_CAPSULE", "mjGEOM_ELLIPSOID", "mjGEOM_MESH")}
    if t == G["mjGEOM_BOX"]:
        return [Shape.box(2 * size, T_link_geom)]
    if t == G["mjGEOM_CYLINDER"]:
        return [Shape.cylinder(size[0], 2 * size[1], T_link_geom)]
    if t == G["mjGEOM_SPHERE"]:
        return [Shape.sphere(size[0], T_link_geom)]
    if t == G["mjGEOM_CAPSULE"]:
        ends = [T_link_geom @ _T(p=[0, 0, s * size[1]]) for s in (-1, 1)]
        return [Shape.cylinder(size[0], 2 * size[1], T_link_geom)] + [Shape.sphere(size[0], T) for T in ends]
    if t == G["mjGEOM_ELLIPSOID"]:
        import trimesh
        sph = trimesh.creation.icosphere(subdivisions=2)
        return [Shape(ShapeKind.MESH, np.ones(3), T_link_geom,
                      mesh=mesh_file(sph.vertices * size, sph.faces, f"geom{g}"))]
    if t == G["mjGEOM_MESH"]:
        k = int(m.geom_dataid[g])
        v0, nv = int(m.mesh_vertadr[k]), int(m.mesh_vertnum[k])
        f0, nf = int(m.mesh_faceadr[k]), int(m.mesh_facenum[k])
        verts = np.asarray(m.mesh_vert[v0:v0 + nv], float) * scale
        faces = np.asarray(m.mesh_face[f0:f0 + nf], int)
        name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_MESH, k) or f"mesh{k}"
        return [Shape(ShapeKind.MESH, np.ones(3), T_link_geom, mesh=mesh_file(verts, faces, name))]
    return []          # plane, height field, SDF: not part of a piece of furniture


def _merge_inertials(parts: list) -> Inertial | None:
    """One inertial (link frame) from ``(mass, com (3,), inertia (3, 3) about com)`` items in the same frame."""
    parts = [p for p in parts if p[0] > 0]
    if not parts:
        return None
    mass = float(sum(p[0] for p in parts))
    com = sum(p[0] * p[1] for p in parts) / mass
    inertia = np.zeros((3, 3))
    for mk, ck, Ik in parts:
        d = ck - com
        inertia += Ik + mk * (float(d @ d) * np.eye(3) - np.outer(d, d))
    return Inertial(mass, _T(p=com), inertia)


def import_mjcf(xml, out, name: str, *, elevation: float = 0.0, counter: bool = False, scale: float = 1.0,
                front_x: float = 1.2, visuals: bool = True) -> ImportedObject:
    """Write the MJCF object ``xml`` as ``out/<name>.urdf`` (meshes in ``out/meshes``), placed for a robot
    standing at the origin (module docstring). ``elevation``: height (m) of the object's lowest collision
    point; with ``counter`` it stands on a counter of that height (default ``COUNTER_HEIGHT`` when
    ``elevation`` is 0). ``visuals`` False writes no visual geometry (smaller files; the collisions are
    what partscene uses). ``scale`` > 0 (module docstring). Deterministic."""
    if not (np.isfinite(scale) and scale > 0):
        raise MjcfImportError(f"{xml}: scale {scale!r} is not a positive number (1.0 keeps the file's size)")
    mujoco = _mujoco()
    m, repairs = load_mjcf(xml)
    d = mujoco.MjData(m)
    mujoco.mj_kinematics(m, d)          # qpos = qpos0: every joint at its ref, the file's rest state
    mujoco.mj_comPos(m, d)
    out = Path(out)
    where = f"{xml}"
    if counter and elevation <= 0:
        elevation = COUNTER_HEIGHT

    def body_name(b):
        return mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, b) or f"body{b}"

    # which link each body belongs to: the nearest body at or above it that has a joint, else the fixed body
    owner = {0: None}
    for b in range(1, m.nbody):
        nj = int(m.body_jntnum[b])
        if nj > 1:
            raise MjcfImportError(f"{where}: body {body_name(b)!r} has {nj} joints (one hinge or slide per part)")
        if nj == 1:
            j = int(m.body_jntadr[b])
            if int(m.jnt_type[j]) not in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)):
                kind = "free" if int(m.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_FREE) else "ball"
                raise MjcfImportError(f"{where}: body {body_name(b)!r} has a {kind} joint "
                                      f"{mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j)!r}: not a drawer "
                                      f"or door (import the articulated object alone)")
            owner[b] = b
        else:
            owner[b] = owner[int(m.body_parentid[b])]

    # world poses at rest: bodies; a moving link's frame is its joint's frame (the body frame at the anchor)
    T_w_body = {b: _T(np.asarray(d.xmat[b]).reshape(3, 3), d.xpos[b]) for b in range(m.nbody)}

    def T_w_link(b):            # b: the owner body (None: the fixed body, the world frame)
        if b is None:
            return np.eye(4)
        j = int(m.body_jntadr[b])
        return T_w_body[b] @ _T(p=m.jnt_pos[j])

    # the placement: front direction from the moving parts standing out of the fixed geometry
    def geom_box(g):
        R = np.asarray(d.geom_xmat[g]).reshape(3, 3)
        c, h = R @ m.geom_aabb[g][:3] + d.geom_xpos[g], np.abs(R) @ m.geom_aabb[g][3:]
        return c - h, c + h

    colliding = [g for g in range(m.ngeom) if m.geom_contype[g] or m.geom_conaffinity[g]]
    if not colliding:
        raise MjcfImportError(f"{where}: no geom collides (contype / conaffinity all 0): nothing to certify")
    fixed = [geom_box(g) for g in colliding if owner[int(m.geom_bodyid[g])] is None]
    moving = [geom_box(g) for g in colliding if owner[int(m.geom_bodyid[g])] is not None]
    lo = np.min([b[0] for b in fixed + moving], axis=0)
    hi = np.max([b[1] for b in fixed + moving], axis=0)
    yaw = 0.0
    if fixed and moving:
        flo, fhi = np.min([b[0] for b in fixed], axis=0), np.max([b[1] for b in fixed], axis=0)
        mlo, mhi = np.min([b[0] for b in moving], axis=0), np.max([b[1] for b in moving], axis=0)
        out_by = {0.0: mhi[0] - fhi[0], np.pi: flo[0] - mlo[0], np.pi / 2: mhi[1] - fhi[1], -np.pi / 2: flo[1] - mlo[1]}
        front = max(out_by, key=lambda k: (round(out_by[k], 4), -abs(k)))   # the side a +yaw turn points at -x
        yaw = np.pi - front     # turn that side onto -x
    from scipy.spatial.transform import Rotation
    Rz = Rotation.from_euler("z", yaw).as_matrix()
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]) @ Rz.T
    clo, chi = corners.min(0) * scale, corners.max(0) * scale
    offset = np.array([front_x - clo[0], -(clo[1] + chi[1]) / 2, elevation - clo[2]])

    def placed(T):              # a world pose of the file -> the placed, scaled pose
        T = T.copy()
        T[:3, 3] *= scale
        return _T(Rz, offset) @ T

    mesh_dir = out / "meshes"
    written: dict = {}

    def mesh_file(verts, faces, tag):
        import trimesh
        mesh_dir.mkdir(parents=True, exist_ok=True)
        fname, k = f"{tag}.obj", 1
        while fname in written:
            k += 1
            fname = f"{tag}_{k}.obj"
        written[fname] = True
        text = trimesh.exchange.obj.export_obj(trimesh.Trimesh(verts, faces, process=False), include_normals=False,
                                               include_color=False, include_texture=False)
        (mesh_dir / fname).write_text(text)
        return f"meshes/{fname}"

    body_link = "body"
    link_name = {None: body_link}
    used = {body_link}
    for b in range(1, m.nbody):
        if owner[b] == b:
            n = body_name(b).replace(" ", "_")
            while n in used:
                n += "_"
            used.add(n)
            link_name[b] = n
    shapes = {k: ([], []) for k in link_name}         # owner -> (visuals, collisions)
    masses = {k: [] for k in link_name}
    T_placed_link = {k: placed(T_w_link(k)) if k is not None else np.eye(4) for k in link_name}   # body: world
    for g in range(m.ngeom):
        b = int(m.geom_bodyid[g])
        k = owner[b]
        T_w_geom = _T(np.asarray(d.geom_xmat[g]).reshape(3, 3), d.geom_xpos[g])
        T_link_geom = np.linalg.solve(T_placed_link[k], placed(T_w_geom))
        is_col = bool(m.geom_contype[g] or m.geom_conaffinity[g])
        if not is_col and not visuals:
            continue
        for s in _geom_shapes(m, g, T_link_geom, scale, mesh_file):
            shapes[k][1 if is_col else 0].append(s)
    for b in range(1, m.nbody):
        k = owner[b]
        mass = float(m.body_mass[b]) * scale ** 3
        if mass <= 0:
            continue
        T_w_i = _T(np.asarray(d.ximat[b]).reshape(3, 3), d.xipos[b])
        T_li = np.linalg.solve(T_placed_link[k], placed(T_w_i))
        I = T_li[:3, :3] @ np.diag(m.body_inertia[b] * scale ** 5) @ T_li[:3, :3].T
        masses[k].append((mass, T_li[:3, 3], I))
    links, joints, kinds = [], [], {}
    counter_link = None
    if counter:
        depth = max(COUNTER_DEPTH, chi[0] - clo[0] + COUNTER_LIP + 0.02)
        width = chi[1] - clo[1] + 0.2
        c = np.array([front_x - COUNTER_LIP + depth / 2, 0.0, elevation / 2])
        box = Shape.box([depth, width, elevation], _T(p=c))
        counter_link = "counter"
        while counter_link in used:
            counter_link += "_"
        links.append(Link(counter_link, None, (box,) if visuals else (), (box,)))
        joints.append(Joint(f"{counter_link}_fixed", JointType.FIXED, body_link, counter_link))
    for k, ln in link_name.items():
        inertial = _merge_inertials(masses[k])
        if k is not None and (inertial is None or inertial.mass < MIN_MASS):
            repairs.append(f"moving part {ln!r} has no mass: given {MIN_MASS} kg")
            inertial = Inertial(MIN_MASS, _T(), np.eye(3) * MIN_MASS * 0.01 ** 2 / 6)
        vis, col = shapes[k]
        links.append(Link(ln, inertial if k is not None else None, tuple(vis), tuple(col)))
    for b, ln in link_name.items():
        if b is None:
            continue
        j = int(m.body_jntadr[b])
        jname = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
        parent = owner[int(m.body_parentid[b])]
        T_parent_joint = np.linalg.solve(T_placed_link[parent], T_placed_link[b])
        slide = int(m.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_SLIDE)
        dof = int(m.jnt_dofadr[j])
        ref = float(m.qpos0[m.jnt_qposadr[j]])
        lim = m.jnt_range[j] * (scale if slide else 1.0) - ref * (scale if slide else 1.0)
        limited = bool(m.jnt_limited[j])
        effort = 100.0
        typ = JointType.PRISMATIC if slide else (JointType.REVOLUTE if limited else JointType.CONTINUOUS)
        if slide and not limited:
            raise MjcfImportError(f"{where}: slide joint {jname!r} has no range (a drawer needs one)")
        joints.append(Joint(jname, typ, link_name[parent], ln, T_parent_joint, np.asarray(m.jnt_axis[j], float),
                            Limit(float(lim[0]), float(lim[1]), effort, 1.0) if limited else Limit(0, 0, effort, 1.0),
                            Dynamics(float(m.dof_damping[dof]), float(m.dof_frictionloss[dof]))))
        kinds[jname] = ("drawer" if slide else "door", ln)
    model = SceneModel(name, links, joints)
    urdf = write_urdf(model, out / f"{name}.urdf")
    return ImportedObject(urdf, body_link, kinds, chi - clo, scale, repairs, counter_link)
