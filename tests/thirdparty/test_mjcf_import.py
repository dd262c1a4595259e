"""Third-party MJCF objects (Franka Kitchen's hinge cabinet, LIBERO's microwave: unchanged sources in
tests/thirdparty/data/mjcf) imported from MuJoCo's compiled model: every collision geom moves in the URDF as
MuJoCo moves it, the joints keep their ranges, damping and friction, the object faces the robot, and the doors
are certified on their own URDF. Bad files are refused by name, repairable ones repaired and said."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from scenes.description import read_urdf
from thirdparty.mjcf_assets import asset_named, build_mjcf_object
from thirdparty.mjcf_import import COUNTER_HEIGHT, MjcfImportError, import_mjcf

mujoco = pytest.importorskip("mujoco")
DATA = Path(__file__).parent / "data" / "mjcf"


def _mujoco_centres(xml: Path, q: dict) -> np.ndarray:
    """(n, 3) world centres of the colliding geoms of ``xml`` at joint values ``q`` (the file's frame)."""
    from thirdparty.mjcf_import import load_mjcf
    m, _ = load_mjcf(xml)
    d = mujoco.MjData(m)
    for name, v in q.items():
        d.qpos[m.jnt_qposadr[m.joint(name).id]] = v
    mujoco.mj_kinematics(m, d)
    return np.array([d.geom_xpos[g] for g in range(m.ngeom) if m.geom_contype[g] or m.geom_conaffinity[g]])


def _urdf_centres(urdf: Path, q: dict, skip: tuple = ()) -> np.ndarray:
    """(n, 3) world centres of the URDF's collision shapes at ``q`` (a capsule's three shapes: its cylinder)."""
    m = read_urdf(urdf)
    out = []
    for name, link in m.links.items():
        if name in skip:
            continue
        T = m.T_world_link(name, q)
        out += [(T @ s.T_link_shape)[:3, 3] for s in link.collisions if s.kind != "sphere"]
    return np.array(out)


def _rigid(a: np.ndarray, b: np.ndarray):
    """(R, t) with b ~ a @ R.T + t (Kabsch)."""
    ca, cb = a.mean(0), b.mean(0)
    U, _, Vt = np.linalg.svd((a - ca).T @ (b - cb))
    D = np.diag([1, 1, np.sign(np.linalg.det(Vt.T @ U.T))])
    R = Vt.T @ D @ U.T
    return R, cb - ca @ R.T


def _matched(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``b`` reordered to ``a`` (nearest neighbours; the importer groups geoms by part)."""
    from scipy.optimize import linear_sum_assignment
    rows, cols = linear_sum_assignment(np.linalg.norm(a[:, None] - b[None], axis=2))
    return b[cols[np.argsort(rows)]]


def test_the_hinge_cabinet_moves_as_mujoco_moves_it_placed_as_a_wall_cabinet(tmp_path):
    xml = DATA / "franka_hingecabinet.xml"
    imp = import_mjcf(xml, tmp_path, "hingecabinet", elevation=1.45)
    m = read_urdf(imp.urdf)
    left, right = m.joints["left_hinge_cabinet"], m.joints["right_hinge_cabinet"]
    assert (left.lower, left.upper, right.lower, right.upper) == (-1.57, 0.0, 0.0, 1.57)
    assert left.dynamics.damping == 2.0 and left.dynamics.friction == 2.0        # damping, frictionloss
    assert imp.repairs == [] and imp.joints["left_hinge_cabinet"] == ("door", "hingeleftdoor")
    rest = _urdf_centres(imp.urdf, {})
    R, t = _rigid(_mujoco_centres(xml, {}), rest)          # the placement (geoms in the same order at rest)
    for q in ({}, {"left_hinge_cabinet": -1.2, "right_hinge_cabinet": 0.9}):
        mj = _mujoco_centres(xml, q) @ R.T + t
        assert np.abs(_matched(mj, _urdf_centres(imp.urdf, q)) - mj).max() < 1e-6
    assert np.isclose(np.degrees(np.arctan2(R[1, 0], R[0, 0])) % 360, 270.0)   # its front (-y) turned onto -x
    lo = min((m.T_world_link(n) @ np.append(s.corners(), np.ones((8, 1)), 1).T)[2].min()
             for n, link in m.links.items() for s in link.collisions)
    assert np.isclose(lo, 1.45)


def test_the_libero_microwave_stands_on_a_counter_with_its_inertia_repaired(tmp_path):
    imp = import_mjcf(DATA / "libero_microwave.xml", tmp_path, "microwave", counter=True)
    assert imp.counter_link == "counter" and "inertia from the collision geoms" in imp.repairs[0]
    m = read_urdf(imp.urdf)
    door = m.links["microdoorroot"]
    assert 0.2 < door.inertial.mass < 0.3                    # its collision geoms' masses, 0.26 kg
    top = max((m.T_world_link("counter") @ np.append(s.corners(), np.ones((8, 1)), 1).T)[2].max()
              for s in m.links["counter"].collisions)
    assert np.isclose(top, COUNTER_HEIGHT)


@pytest.mark.parametrize("name, source, joint", [("franka_hingecabinet", "franka_hingecabinet.xml", "left_hinge_cabinet"),
                                                  ("libero_microwave", "libero_microwave.xml", "microjoint")])
def test_a_light_third_party_door_is_certified_on_its_own_urdf(name, source, joint, tmp_path):
    """Doors of 0.26-0.4 kg whose centre of mass is far from the hinge: the grasp spring's stability bound reads
    the handle's true lever (simcheck.bullet.point_jacobian); before, they chattered against their stop."""
    from simcheck.certification import certify
    built = build_mjcf_object(asset_named(name), {}, tmp_path, source=DATA / source)
    front = next(f for f in built.fronts if f.joint == joint)
    assert front.kind == "door_left" and front.sign == -1 and front.handle_geoms
    t = certify(built.urdf, [front.task], images=False).tasks[0]
    assert t.status.value == "certified", t.reason
    assert t.amount < 0


@pytest.mark.parametrize("name, source", [("libero_slide_cabinet", "libero_slide_cabinet.xml"),
                                          ("libero_window", "libero_window.xml")])
def test_a_front_sliding_across_itself_is_grasped_on_its_face_and_certified(name, source, tmp_path):
    """A sliding door and an 80 g window sash: the handle is what stands out of the face (not along the motion;
    planners.handle.sliding_front), approached along the face's normal; the sash is light enough that the grasp
    spring's damping is bounded by its effective mass (simcheck.grasp_spring.stable_damping)."""
    from simcheck.certification import certify
    built = build_mjcf_object(asset_named(name), {}, tmp_path, source=DATA / source)
    t = certify(built.urdf, [built.fronts[0].task], images=False).tasks[0]
    assert t.status.value == "certified", t.reason


BAD = """<mujoco model="bad"><compiler inertiafromgeom="auto" inertiagrouprange="4 4"/>
  <worldbody><body name="carcass"><geom type="box" size="0.3 0.2 0.4" group="0"/>
    <body name="door" pos="0 -0.25 0"><joint name="hinge" type="{joint}" axis="0 0 1" range="0 1.5"/>
      <geom type="box" size="0.3 0.02 0.4" pos="0.3 0 0" group="0"/></body></body>{extra}</worldbody></mujoco>"""


def test_a_ball_joint_is_refused_naming_the_body_and_joint(tmp_path):
    f = tmp_path / "ball.xml"
    f.write_text(BAD.format(joint="ball", extra="").replace(' axis="0 0 1" range="0 1.5"', ""))
    with pytest.raises(MjcfImportError, match="body 'door' has a ball joint 'hinge': not a drawer or door"):
        import_mjcf(f, tmp_path / "out", "ball")


def test_a_simulators_own_element_is_left_out_and_said(tmp_path):
    f = tmp_path / "region.xml"
    f.write_text(BAD.format(joint="hinge", extra='<region name="r" pos="0 0 0"/>'))
    imp = import_mjcf(f, tmp_path / "out", "region")
    assert any("['region']" in r for r in imp.repairs) and any("inertia" in r for r in imp.repairs)
    assert imp.joints == {"hinge": ("door", "door")}


SLIDE = BAD.replace('type="{joint}" axis="0 0 1" range="0 1.5"', 'type="slide" axis="0 -1 0" range="0 0.3"')


def test_a_tabletop_asset_scaled_keeps_its_shape_and_density(tmp_path):
    """``scale=s``: lengths (shapes, joint origins, a slide's travel) x s, masses x s^3, inertias x s^5; a
    hinge's range (an angle) and the joint's damping and friction as given."""
    f = tmp_path / "slide.xml"
    f.write_text(SLIDE.format(extra=""))
    one, two = (read_urdf(import_mjcf(f, tmp_path / f"s{s}", "drawer", scale=s).urdf) for s in (1.0, 2.0))
    assert np.allclose(two.links["door"].collisions[0].size, 2 * one.links["door"].collisions[0].size)
    assert np.isclose(two.links["door"].inertial.mass, 8 * one.links["door"].inertial.mass)
    assert np.allclose(two.links["door"].inertial.inertia, 32 * one.links["door"].inertial.inertia)
    assert np.isclose(two.joints["hinge"].upper, 2 * one.joints["hinge"].upper)
    f.write_text(BAD.format(joint="hinge", extra=""))
    h1, h2 = (read_urdf(import_mjcf(f, tmp_path / f"h{s}", "door", scale=s).urdf).joints["hinge"] for s in (1.0, 2.0))
    assert (h2.lower, h2.upper) == (h1.lower, h1.upper) == (0.0, pytest.approx(np.radians(1.5)))  # MJCF: degrees


@pytest.mark.parametrize("scale", [0.0, -1.0, float("nan")])
def test_a_scale_that_is_not_a_positive_number_is_refused(scale, tmp_path):
    f = tmp_path / "door.xml"
    f.write_text(BAD.format(joint="hinge", extra=""))
    with pytest.raises(MjcfImportError, match="scale"):
        import_mjcf(f, tmp_path / "out", "door", scale=scale)
