"""Scripted scenarios: a scene, a robot, and a sequence of tasks run one after the other with the world
state carried from task to task (drawer A stays open while door B is opened).

``SCENARIO.yaml``::

    scene: truth.urdf            # relative paths are relative to the YAML file
    against: null                # optional reference URDF to execute on
    robot: default               # or compliant, or a robot spec file (see simcheck.robot_spec_file)
    seed: 0
    tasks:
      - open-drawer:cabinet3_drawer12_joint
      - {kind: open-door, joint: cabinet5_door14_joint, amount: 1.2}   # also grasp_point, grasp_link
      - close-drawer:cabinet3_drawer12_joint       # shut from where the first task left it
      - {kind: close-door, joint: cabinet5_door16_joint, from: 0.8}      # set 0.8 rad open first
      - plan: drawer.plan.json     # a given plan (partscene.plan/1, one expectation), replayed as it is;
                                   # its first waypoint must be where the previous task left the robot;
                                   # executed with the scenario's robot (the plan's 'robot' is not used)

Any other key is an error naming it and the closest valid key (:mod:`simcheck.file_schemas`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from planners.task import ACTIONS, OpenTask, parse_task
from simcheck.errors import ScenarioError
from simcheck.file_schemas import SCENARIO_SCHEMA, check_document
from simcheck.robot_spec_file import is_named_robot

__all__ = ["Scenario", "load_scenario"]


@dataclass(frozen=True)
class Scenario:
    """A parsed scenario (paths absolute)."""

    path: Path
    scene: Path
    against: Path | None
    robot: str
    seed: int
    tasks: tuple[OpenTask | Path, ...]     # a Path: a given plan file


def _task(entry, path: Path, i: int) -> OpenTask | Path:
    if isinstance(entry, dict) and "plan" in entry:
        if len(entry) != 1:
            raise ScenarioError(f"{path}: tasks[{i}] gives a plan file and {sorted(set(entry) - {'plan'})}: a plan "
                                "entry is {plan: FILE} alone")
        return (path.parent / str(entry["plan"])).resolve()
    if isinstance(entry, str):
        return parse_task(entry)
    if isinstance(entry, dict):
        if "kind" in entry and "joint" in entry:
            kind, joint = entry["kind"], entry["joint"]
        elif len([k for k in entry if k in ACTIONS]) == 1:
            kind = next(k for k in entry if k in ACTIONS)
            joint = entry[kind]
        else:
            raise ScenarioError(f"{path}: tasks[{i}] needs 'kind' and 'joint' (or 'open-drawer: JOINT'), got {entry}")
        task = parse_task(f"{kind}:{joint}")
        wrong = "amount" if task.close else "from"
        if wrong in entry:
            raise ScenarioError(f"{path}: tasks[{i}] ({task}): '{wrong}' is for {'opening' if task.close else 'close'} "
                                f"tasks; {'a close task starts open by from' if task.close else 'an opening goes by amount'}")
        return OpenTask(task.kind, task.joint, entry.get("from" if task.close else "amount"), entry.get("grasp_point"),
                        entry.get("grasp_link"), task.close)
    raise ScenarioError(f"{path}: tasks[{i}] must be a string or a mapping, got {type(entry).__name__}")


def load_scenario(path: str | Path) -> Scenario:
    """Read and check ``SCENARIO.yaml``.

    Raises:
        ScenarioError: missing file, invalid YAML, a missing, ill-typed or unknown field (names the file and
            the field, and for an unknown field the closest valid one; :data:`simcheck.file_schemas.SCENARIO_SCHEMA`).
    """
    import yaml

    path = Path(path)
    if not path.is_file():
        raise ScenarioError(f"scenario {path} does not exist")
    try:
        doc = yaml.safe_load(path.read_text())
    except yaml.YAMLError as exc:
        raise ScenarioError(f"scenario {path} is not valid YAML: {exc}") from exc
    check_document(doc, SCENARIO_SCHEMA, "scenario", path, ScenarioError)
    tasks = doc["tasks"]
    base = path.parent

    def resolve(p):
        return None if p is None else (base / str(p)).resolve()

    seed = doc.get("seed", 0)
    robot = str(doc.get("robot", "default"))
    if not is_named_robot(robot):
        robot = str(resolve(robot))
    return Scenario(path=path, scene=resolve(doc["scene"]), against=resolve(doc.get("against")), robot=robot,
                    seed=seed, tasks=tuple(_task(t, path, i) for i, t in enumerate(tasks)))
