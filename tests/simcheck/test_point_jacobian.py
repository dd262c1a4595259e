"""simcheck.bullet.point_jacobian: the Jacobian of a point of a scene link whose centre of mass is far from
its joint and whose inertial frame is turned (as third-party files have them) is that point's velocity per
unit joint value -- PyBullet takes the point from the link frame's origin, in the inertial frame's axes."""

import numpy as np

from simcheck.bullet import link_pose, pb, point_jacobian

DOOR = """<?xml version="1.0"?>
<robot name="door">
  <link name="frame"/>
  <link name="door">
    <inertial><origin xyz="0.3 -0.04 0.1" rpy="0.3 -0.2 0.7"/><mass value="0.26"/>
      <inertia ixx="0.003" ixy="0" ixz="0" iyy="0.0098" iyz="0" izz="0.0069"/></inertial>
    <collision><origin xyz="0.26 -0.03 0"/><geometry><box size="0.52 0.05 0.37"/></geometry></collision>
  </link>
  <joint name="hinge" type="revolute"><parent link="frame"/><child link="door"/>
    <origin xyz="1.3 0.35 1.1" rpy="0 0 -1.5708"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="0" effort="100" velocity="1"/></joint>
</robot>
"""


def test_the_jacobian_of_a_handle_point_is_its_velocity_about_the_hinge(tmp_path):
    f = tmp_path / "door.urdf"
    f.write_text(DOOR)
    c = pb.connect(pb.DIRECT)
    try:
        body = pb.loadURDF(str(f), useFixedBase=True, flags=pb.URDF_USE_INERTIA_FROM_FILE, physicsClientId=c)
        pb.resetJointState(body, 0, -0.4, physicsClientId=c)
        T = link_pose(c, body, 0)
        p_local = np.array([0.47, -0.1, 0.05])                     # the handle, 0.48 m from the hinge
        J = point_jacobian(c, body, 0, p_local)
        p = (T @ np.append(p_local, 1.0))[:3]
        axis, anchor = T[:3, 2], T[:3, 3]                          # the hinge: the link's z through its origin
        assert np.allclose(J[:, 0], np.cross(axis, p - anchor), atol=1e-6)
        assert np.isclose(np.linalg.norm(J), np.linalg.norm(p_local[:2]), atol=1e-6)
    finally:
        pb.disconnect(c)
