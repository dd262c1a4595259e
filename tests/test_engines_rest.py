"""The scene rests in every engine: a reconstructed kitchen's plain ``scene.urdf`` (clean and realistic
scan) and the truth's ``truth.urdf``, loaded as a user would (no robot, no collision filter of ours),
keep every movable joint still under 2 s of gravity in MuJoCo, in PyBullet with self-collision on and
in Drake (when installed); no two links overlap at q = 0; and the same input gives the same bytes.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from simcheck.rest import drake_rest, link_overlaps, moved_joints, mujoco_rest, pybullet_rest

REST_SECONDS = 2.0
MAX_SLIDE = 1e-3      # m a prismatic joint may move at rest
MAX_HINGE = 0.01      # rad a revolute joint may move at rest
MAX_OVERLAP = 5e-4    # m two links may interpenetrate at q = 0


PRESETS = ("clean", "realistic")
_KITCHENS: dict[str, dict] = {}


def _kitchen(preset: str, tmp_path_factory) -> dict:
    """{"scene.urdf", "scene.xml", "scene.srdf", "truth.urdf", "scan", "labels", "preset"} of kitchen seed 0
    reconstructed from a ``preset`` scan; built once per test process."""
    if preset not in _KITCHENS:
        import scenes
        from recon import reconstruct, write_reconstruction

        out = tmp_path_factory.mktemp(f"kitchen_{preset}")
        scenes.make_scene("kitchen", seed=0, preset=preset, out=out / "truth", previews=False)
        rec = reconstruct(out / "truth" / "scan.npz", out / "truth" / "labels.json", seed=0)
        paths = write_reconstruction(rec, out / "recon", mjcf=True)
        _KITCHENS[preset] = {"scene.urdf": paths["scene.urdf"], "scene.xml": paths["scene.xml"],
                             "scene.srdf": paths["scene.srdf"], "truth.urdf": out / "truth" / "truth.urdf",
                             "scan": out / "truth" / "scan.npz", "labels": out / "truth" / "labels.json",
                             "preset": preset}
    return _KITCHENS[preset]


@pytest.fixture(scope="module", params=PRESETS)
def kitchen(request, tmp_path_factory) -> dict:
    """The reconstructed kitchen of each scan preset."""
    return _kitchen(request.param, tmp_path_factory)


@pytest.fixture(scope="module", params=[f"{p} scene.urdf" for p in PRESETS] + ["truth.urdf"])
def urdf(request, tmp_path_factory) -> Path:
    """Each preset's reconstructed scene.urdf, and the truth.urdf (the same whatever the scan)."""
    preset, _, name = request.param.rpartition(" ")
    return _kitchen(preset or PRESETS[0], tmp_path_factory)[name]


def test_no_two_links_overlap_at_rest(urdf):
    """Signed distance (coal, an engine independent of recon's own test) between every pair of links."""
    overlaps = link_overlaps(urdf, MAX_OVERLAP)
    assert not overlaps, f"{urdf}: links overlapping at q = 0 (mm): {[(a, b, round(d * 1e3, 2)) for a, b, d in overlaps]}"


def _assert_still(moved: dict[str, tuple[str, float]], what: str):
    bad = {n: round(v, 5) for n, v in moved_joints(moved, MAX_SLIDE, MAX_HINGE).items()}
    assert not bad, f"{what}: joints moved at rest (m or rad): {bad}"


def test_rests_in_mujoco(urdf):
    pytest.importorskip("mujoco")
    moved = mujoco_rest(urdf)
    assert moved, f"{urdf}: MuJoCo found no movable joint"
    _assert_still(moved, f"MuJoCo, {urdf}")


def test_scene_xml_rests_in_mujoco(kitchen):
    pytest.importorskip("mujoco")
    moved = mujoco_rest(kitchen["scene.xml"])
    assert moved, f"{kitchen['scene.xml']}: MuJoCo found no movable joint"
    _assert_still(moved, f"MuJoCo, {kitchen['scene.xml']}")


