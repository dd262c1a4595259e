"""simcheck.scene_bodies: the pure URDF -> PyBullet bodies split, checked without PyBullet."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from scenes.description import read_urdf
from simcheck.scene_bodies import ANCHOR, scene_bodies

FIXTURE = Path(__file__).parents[1] / "planners" / "data" / "cabinet_fixture.urdf"


def _body_model(tmp_path, body):
    path = tmp_path / f"{body.name}.urdf"
    path.write_text(body.urdf)
    return read_urdf(path)


def test_every_link_is_in_one_body_at_its_scene_pose(tmp_path):
    scene = read_urdf(FIXTURE)
    bodies = scene_bodies(scene)
    moving = [b for b in bodies if b.moving]
    assert sorted(b.name for b in moving) == ["cabinet1_door14_joint", "cabinet1_drawer12_joint"]
    assert [b.name for b in bodies if not b.moving] == [ln for ln in scene.links if not scene.is_moving(ln)]
    seen = []
    rng = np.random.default_rng(0)
    q = {n: float(rng.uniform(j.lower, j.upper)) for n, j in scene.joints.items() if j.movable}
    for b in bodies:
        m = _body_model(tmp_path, b)
        links = [ln for ln in m.links if ln != ANCHOR]
        seen += links
        for ln in links:
            T = b.T_world_root @ m.T_world_link(ln, q)
            assert np.allclose(T, scene.T_world_link(ln, q), atol=1e-9), ln
        if b.moving:
            assert m.root == ANCHOR and set(b.static_ancestors) >= {"world", "cabinet1_body10"}
            top = m.joints[b.name]
            assert top.limit == scene.joints[b.name].limit and top.dynamics == scene.joints[b.name].dynamics
    assert sorted(seen) == sorted(scene.links)


def test_static_meshes_collide_as_triangles(tmp_path):
    (tmp_path / "m.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    path = tmp_path / "s.urdf"
    path.write_text('<robot name="r"><link name="world"><collision><geometry><mesh filename="m.obj"/></geometry>'
                    '</collision></link></robot>')
    (body,) = scene_bodies(read_urdf(path))
    assert 'concave="yes"' in body.urdf and str((tmp_path / "m.obj").resolve()) in body.urdf


def test_a_moving_mesh_of_several_pieces_is_split_into_them(tmp_path):
    """A front exported as one mesh (panel + U handle: 4 pieces) becomes 4 collision meshes (Bullet would
    collide the one mesh as its convex hull, filling the space behind the bar); the static carcass is kept."""
    import thirdparty
    o = thirdparty.build_object(thirdparty.spec_named("one_mesh_fronts"), tmp_path / "obj")
    (tmp_path / "pieces").mkdir()
    bodies = {b.name: b for b in scene_bodies(read_urdf(o.urdf), mesh_dir=tmp_path / "pieces")}
    door = o.fronts[1]
    model = _body_model(tmp_path, bodies[door.joint])
    cols = model.links[door.moving_link].collisions
    assert len(cols) == 4 and all(c.kind.value == "mesh" and Path(c.mesh).parent == tmp_path / "pieces" for c in cols)
    kept = {b.name: b for b in scene_bodies(read_urdf(o.urdf))}       # without a folder: unchanged
    assert len(_body_model(tmp_path, kept[door.joint]).links[door.moving_link].collisions) == 1
