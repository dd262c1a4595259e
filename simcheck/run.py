"""Running scenarios, and the assertion helper for users' tests."""

from __future__ import annotations

from pathlib import Path

from simcheck.certificate import Certificate
from simcheck.certification import certify
from simcheck.robot_spec_file import load_robot_spec
from simcheck.scenario import load_scenario

__all__ = ["run_scenario", "assert_certified"]


def run_scenario(path, *, out=None, seed: int | None = None, images: bool = True, video: bool = False,
                 gui: bool = False, **kwargs) -> Certificate:
    """Run the scenario YAML at ``path``: its tasks in order, the world state carried from task to task
    (the scene's joints keep their values; each plan starts from the robot's current configuration when
    the planner can, else from its own start); each task's certificate records where it started
    (``start_state``: the scene's joints, ``start_robot_q``: the robot). ``seed`` overrides the scenario's seed."""
    sc = load_scenario(path)
    robot = load_robot_spec(sc.robot)
    return certify(sc.scene, list(sc.tasks), against=sc.against, seed=sc.seed if seed is None else seed,
                   out=Path(out) if out is not None else None, robot=robot, images=images, video=video, gui=gui,
                   carry_state=True, **kwargs)


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
