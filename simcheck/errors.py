"""Errors raised by :mod:`simcheck` for inputs it cannot use.

Expected outcomes (a task that fails certification, a plan that was not found) are never raised: they
are :class:`simcheck.TaskCertificate` entries with a :class:`scenes.outcome.Outcome` and a reason. The
exceptions below are for input that cannot be certified at all; every message names the file and the
joint, link or field. Every input error (:class:`SimcheckInputError`, ``planners.PlannerInputError``) is a
``scenes.description.InputError``: exit code 2, outcome ``unusable``. A malformed task, or one whose joint does not fit the scene, raises the planner's
``TaskSpecError`` (re-exported here; tasks are ``planners.OpenTask``).
"""

from __future__ import annotations

from planners.errors import TaskSpecError
from scenes.description import InputError, PartsceneError

__all__ = ["SimcheckError", "SimcheckInputError", "SceneLoadError", "TaskSpecError", "RobotBindingError",
           "ScenarioError", "RolloutFormatError", "PlanFileError"]


class SimcheckError(PartsceneError):
    """Base class of every exception raised by :mod:`simcheck`."""


class SimcheckInputError(SimcheckError, InputError):
    """The input (scene URDF, task, robot, scenario) cannot be used; the message says why."""


class SceneLoadError(SimcheckInputError):
    """A scene URDF is missing, unparsable or rejected by PyBullet (names the file)."""


class RobotBindingError(SimcheckInputError):
    """A robot description does not match its URDF (names the URDF and the joint or link)."""


class ScenarioError(SimcheckInputError):
    """A scenario YAML file is malformed (names the file and the field)."""


class PlanFileError(SimcheckInputError):
    """A plan file (``partscene.plan/1``) or given plan is malformed or does not fit the robot, scene or
    carried-over state (names the file and the field: segment, waypoint, column and joint)."""


class RolloutFormatError(SimcheckError):
    """A saved rollout file is not a partscene rollout (names the file and the missing array)."""
