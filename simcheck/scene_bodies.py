"""A scene URDF cut into the bodies the PyBullet world loads (pure: no simulator).

Every link that no prismatic/revolute/continuous joint moves becomes its own single-link body (static:
Bullet never tests two static bodies against each other and never integrates them; its mesh collisions
are marked ``concave="yes"`` so PyBullet keeps them as triangle meshes, not convex hulls -- a hollow
carcass stays hollow, as coal sees it when planning). Every movable joint whose parent never moves
becomes a fixed-base body holding that joint and the whole subtree below it, rooted at an empty anchor
link (:data:`ANCHOR`) placed at the parent's world pose. One multibody of every link would cost a
Featherstone pass and a broad-phase update over all its links every step; this costs them only for the
links that can move. Link and joint names are kept; poses are of the closed state (every joint at 0).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from scenes.description import Inertial, Joint, Link, SceneModel, ShapeKind, urdf_text, urdf_xml, xml_text

__all__ = ["ANCHOR", "SceneBody", "scene_bodies"]

ANCHOR = "__partscene_anchor__"
"""Name of the empty root link of a split-off articulated subtree (fixed base: its mass never matters)."""


@dataclass(frozen=True)
class SceneBody:
    """One body of the split scene.

    name : the static link's name, or the name of the movable joint at the top of the subtree
    urdf : its URDF text (mesh paths absolute)
    T_world_root : (4, 4) float64, world pose of the body's root link frame, metres
    moving : True for an articulated subtree, False for a single never-moving link
    static_ancestors : the never-moving links above the subtree (it must not collide with them)
    """

    name: str
    urdf: str
    T_world_root: np.ndarray
    moving: bool
    static_ancestors: tuple[str, ...]


def _static_urdf(model: SceneModel, link: Link) -> str:
    el = urdf_xml(SceneModel(link.name, [link], [], model.materials))
    for col in el.iter("collision"):
        if col.find("geometry/mesh") is not None:
            col.set("concave", "yes")
    return xml_text(el)


def _subtree_urdf(model: SceneModel, top: Joint) -> str:
    anchor = Link(ANCHOR, Inertial(1.0, np.eye(4), np.eye(3)))
    joints, stack = [], [top]
    while stack:
        cur = stack.pop()
        joints.append(cur)
        stack.extend(reversed(model.child_joints(cur.child)))
    links = [anchor] + [model.links[j.child] for j in joints]
    joints[0] = Joint(top.name, top.type, ANCHOR, top.child, top.T_parent_joint, top.axis, top.limit, top.dynamics)
    return urdf_text(SceneModel(top.name, links, joints, model.materials))


MAX_PIECES = 64
"""A moving link's collision mesh of 2..MAX_PIECES connected pieces is split into them (see :func:`scene_bodies`)."""


def _pieces(link: Link, mesh_dir: Path, tag: str) -> Link:
    """``link`` with each collision mesh made of several connected pieces replaced by one mesh per piece,
    written to ``mesh_dir`` (OBJ, named from ``tag``); unreadable or single-piece meshes are kept."""
    import trimesh
    new = []
    for k, c in enumerate(link.collisions):
        if c.kind is ShapeKind.MESH:
            try:
                parts = trimesh.load(c.mesh, force="mesh").split(only_watertight=False)
            except Exception:
                parts = []
            if 1 < len(parts) <= MAX_PIECES:
                for i, part in enumerate(parts):
                    f = Path(mesh_dir) / f"{tag}_{k}_{i}.obj"
                    f.write_text(trimesh.exchange.obj.export_obj(part, include_normals=False, include_color=False,
                                                                 include_texture=False))
                    new.append(dataclasses.replace(c, mesh=str(f)))
                continue
        new.append(c)
    return dataclasses.replace(link, collisions=tuple(new))


def scene_bodies(model: SceneModel, mesh_dir=None) -> list[SceneBody]:
    """The bodies of ``model``: the static links in link order, then the articulated subtrees in joint order.

    With ``mesh_dir`` (a folder that lives while the bodies are loaded), each collision mesh of a moving
    link made of several connected pieces (a door exported as one mesh, its panel and its handle) is split
    into one mesh per piece there: Bullet collides a moving link's mesh as one convex hull, which would
    fill the space between a panel and its handle bar (the gripper could not close around the bar)."""
    if mesh_dir is not None:
        moving = [name for name in model.links if model.is_moving(name)]
        model = model.replaced(*(_pieces(model.links[name], mesh_dir, f"link{k}") for k, name in enumerate(moving)))
    bodies = [SceneBody(name, _static_urdf(model, link), model.T_world_link(name), False, ())
              for name, link in model.links.items() if not model.is_moving(name)]
    for j in model.joints.values():
        if j.movable and not model.is_moving(j.parent):
            bodies.append(SceneBody(j.name, _subtree_urdf(model, j), model.T_world_link(j.parent), True,
                                    tuple(model.ancestors(j.parent))))
    return bodies
