"""A URDF somebody else wrote with meshes, PartNet-Mobility style: one concave carcass mesh, one concave
drawer mesh, a bar-on-posts handle mesh, relative mesh paths, links without inertials. It is certified;
the same URDF with a wrong axis is rejected against it; a missing mesh is an input error naming it; and
PyBullet's C-level warnings about it never reach the terminal."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

import simcheck
import simcheck.estimate_faults as wrong
from scenes.outcome import Outcome
from simcheck.cli import main

W, D, H, T = 0.6, 0.5, 0.8, 0.018   # carcass width (y), depth (x), height, panel thickness (m)
DRAWER = (D - T - 0.01, W - 2 * T - 0.006, 0.25)   # drawer box depth, width, height


def _meshes() -> dict[str, trimesh.Trimesh]:
    outer = trimesh.creation.box(extents=[D, W, H])
    inner = trimesh.creation.box(extents=[D, W - 2 * T, H - 2 * T])
    inner.apply_translation([T, 0, 0])                          # open towards +x
    dd, dw, dh = DRAWER
    box = trimesh.creation.box(extents=[dd, dw, dh]).difference(
        trimesh.creation.box(extents=[dd - 0.02, dw - 0.02, dh]).apply_translation([0, 0, 0.01]))
    front = trimesh.creation.box(extents=[T, W - 0.004, dh + 0.02]).apply_translation([dd / 2 + T / 2, 0, 0])
    along_x = trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0])
    posts = [trimesh.creation.cylinder(radius=0.006, height=0.035, sections=12, transform=along_x)
             .apply_translation([0.0175, y, 0]) for y in (-0.085, 0.085)]
    bar = trimesh.creation.box(extents=[0.014, 0.2, 0.014]).apply_translation([0.042, 0, 0])
    return {"carcass": outer.difference(inner), "drawer": trimesh.util.concatenate([box, front]),
            "handle": trimesh.util.concatenate([bar] + posts)}


def _link(name: str, inertial: bool = True) -> str:
    mesh = f'<geometry><mesh filename="meshes/{name}.obj"/></geometry>'
    inertia = ('<inertial><mass value="1"/><inertia ixx="0.05" iyy="0.05" izz="0.05" ixy="0" ixz="0" iyz="0"/>'
               "</inertial>") if inertial else ""
    return f'<link name="{name}">{inertia}<visual>{mesh}</visual><collision>{mesh}</collision></link>'


@pytest.fixture(scope="module")
def mesh_cabinet(tmp_path_factory):
    d = tmp_path_factory.mktemp("mesh_cabinet")
    (d / "meshes").mkdir()
    for name, mesh in _meshes().items():
        mesh.export(d / "meshes" / f"{name}.obj")
    dd, _, dh = DRAWER
    urdf = (f'<robot name="their_cabinet"><link name="base"/>{_link("carcass")}{_link("drawer")}'
            f'{_link("handle", inertial=False)}'
            f'<joint name="base_fixed" type="fixed"><parent link="base"/><child link="carcass"/>'
            f'<origin xyz="0 0 {H / 2}"/></joint>'
            f'<joint name="Drawer Slide" type="prismatic"><parent link="carcass"/><child link="drawer"/>'
            f'<origin xyz="{D / 2 - dd / 2 - T:.4f} 0 {H / 2 - T - dh / 2 - 0.03:.4f}"/><axis xyz="1 0 0"/>'
            f'<limit lower="0" upper="0.4" effort="100" velocity="1"/></joint>'
            f'<joint name="handle_fixed" type="fixed"><parent link="drawer"/><child link="handle"/>'
            f'<origin xyz="{dd / 2 + T:.4f} 0 0"/></joint></robot>')
    (d / "cabinet.urdf").write_text(urdf)
    return d / "cabinet.urdf"


def test_a_mesh_cabinet_is_certified_and_pybullet_says_nothing_on_the_terminal(mesh_cabinet, capfd):
    cert = simcheck.certify(mesh_cabinet, ["open-drawer:Drawer Slide"], images=False)
    out, err = capfd.readouterr()
    t = cert["Drawer Slide"]
    assert t.ok, t.reason
    assert t.criterion("opened_fraction").value > 0.95 and t.criterion("grasp_held").passed
    assert "b3Warning" not in out + err and "inertial" not in out + err


def test_a_wrong_axis_estimate_of_the_mesh_cabinet_fails_against_it(mesh_cabinet, tmp_path):
    est = wrong.rotate_axis(mesh_cabinet, "Drawer Slide", 30.0, mesh_cabinet.parent / "axis30.urdf")
    t = simcheck.certify(est, ["open-drawer:Drawer Slide"], against=mesh_cabinet, images=False).tasks[0]
    assert t.status is Outcome.FAILED, t.reason
    assert "deg off the reference axis" in t.reason


def test_a_missing_mesh_exits_2_naming_the_link_and_the_file(mesh_cabinet, tmp_path, capsys):
    broken = mesh_cabinet.parent / "missing_mesh.urdf"
    broken.write_text(mesh_cabinet.read_text().replace("meshes/handle.obj", "meshes/handel.obj"))
    assert main(["certify", str(broken), "--task", "open-drawer:Drawer Slide", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "link 'handle' mesh 'meshes/handel.obj' not found" in err and "missing_mesh.urdf" in err


def test_a_static_mesh_stays_hollow_in_physics(mesh_cabinet):
    """The carcass is one concave mesh: a ball inside its cavity must not be inside the carcass (PyBullet
    would otherwise use the mesh's convex hull, a solid block)."""
    import pybullet as pb

    from simcheck.world import World

    with World(mesh_cabinet) as world:
        body, index = world._scene_link_index("carcass")     # white box: the PyBullet body of the link
        ball = pb.createMultiBody(0.1, pb.createCollisionShape(pb.GEOM_SPHERE, radius=0.03, physicsClientId=world.client),
                                  basePosition=[0.0, 0.0, 0.2], physicsClientId=world.client)
        closest = pb.getClosestPoints(body, ball, 0.5, linkIndexA=index, physicsClientId=world.client)
        assert closest and min(c[8] for c in closest) > 0.1     # ~ the drawer box's free space, not -0.2
