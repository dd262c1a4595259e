"""A scene loaded again in the same process is not split into bodies again nor loaded whole again for its joint
table (a batch certifies many tasks of one scene in one worker), and loads the same; a changed file is split and
loaded anew; a file PyBullet cannot load fails every time."""

import shutil

import pybullet as pb
import pytest

import simcheck.scene_loading as scene_loading
from simcheck.config import DEFAULT_PHYSICS
from simcheck.errors import SceneLoadError
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
    splits, whole = [], []
    real, real_load = scene_loading.scene_bodies, scene_loading.pb.loadURDF
    monkeypatch.setattr(scene_loading, "scene_bodies", lambda *a, **k: splits.append(1) or real(*a, **k))
    monkeypatch.setattr(scene_loading.pb, "loadURDF",
                        lambda path, *a, **k: (path == str(urdf) and whole.append(1)) or real_load(path, *a, **k))
    first = _loaded(urdf)
    assert _loaded(urdf) == first and len(splits) == 1 and len(whole) == 1
    urdf.write_text(urdf.read_text().replace("<robot ", "<!-- changed -->\n<robot ", 1))
    assert _loaded(urdf) == first and len(splits) == 2 and len(whole) == 2


def test_a_scene_pybullet_cannot_load_fails_every_time(tmp_path):
    urdf = tmp_path / "broken.urdf"
    urdf.write_text('<robot name="b"><link name="world"/><joint name="j" type="fixed"><parent link="world"/>'
                    '<child link="missing"/></joint></robot>')
    for _ in range(2):
        with pytest.raises(SceneLoadError, match="PyBullet cannot load scene URDF .*broken.urdf"):
            _loaded(urdf)
