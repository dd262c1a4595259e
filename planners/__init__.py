"""planners: robot description, planning-time collision checking (pinocchio + coal), IK, base placement,
OMPL approach and the opening motion that follows the estimated articulation.

API (see docs/contracts.md, "planners <-> simcheck")::

    from planners import default_robot, OpenTask, parse_task, plan_open_task, PlanStatus
    robot = default_robot()
    task = OpenTask("drawer", "cabinet3_drawer12_joint")     # = parse_task("open-drawer:cabinet3_drawer12_joint")
    plan = plan_open_task(robot, "scene.urdf", task, seed=0)
    if plan.ok:
        for seg in plan.segments:   # approach, grasp, open, release, retreat
            seg.q, seg.object_q, seg.T_world_tool, seg.gripper

``plan.joint_names`` are the base joints then the arm joints (the fingers are commanded through
``Segment.gripper`` and ``RobotSpec.finger_open/finger_closed``).

``OpenTask`` is partscene's one task type (simcheck certifies the same objects and executes the
``PlanResult`` as it is). Differences from docs/contracts.md (stable since the first commit):
``OpenTask(kind, joint, amount=None, grasp_point=None, grasp_link=None, close=False)`` (``close``: shut the
part, from ``amount`` open; :func:`close_start_value` gives the value it starts at); ``plan_open_task(..., start=None, scene_state=None, config=None)``;
``PlanResult`` also carries ``grasp_link`` (the link whose bar is grasped), ``moving_link``,
``T_link_grasp``, ``start_object_q`` and ``method`` ("ik_tracking" or "constrained"). Input that cannot be
planned on raises ``PlannerInputError`` (file and joint named); every other outcome is a ``PlanResult``.
"""

import lazy_loader

# Names are imported on first use: importing planners.task or planners.scene_urdf (pure modules) does not
# load pinocchio, coal or OMPL; only planning does.
__getattr__, __dir__, __all__ = lazy_loader.attach(__name__, submod_attrs={
    "robot": ["RobotSpec", "default_robot"],
    "task": ["OpenTask", "PlanResult", "PlanStatus", "Segment", "SEGMENT_NAMES", "parse_task", "parse_tasks",
             "check_task", "ALL_MOVABLE", "movable_joint_tasks", "ACTIONS"],
    "plan": ["plan_open_task", "close_start_value", "closed_value"],
    "config": ["PlannerConfig", "default_amount"],
    "errors": ["PlannerError", "PlannerInputError", "SceneURDFError", "TaskSpecError", "TaskJointError",
               "HandleNotFoundError", "RobotDescriptionError"],
})