def test_scene_xml_is_the_scene_urdf_in_mujoco(kitchen):
    """MuJoCo's own import of scene.urdf and our scene.xml agree: joint names and types, world axes and
    anchors at q = 0 and at mid-range, ranges, damping, friction loss, the mass that moves; collision geoms collide,
    visual geoms do not and carry their part label's colour."""
    mujoco = pytest.importorskip("mujoco")
    models = [mujoco.MjModel.from_xml_path(str(kitchen[k])) for k in ("scene.urdf", "scene.xml")]
    datas = [mujoco.MjData(m) for m in models]

    def joints(m, d):
        out = {}
        for j in range(m.njnt):
            dof = m.jnt_dofadr[j]
            out[mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j)] = dict(
                type=int(m.jnt_type[j]), range=m.jnt_range[j].copy(), damping=float(m.dof_damping[dof]),
                frictionloss=float(m.dof_frictionloss[dof]), armature=float(m.dof_armature[dof]),
                axis=d.xaxis[j].copy(), anchor=d.xanchor[j].copy())
        return out

    for fraction in (0.0, 0.5):
        for m, d in zip(models, datas):
            for j in range(m.njnt):
                d.qpos[m.jnt_qposadr[j]] = m.jnt_range[j][0] + fraction * (m.jnt_range[j][1] - m.jnt_range[j][0])
            mujoco.mj_forward(m, d)
        a, b = joints(models[0], datas[0]), joints(models[1], datas[1])
        assert set(a) == set(b) and a
        for name in a:
            for key in ("type", "damping", "frictionloss", "armature"):
                assert a[name][key] == pytest.approx(b[name][key], abs=1e-9), (name, key)
            for key in ("range", "axis", "anchor"):
                assert np.allclose(a[name][key], b[name][key], atol=1e-5), (name, key, a[name][key], b[name][key])
    moving_mass = [float(m.body_mass[m.body_weldid != 0].sum()) for m in models]   # the URDF import fuses static links
    assert moving_mass[0] > 0 and moving_mass[0] == pytest.approx(moving_mass[1], rel=1e-6)
    m = models[1]
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, g) for g in range(m.ngeom)]
    for g, name in enumerate(names):
        if "_collision" in name:
            assert m.geom_contype[g] == 1 and m.geom_conaffinity[g] == 1, name
        else:
            assert m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0, name
    from scenes.description import LABEL_RGBA

    door = next(g for g, n in enumerate(names) if "_door" in n and "_visual" in n)
    assert np.allclose(m.mat_rgba[m.geom_matid[door]], LABEL_RGBA["door"])


def test_scene_srdf_lists_the_pairs_in_contact_at_rest(kitchen):
    import xml.etree.ElementTree as ET

    import yourdfpy

    root = ET.parse(kitchen["scene.srdf"]).getroot()
    pairs = {(e.get("link1"), e.get("link2")): e.get("reason") for e in root.iter("disable_collisions")}
    u = yourdfpy.URDF.load(str(kitchen["scene.urdf"]), build_scene_graph=False, load_meshes=False)
    links = {link.name for link in u.robot.links}
    assert pairs and all(a in links and b in links and a < b for a, b in pairs)
    handles = [j for j in u.robot.joints if "handle" in j.child]
    assert all(pairs.get(tuple(sorted((j.parent, j.child)))) == "Adjacent" for j in handles)
    drawers = [j for j in u.robot.joints if j.type == "prismatic"]
    assert drawers and all(tuple(sorted((j.parent, j.child))) in pairs for j in drawers)


def test_simcheck_disables_no_collision_pair_of_our_files(urdf):
    """simcheck's overlap filter is for third-party files: on ours it disables nothing."""
    from simcheck.world import World

    with World(urdf) as world:
        assert world.disabled_overlaps == ()


def test_rests_in_pybullet_with_self_collision(urdf):
    moved = pybullet_rest(urdf)
    assert moved, f"{urdf}: PyBullet found no movable joint"
    _assert_still(moved, f"PyBullet, {urdf}")


def test_parses_and_rests_in_drake(urdf):
    pytest.importorskip("pydrake")
    moved = drake_rest(urdf)
    assert moved, f"{urdf}: Drake found no movable joint"
    _assert_still(moved, f"Drake, {urdf}")


def test_the_same_scan_gives_a_byte_identical_scene_urdf(tmp_path_factory, tmp_path):
    """``recon build`` in a fresh process writes exactly the bytes the in-process reconstruction wrote
    (on the clean scan: one scan is enough)."""
    kitchen = _kitchen("clean", tmp_path_factory)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(__file__).resolve().parents[1])]
                                                      + os.environ.get("PYTHONPATH", "").split(os.pathsep)))
    r = subprocess.run([sys.executable, "-m", "recon", "build", str(kitchen["scan"]), "--labels", str(kitchen["labels"]),
                        "--out", str(tmp_path), "--no-preview", "-q"], env=env, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "scene.urdf").read_bytes() == kitchen["scene.urdf"].read_bytes()


def test_scene_urdf_numbers_are_rounded_and_visuals_coloured_by_label(kitchen):
    import xml.etree.ElementTree as ET

    root = ET.parse(kitchen["scene.urdf"]).getroot()
    for el in root.iter("origin"):
        for v in (el.get("xyz") + " " + el.get("rpy")).split():
            assert len(v.split(".")[-1]) <= 6 if "." in v else True, f"{v} has more than 6 decimals"
    for el in root.iter("mass"):
        assert len(el.get("value").replace("-", "").replace(".", "").lstrip("0")) <= 9
    colours = {}
    for link in root.iter("link"):
        for vis in link.iter("visual"):
            mat = vis.find("material")
            assert mat is not None and mat.find("color") is not None, f"{link.get('name')}: a visual without a colour"
            colours.setdefault(mat.get("name"), set()).add(mat.find("color").get("rgba"))
    assert {"label_body", "label_door", "label_drawer", "label_handle"} <= set(colours)
    assert all(len(v) == 1 for v in colours.values())
