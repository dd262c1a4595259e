"""A scene loaded again in the same process is not split into bodies again (a batch certifies many tasks of
one scene in one worker), and loads the same; a changed file is split anew."""

import shutil

import pybullet as pb

import simcheck.scene_loading as scene_loading
from simcheck.config import DEFAULT_PHYSICS
from simcheck.scene_loading import load_scene

from simcheck_fixture_plans import CABINET


def _loaded(urdf):
    c = pb.connect(pb.DIRECT)
    try:
        s = load_scene(c, urdf, DEFAULT_PHYSICS, visuals=False)
        return s.link_at, {k: v.tolist() for k, v in s.static_pose.items()}, s.joints, s.rest_contacts
    finally:
        pb.disconnect(c)


def test_kept_bodies_load_the_same_and_a_changed_file_is_split_anew(tmp_path, monkeypatch):
    urdf = tmp_path / "cabinet.urdf"
    shutil.copy(CABINET, urdf)
    for mesh in CABINET.parent.iterdir():            # meshes the URDF names relatively
        if mesh.suffix in (".obj", ".stl", ".dae") and not (tmp_path / mesh.name).exists():
            shutil.copy(mesh, tmp_path / mesh.name)
    splits = []
    real = scene_loading.scene_bodies
    monkeypatch.setattr(scene_loading, "scene_bodies", lambda *a, **k: splits.append(1) or real(*a, **k))
    first = _loaded(urdf)
    assert _loaded(urdf) == first and len(splits) == 1
    urdf.write_text(urdf.read_text().replace("<robot ", "<!-- changed -->\n<robot ", 1))
    assert _loaded(urdf) == first and len(splits) == 2
