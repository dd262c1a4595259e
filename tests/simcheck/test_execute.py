"""Physics execution on the hand-made fixture (gantry gripper + cabinet; hand-made plans, no planner)."""

import dataclasses

import numpy as np
import pytest

from planners.task import PlanResult
from scenes.outcome import Outcome
from simcheck.certificate import Certificate
from simcheck.certification import certify
from simcheck.errors import RolloutFormatError, SceneLoadError, TaskSpecError
from simcheck.execute import execute_task, handle_link_for
from simcheck.plan_recheck import densify, recheck_plan
from simcheck.rollout import Rollout
from simcheck.world import World

from simcheck_fixture_plans import (CABINET, CABINET_BLOCKED, DOOR, DRAWER, ROBOT, door_plan, drawer_plan,
                                    fixture_planner, line, _seg)
import simcheck.estimate_faults as wrong


@pytest.fixture(scope="module")
def good(tmp_path_factory):
    """Drawer and door certified on the fixture; the certificate and rollouts written to a temp folder."""
    out = tmp_path_factory.mktemp("good")
    cert = certify(CABINET, [f"open-drawer:{DRAWER}", f"open-door:{DOOR}"], robot=ROBOT, out=out, video=True,
                   planner=fixture_planner({DRAWER: drawer_plan(), DOOR: door_plan()}))
    return cert, out


def test_fixture_drawer_and_door_are_certified(good):
    cert, out = good
    assert cert.ok and cert.exit_code == 0, cert.summary()
    drawer = cert[DRAWER]
    assert drawer.criterion("opened_fraction").value == pytest.approx(1.0, abs=0.02)
    assert drawer.criterion("handle_path_deviation").value < 0.01
    assert cert[DOOR].criterion("opened_fraction").value == pytest.approx(1.0, abs=0.02)
    assert {c.name for c in drawer.criteria} >= {"plan_found", "plan_collision_free", "opened_fraction",
                                                 "handle_path_deviation", "settled_linear_speed",
                                                 "settled_angular_speed", "unexpected_contact_force",
                                                 "grasp_held", "robot_joint_limits"}


def test_certificate_file_round_trips_and_records_provenance(good):
    cert, out = good
    back = Certificate.load(out / "certificate.json")
    assert back.to_dict() == cert.to_dict()
    assert back.criteria["name"] == "partscene-default" and back.criteria["version"] == "2.2"
    assert set(back.versions) >= {"pybullet", "pinocchio", "ompl", "numpy", "partscene"}
    assert back.seeds == {"seed": 0}
    assert back[DRAWER].timings["execute"] > 0 and back[DRAWER].timings["simulated"] > 3.0


def test_rollout_is_saved_with_every_array_and_loads_back(good):
    cert, out = good
    r = Rollout.load(out / cert[DRAWER].rollout)
    assert r.joint == DRAWER and r.handle_link == "cabinet1_handle3"
    assert r.robot_q.shape == (r.n, 4) and r.T_world_handle.shape == (r.n, 4, 4)
    assert r.object_q[0] == pytest.approx(0.0, abs=1e-4) and r.object_q[-1] == pytest.approx(0.3, abs=5e-3)
    assert r.grasp_active[r.in_segment("open")].all() and r.grasp_force.max() > 0
    assert set(r.contact_scene_link) == {"cabinet1_handle3"}      # the gripper touched only the handle
    path = r.save(out / "copy.npz")
    assert Rollout.load(path).isclose(r)


def test_key_frames_are_written_as_png(good):
    cert, out = good
    images = [p for p in cert[DOOR].images if p.endswith(".png")]
    assert {p.rsplit("_", 1)[-1] for p in images} == {"start.png", "grasped.png", "opened.png", "end.png"}
    gif = [p for p in cert[DOOR].images if p.endswith(".gif")]
    assert len(gif) == 1 and (out / gif[0]).read_bytes()[:6] == b"GIF89a"
    from PIL import Image
    assert Image.open(out / gif[0]).n_frames >= 10
    for p in images:
        data = (out / p).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 2000


def test_a_bad_rollout_file_is_rejected_with_its_name(tmp_path):
    p = tmp_path / "junk.npz"
    np.savez(p, t=np.zeros(3))
    with pytest.raises(RolloutFormatError, match="junk.npz"):
        Rollout.load(p)


def test_execution_is_deterministic():
    runs = []
    for _ in range(2):
        with World(CABINET, ROBOT) as w:
            runs.append(execute_task(w, drawer_plan(amount=0.1)))
    a, b = runs
    assert a.n == b.n and np.array_equal(a.object_q, b.object_q) and np.array_equal(a.robot_q, b.robot_q)


def test_the_object_moves_only_when_the_robot_moves_it():
    plan = drawer_plan()
    idle = dataclasses.replace(plan, segments=plan.segments[:1])   # approach only, never grasps
    with World(CABINET, ROBOT) as w:
        r = execute_task(w, idle)
    assert np.abs(r.object_q).max() < 1e-4 and not r.grasp_active.any()


