"""Reading scene URDFs: every malformed input names the file and the element; FK agrees with pinocchio."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from planners import SceneURDFError
from planners.scene_urdf import read_scene_urdf

DRAWER = "cabinet1_drawer12_joint"
DOOR = "cabinet1_door14_joint"


def test_fixture_is_read_as_one_tree(fixture_urdf):
    s = read_scene_urdf(fixture_urdf)
    assert s.root == "world"
    assert s.joints[DRAWER].type == "prismatic" and s.joints[DOOR].type == "revolute"
    assert s.joints[DRAWER].upper == pytest.approx(0.35)
    assert set(s.subtree_links("cabinet1_drawer12")) == {"cabinet1_drawer12", "cabinet1_handle13"}


def test_forward_kinematics_matches_pinocchio(fixture_urdf):
    s = read_scene_urdf(fixture_urdf)
    model = pin.buildModelFromUrdf(str(fixture_urdf))
    data = model.createData()
    rng = np.random.default_rng(3)
    for _ in range(5):
        values = {DRAWER: rng.uniform(0, 0.35), DOOR: rng.uniform(0, 1.9)}
        q = pin.neutral(model)
        for name, v in values.items():
            q[model.joints[model.getJointId(name)].idx_q] = v
        pin.framesForwardKinematics(model, data, q)
        for link in ("cabinet1_handle13", "cabinet1_handle15", "cabinet1_door14"):
            T_pin = data.oMf[model.getFrameId(link)].homogeneous
            assert np.allclose(s.T_world_link(link, values), T_pin, atol=1e-12)


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace('<box size="0.5 0.8 0.02"/>', '<box size="0.5 -0.8 0.02"/>', 1), "non-positive size"),
    (lambda t: t.replace('<parent link="cabinet1_body10"/><child link="cabinet1_drawer12"/>',
                         '<parent link="cabinet1_bodyX"/><child link="cabinet1_drawer12"/>'),
     "'cabinet1_drawer12_joint' names parent link 'cabinet1_bodyX'"),
    (lambda t: t.replace('lower="0.0" upper="0.35"', 'lower="0.0" upper="-0.35"'), "upper limit -0.35 < lower"),
    (lambda t: t.replace('<axis xyz="1 0 0"/>', '<axis xyz="0 0 0"/>'), "'cabinet1_drawer12_joint' has a zero axis"),
    (lambda t: t.replace('lower="0.0" upper="0.35"', 'lower="0.0" upper="nan"'), "finite"),
    (lambda t: t[: len(t) // 2], "not valid XML"),
    (lambda t: t.replace('<joint name="cabinet1_drawer12_joint" type="prismatic">',
                         '<joint name="cabinet1_drawer12_joint" type="slider">'), "unknown type 'slider'"),
])
def test_malformed_scene_urdf_is_rejected_with_names(variants, edit, message):
    path = variants.write("bad.urdf", edit(variants.text))
    with pytest.raises(SceneURDFError, match=message) as e:
        read_scene_urdf(path)
    assert "bad.urdf" in str(e.value)


def test_missing_file_is_named(tmp_path):
    with pytest.raises(SceneURDFError, match="nothere.urdf: scene URDF not found"):
        read_scene_urdf(tmp_path / "nothere.urdf")
