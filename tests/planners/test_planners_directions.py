"""Which way a task opens its joint (``planners.plan._validate``): toward the limit farther from the current
value, an explicit amount of either sign, a default for joints without limits; no planning (fast)."""

import math

import pytest

from planners.config import PlannerConfig
from planners.errors import TaskJointError
from planners.plan import _validate
from planners.scene_urdf import read_scene_urdf
from planners.task import OpenTask

DRAWER, DOOR = "cabinet1_drawer12_joint", "cabinet1_door14_joint"
CFG = PlannerConfig()


def _scene(fixture_urdf, tmp_path, door_limits, drawer_limits, door_type="revolute"):
    text = open(fixture_urdf).read()
    text = text.replace('lower="0.0" upper="1.9"', f'lower="{door_limits[0]}" upper="{door_limits[1]}"')
    text = text.replace('lower="0.0" upper="0.35"', f'lower="{drawer_limits[0]}" upper="{drawer_limits[1]}"')
    text = text.replace(f'<joint name="{DOOR}" type="revolute">', f'<joint name="{DOOR}" type="{door_type}">')
    out = tmp_path / "s.urdf"
    out.write_text(text)
    return read_scene_urdf(out)


def test_a_joint_with_a_negative_range_opens_toward_its_lower_limit(fixture_urdf, tmp_path):
    scene = _scene(fixture_urdf, tmp_path, (-1.57, 0.0), (-0.3, 0.0))
    assert _validate(scene, OpenTask("door", DOOR), 0.0, CFG) == pytest.approx(-min(0.9 * 1.57, CFG.door_max))
    assert _validate(scene, OpenTask("drawer", DRAWER), 0.0, CFG) == pytest.approx(-0.9 * 0.3)
    assert _validate(scene, OpenTask("drawer", DRAWER, amount=-0.1), 0.0, CFG) == pytest.approx(-0.1)
    with pytest.raises(TaskJointError, match=r"amount 0.1 from 0 leaves the limits \[-0.3, 0\]"):
        _validate(scene, OpenTask("drawer", DRAWER, amount=0.1), 0.0, CFG)


def test_our_positive_convention_is_kept_and_a_continuous_joint_opens_85_deg(fixture_urdf, tmp_path):
    scene = _scene(fixture_urdf, tmp_path, (0.0, 1.9), (0.0, 0.35))
    assert _validate(scene, OpenTask("door", DOOR), 0.0, CFG) == pytest.approx(CFG.door_max)
    assert _validate(scene, OpenTask("drawer", DRAWER), 0.0, CFG) == pytest.approx(0.9 * 0.35)
    scene = _scene(fixture_urdf, tmp_path, (0.0, 1.9), (0.0, 0.35), door_type="continuous")
    assert _validate(scene, OpenTask("door", DOOR), 0.3, CFG) == pytest.approx(CFG.door_max)
    assert CFG.door_max == pytest.approx(math.radians(85))
