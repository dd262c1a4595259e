"""scenes.description: the one URDF reader/writer, the scene model's forward kinematics, the shape type."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from scenes.description import (DescriptionError, Dynamics, Inertial, InputError, Joint, JointType, Limit, Link,
                                Material, PartsceneError, SceneModel, Shape, ShapeKind, T_from_xyz_rpy,
                                T_inverse, read_urdf, urdf_text, write_urdf, xyz_rpy_from_T)


def _random_T(rng) -> np.ndarray:
    return T_from_xyz_rpy(rng.uniform(-0.5, 0.5, 3), rng.uniform(-np.pi, np.pi, 3))


def generated_model(seed: int, n_links: int = 8) -> SceneModel:
    """A random tree: every kind of joint, shape, material, inertial, limit and dynamics; odd links have
    PyBullet's ``<contact><lateral_friction>``."""
    rng = np.random.default_rng(seed)
    links = [Link("world")]
    joints = []
    types = [JointType.FIXED, JointType.PRISMATIC, JointType.REVOLUTE, JointType.CONTINUOUS]
    for i in range(1, n_links):
        shapes = [Shape.box(rng.uniform(0.05, 0.5, 3), _random_T(rng), name=f"l{i}_box"),
                  Shape.cylinder(rng.uniform(0.01, 0.1), rng.uniform(0.1, 0.4), _random_T(rng), name=f"l{i}_cyl"),
                  Shape.sphere(rng.uniform(0.01, 0.1), _random_T(rng), name=f"l{i}_sph")]
        mat = Material(f"m{i}", tuple(rng.uniform(0, 1, 4)))
        visuals = tuple(Shape(s.kind, s.size, s.T_link_shape, s.name + "_v", material=mat) for s in shapes)
        inertia = np.diag(rng.uniform(0.01, 0.1, 3))
        links.append(Link(f"link{i}", Inertial(float(rng.uniform(0.5, 5)), _random_T(rng), inertia), visuals,
                          tuple(shapes), lateral_friction=0.5 + 0.05 * i if i % 2 else None))
        jt = types[i % 4]
        lo = float(rng.uniform(-1, 0))
        joints.append(Joint(f"joint{i}", jt, links[int(rng.integers(0, i))].name, f"link{i}", _random_T(rng),
                            Rotation.random(random_state=seed * 100 + i).apply([0, 0, 1]),
                            Limit(lo, lo + float(rng.uniform(0.1, 2)), float(rng.uniform(1, 100)),
                                  float(rng.uniform(0.1, 3))) if jt is not JointType.FIXED else None,
                            Dynamics(float(rng.uniform(0, 2)), float(rng.uniform(0, 1)))))
    return SceneModel(f"generated{seed}", links, joints)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_write_then_read_gives_the_same_model(tmp_path, seed):
    model = generated_model(seed)
    back = read_urdf(write_urdf(model, tmp_path / "scene.urdf"))
    assert back.root == "world" and list(back.links) == list(model.links)
    assert back.isclose(model, atol=1e-9)
    j = back.joints["joint2"]
    assert j.limit == pytest.approx(model.joints["joint2"].limit) and j.dynamics is not None
    assert back.links["link1"].visuals[0].material.rgba == pytest.approx(model.links["link1"].visuals[0].material.rgba)
    assert back.links["link3"].inertial.isclose(model.links["link3"].inertial)
    assert [lk.lateral_friction for lk in back.links.values()] == [lk.lateral_friction for lk in model.links.values()]


def test_forward_kinematics_matches_pinocchio(tmp_path):
    pin = pytest.importorskip("pinocchio")
    model = generated_model(4, n_links=10)
    path = write_urdf(model, tmp_path / "scene.urdf")
    pm = pin.buildModelFromUrdf(str(path))
    data = pm.createData()
    rng = np.random.default_rng(5)
    for _ in range(5):
        q_by_name = {n: float(rng.uniform(j.lower, j.upper)) if np.isfinite(j.lower) else float(rng.uniform(-3, 3))
                     for n, j in model.joints.items() if j.movable}
        q = pin.neutral(pm)
        for n, v in q_by_name.items():
            jm = pm.joints[pm.getJointId(n)]
            if jm.nq == 2:                   # continuous: (cos, sin)
                q[jm.idx_q:jm.idx_q + 2] = np.cos(v), np.sin(v)
            else:
                q[jm.idx_q] = v
        pin.framesForwardKinematics(pm, data, q)
        for link in model.links:
            T_pin = data.oMf[pm.getFrameId(link)].homogeneous
            assert np.allclose(model.T_world_link(link, q_by_name), T_pin, atol=1e-10), link


def test_cylinder_size_is_diameter_diameter_length(tmp_path):
    c = Shape.cylinder(0.1, 0.5)
    assert c.kind is ShapeKind.CYLINDER and np.allclose(c.size, [0.2, 0.2, 0.5])
    assert c.radius == pytest.approx(0.1) and c.length == pytest.approx(0.5)
    assert c.volume == pytest.approx(np.pi * 0.01 * 0.5)
    m = 2.0       # closed forms: solid cylinder about its centre
    assert np.allclose(np.diag(c.inertia(m)), [m * (3 * 0.01 + 0.25) / 12, m * (3 * 0.01 + 0.25) / 12, m * 0.01 / 2])
    model = SceneModel("c", [Link("world", None, (c,), (c,))], [])
    text = urdf_text(model)
    assert 'radius="0.1"' in text and 'length="0.5"' in text
    path = tmp_path / "c.urdf"
    path.write_text(text)
    assert np.allclose(read_urdf(path).links["world"].collisions[0].size, [0.2, 0.2, 0.5])


