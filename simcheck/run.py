"""Running scenarios, and the assertion helper for users' tests."""

from __future__ import annotations

from pathlib import Path

from simcheck.certificate import Certificate
from simcheck.certification import certify
from simcheck.robot_spec_file import is_named_robot, load_robot_spec
from simcheck.scenario import load_scenario

__all__ = ["run_scenario", "assert_certified"]


def run_scenario(path, *, out=None, seed: int | None = None, images: bool = True, video: bool = False,
                 gui: bool = False, **kwargs) -> Certificate:
    """Run the scenario YAML at ``path``: its tasks in order, the world state carried from task to task
    (the scene's joints keep their values; each plan starts from the robot's current configuration when
    the planner can, else from its own start); each task's certificate records where it started
    (``start_state``: the scene's joints, ``start_robot_q``: the robot). ``seed`` overrides the scenario's seed.
    The certificate records the scenario file's sha256 beside the scene's (``Certificate.files``)."""
    sc = load_scenario(path)
    robot = load_robot_spec(sc.robot)
    files = {"scenario": sc.path, "robot_spec": None if is_named_robot(sc.robot) else sc.robot,
             **{f"plan{i}": t for i, t in enumerate(sc.tasks) if isinstance(t, Path)}, **kwargs.pop("files", {})}
    tasks, planner = list(sc.tasks), None
    if any(isinstance(t, Path) for t in tasks):
        tasks, planner = _mixed_tasks(sc, robot, kwargs.pop("planner_config", None))
    return certify(sc.scene, tasks, against=sc.against, seed=sc.seed if seed is None else seed,
                   out=Path(out) if out is not None else None, robot=robot, images=images, video=video, gui=gui,
                   carry_state=True, planner=planner, files=files, **kwargs)


def _mixed_tasks(sc, robot, planner_config):
    """The tasks of a scenario that mixes planned tasks and given plans (``Path`` entries), and the planner
    that answers them in order: the planners' planner for a task, the bound plan for a plan file (which
    must have one expectation: a scenario task is one opening)."""
    from planners.config import PlannerConfig
    from simcheck.certification import planners_planner
    from simcheck.errors import PlanFileError
    from simcheck.given_plan import given_planner

    own = planners_planner(robot, planner_config or PlannerConfig())
    tasks, planners = [], []
    for i, entry in enumerate(sc.tasks):
        if isinstance(entry, Path):
            given_tasks, planner = given_planner(entry, robot, sc.scene)
            if len(given_tasks) != 1:
                raise PlanFileError(f"scenario {sc.path}: tasks[{i}]: plan {entry} has {len(given_tasks)} "
                                    "expectations; a scenario's plan has one (split it into one plan per expectation)")
            tasks.append(given_tasks[0])
            planners.append(planner)
        else:
            tasks.append(entry)
            planners.append(own)
    queue = iter(planners)

    def plan(scene, task, seed, start=None, scene_state=None):
        return next(queue)(scene, task, seed, start, scene_state)

    plan.robot_spec = robot
    return tasks, plan


def assert_certified(cert: Certificate, *joints: str) -> None:
    """Raise AssertionError (with every failed criterion and reason) unless every task -- or the tasks
    of ``joints`` -- is certified."""
    tasks = [cert[j] for j in joints] if joints else list(cert.tasks)
    if not tasks:
        raise AssertionError("certificate has no task")
    bad = [t for t in tasks if not t.ok]
    if bad:
        lines = [f"{t.kind}:{t.joint} {t.status.value}: {t.reason}" for t in bad]
        raise AssertionError("not certified:\n  " + "\n  ".join(lines))
