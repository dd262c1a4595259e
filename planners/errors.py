"""Errors raised by :mod:`planners` for inputs it cannot use.

Expected planning failures (no stand pose, no path in time, ...) are never raised: they come back as a
:class:`planners.PlanResult` with a :class:`planners.PlanStatus` and a reason. The exceptions below are
for input that cannot be planned on at all (a broken URDF, a missing or fixed joint, a revolute joint
named as a drawer, a moving part without a handle). Every message names the file and the joint or link;
``simcheck``'s CLI maps :class:`PlannerInputError` to exit code 2.
"""

from __future__ import annotations

from scenes.description import InputError, PartsceneError

__all__ = ["PlannerError", "PlannerInputError", "SceneURDFError", "TaskSpecError", "TaskJointError",
           "HandleNotFoundError", "HandleStaysPutError", "RobotDescriptionError"]


class PlannerError(PartsceneError):
    """Base class of every exception raised by :mod:`planners`."""


class PlannerInputError(PlannerError, InputError):
    """The input (scene URDF, task, robot description) cannot be used; the message says why."""


class SceneURDFError(PlannerInputError):
    """The scene URDF is missing, unparsable, or inconsistent (names the file and the element)."""


class TaskSpecError(PlannerInputError):
    """A task is malformed (unknown kind, no joint, a non-positive amount, a bad grasp point) or does not fit
    the scene (names the task, and the file and joint)."""


class TaskJointError(TaskSpecError):
    """The task's joint is missing, fixed, of the wrong type for the task or without a range (names file
    and joint)."""


class HandleNotFoundError(PlannerInputError):
    """No handle could be found on the part moved by the task's joint (names file and joint)."""


class HandleStaysPutError(HandleNotFoundError):
    """The handle found does not move when the joint opens (it lies on the estimated hinge axis): the
    estimate is usable, but nothing can be pulled; :func:`planners.plan_open_task` reports it as a planning
    outcome (``OPENING_FAILED``), not as unusable input."""


class RobotDescriptionError(PlannerInputError):
    """A :class:`planners.RobotSpec` does not match its URDF (names the URDF and the joint/frame)."""