def test_box_inertia_closed_form():
    b = Shape.box([0.3, 0.4, 0.5])
    m = 3.0
    assert np.allclose(np.diag(b.inertia(m)), m / 12 * np.array([0.16 + 0.25, 0.09 + 0.25, 0.09 + 0.16]))


def _chain(tmp_path, body: str):
    path = tmp_path / "bad.urdf"
    path.write_text(f'<?xml version="1.0"?><robot name="r"><link name="world"/><link name="a"/><link name="b"/>{body}</robot>')
    return path


def test_cycle_is_rejected_naming_the_links(tmp_path):
    path = _chain(tmp_path, '<joint name="ja" type="fixed"><parent link="b"/><child link="a"/></joint>'
                            '<joint name="jb" type="fixed"><parent link="a"/><child link="b"/></joint>')
    with pytest.raises(DescriptionError, match=r"bad.urdf: links \['a', 'b'\] are not below the root link 'world'"):
        read_urdf(path)


def test_a_link_cut_off_from_the_root_is_rejected(tmp_path):
    path = _chain(tmp_path, '<joint name="ja" type="fixed"><parent link="world"/><child link="a"/></joint>')
    with pytest.raises(DescriptionError, match=r"expected one root link, found \['world', 'b'\]"):
        read_urdf(path)


@pytest.mark.parametrize("joint, message", [
    ('<joint name="j" type="revolute"><parent link="world"/><child link="a"/><axis xyz="0 0 1"/></joint>',
     "revolute joint 'j' has no <limit>"),
    ('<joint name="j" type="prismatic"><parent link="world"/><child link="a"/><axis xyz="0 0 0"/>'
     '<limit lower="0" upper="1" effort="1" velocity="1"/></joint>', "joint 'j' has a zero axis"),
    ('<joint name="j" type="slider"><parent link="world"/><child link="a"/></joint>', "unknown type 'slider'"),
    ('<joint name="j" type="fixed"><parent link="world"/><child link="zz"/></joint>',
     "joint 'j' names child link 'zz', which does not exist"),
    ('<joint name="j" type="fixed"><parent link="world"/><child link="a"/><origin xyz="0 nan 0"/></joint>',
     "finite"),
])
def test_malformed_joints_are_named(tmp_path, joint, message):
    path = _chain(tmp_path, joint + '<joint name="jb" type="fixed"><parent link="world"/><child link="b"/></joint>')
    with pytest.raises(DescriptionError, match=message) as e:
        read_urdf(path)
    assert "bad.urdf" in str(e.value)


def test_relative_mesh_paths_are_resolved_against_the_file(tmp_path):
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "m.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    path = tmp_path / "m.urdf"
    path.write_text('<robot name="r"><link name="world"><visual><geometry><mesh filename="meshes/m.obj" '
                    'scale="2 2 2"/></geometry></visual></link></robot>')
    s = read_urdf(path).links["world"].visuals[0]
    assert s.kind is ShapeKind.MESH and s.mesh == str((tmp_path / "meshes" / "m.obj").resolve())
    assert np.allclose(s.size, 2.0)
    path.write_text(path.read_text().replace("meshes/m.obj", "meshes/gone.obj"))
    with pytest.raises(DescriptionError, match="mesh 'meshes/gone.obj' not found"):
        read_urdf(path)


def test_errors_share_one_base():
    from planners.errors import PlannerInputError
    from recon.errors import ScanError
    from scenes.errors import SceneSpecError
    from simcheck.errors import SimcheckInputError
    for cls in (PlannerInputError, ScanError, SceneSpecError, SimcheckInputError, DescriptionError):
        assert issubclass(cls, InputError) and issubclass(cls, PartsceneError) and issubclass(cls, ValueError)


def test_pose_helpers_round_trip():
    rng = np.random.default_rng(0)
    for _ in range(10):
        T = _random_T(rng)
        xyz, rpy = xyz_rpy_from_T(T)
        assert np.allclose(T_from_xyz_rpy(xyz, rpy), T, atol=1e-12)
        assert np.allclose(T_inverse(T) @ T, np.eye(4), atol=1e-12)


@pytest.mark.parametrize("T, message", [
    (np.eye(3), r"must be a \(4, 4\) pose, got shape \(3, 3\)"),
    (np.full((4, 4), np.nan), "non-finite"),
    (np.diag([1.0, 1.0, 2.0, 1.0]), "is not a rotation"),
    (np.diag([1.0, 1.0, -1.0, 1.0]), "is not a rotation"),      # a reflection: det -1
])
def test_checked_poses_name_what_is_wrong(T, message):
    from scenes.description import check_pose
    with pytest.raises(ValueError, match=message):
        check_pose(T, "T_world_part")


def test_reading_an_unchanged_file_again_gives_an_equal_independent_model(tmp_path):
    path = write_urdf(generated_model(5), tmp_path / "scene.urdf")
    first, again = read_urdf(path), read_urdf(path)
    assert again is not first and again.isclose(first, atol=0.0) and again.path == first.path
    again.joints["joint2"].T_parent_joint[0, 3] += 1.0                 # changing one copy leaves the others
    assert read_urdf(path).isclose(first, atol=0.0)
    write_urdf(generated_model(6), path)                                # a changed file is parsed anew
    assert read_urdf(path).isclose(generated_model(6), atol=1e-9)