def test_a_grasp_above_the_handle_is_never_made_and_fails():
    plan = drawer_plan(handle=(0.29, 0.0, 0.76))          # 8 cm above the bar: fingers close on air
    cert = certify(CABINET, [f"open-drawer:{DRAWER}"], robot=ROBOT, planner=fixture_planner({DRAWER: plan}))
    t = cert[DRAWER]
    assert t.status is Outcome.FAILED and cert.exit_code == 1
    assert not t.criterion("grasp_held").passed and "does not touch handle" in t.criterion("grasp_held").detail
    assert not t.criterion("opened_fraction").passed


def _through_the_top_panel() -> PlanResult:
    """The drawer plan, but the approach comes down through the cabinet's top panel."""
    plan = drawer_plan()
    grasp_q = plan.segments[1].q[0]
    above = grasp_q + [-0.25, 0.0, 0.5, 0.0]
    inside = grasp_q + [-0.25, 0.0, 0.0, 0.0]
    approach = _seg("approach", np.concatenate([line(above, inside, 12), line(inside, grasp_q, 8)]), "open", 0.0)
    return dataclasses.replace(plan, segments=(approach,) + plan.segments[1:])


def test_independent_recheck_finds_a_colliding_plan():
    with World(CABINET, ROBOT) as w:
        before = w.robot_q().copy()
        check = recheck_plan(w, _through_the_top_panel())
        clean = recheck_plan(w, drawer_plan())
        assert np.array_equal(w.robot_q(), before) and w.scene_joint_state(DRAWER)[0] == 0.0   # restored
    assert check.max_depth > 0.01 and "approach" in check.detail
    assert "scene link cabinet1_body1" in check.detail or "scene link cabinet1_drawer2" in check.detail
    assert clean.max_depth == 0.0 and clean.n_states > 50


def test_a_colliding_plan_is_never_certified_and_the_contact_is_seen_in_physics():
    cert = certify(CABINET, [f"open-drawer:{DRAWER}"], robot=ROBOT, images=False,
                   planner=fixture_planner({DRAWER: _through_the_top_panel()}))
    t = cert[DRAWER]
    assert t.status is Outcome.FAILED
    assert not t.criterion("plan_collision_free").passed
    hit = t.criterion("unexpected_contact_force")
    assert not hit.passed and ("cabinet1_body1" in hit.detail or "cabinet1_drawer2" in hit.detail)


def test_densify_bounds_the_joint_step():
    q = np.array([[0.0, 0.0], [1.0, 0.1], [1.0, 0.1]])
    dense, extra = densify(q, 0.02, np.array([0.0, 1.0, 2.0]))
    assert np.abs(np.diff(dense, axis=0)).max() <= 0.02 + 1e-12
    assert np.allclose(dense[[0, -1]], q[[0, -1]]) and extra[-1] == pytest.approx(2.0)


def test_fixture_wrong_axis_estimate_fails_against_the_reference(tmp_path):
    est = wrong.rotate_axis(CABINET, DRAWER, 30.0, tmp_path / "axis30.urdf")
    cert = certify(est, [f"open-drawer:{DRAWER}"], against=CABINET, robot=ROBOT, images=False,
                   planner=fixture_planner({DRAWER: drawer_plan(axis_deg=30.0)}))
    t = cert[DRAWER]
    assert t.status is Outcome.FAILED and "30 deg off the reference axis" in t.reason
    assert not t.criterion("handle_path_deviation").passed


def test_fixture_blocked_door_fails_and_names_the_blocker():
    cert = certify(CABINET, [f"open-door:{DOOR}"], against=CABINET_BLOCKED, robot=ROBOT, images=False,
                   planner=fixture_planner({DOOR: door_plan()}))
    t = cert[DOOR]
    assert t.status is Outcome.FAILED and "box9_body9" in t.reason
    assert not t.criterion("opened_fraction").passed


def test_world_looks_joints_and_links_up_by_name():
    with World(CABINET, ROBOT) as w:
        assert w.scene_joint(DOOR).type == "revolute" and w.scene_joint(DOOR).upper == pytest.approx(1.7)
        assert handle_link_for(w, DRAWER) == "cabinet1_handle3"
        assert np.allclose(w.scene_link_pose("cabinet1_handle3")[:3, 3], [0.29, 0.0, 0.68], atol=1e-6)
        with pytest.raises(TaskSpecError, match=r"cabinet\.urdf has no joint 'nope'"):
            w.scene_joint("nope")
        img = w.render(np.array([0.3, 0, 0.5]), np.array([2.0, 1.0, 1.5]), 64, 48)
        assert img.shape == (48, 64, 3) and img.dtype == np.uint8 and img.std() > 1


def test_world_rejects_missing_and_broken_scenes(tmp_path, monkeypatch):
    with pytest.raises(SceneLoadError, match="nothing.urdf does not exist"):
        World(tmp_path / "nothing.urdf", ROBOT)
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'/><joint name='j' type='fixed'><parent link='a'/>"
                   "<child link='missing'/></joint></robot>")
    with pytest.raises(SceneLoadError, match="bad.urdf"):
        World(bad, ROBOT)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    with pytest.raises(SceneLoadError, match="needs a display"):
        World(CABINET, ROBOT, gui=True)
