"""simcheck: certify opening tasks in PyBullet physics with a mobile manipulator.

Python API (for users' own pytest tests)::

    import simcheck
    cert = simcheck.certify("scene.urdf", ["open-drawer:cabinet3_drawer12_joint"], against="truth.urdf", seed=0)
    simcheck.assert_certified(cert)                 # AssertionError listing every failed criterion
    cert.ok, cert.exit_code, cert.tasks[0].criterion("opened_fraction").margin
    cert["cabinet3_drawer12_joint"].status          # an Outcome: certified, failed, not_planned, unreachable, ...

    cert = simcheck.run_scenario("scenario.yaml")  # tasks in sequence, world state carried over

Names are imported lazily so ``import simcheck.report`` or ``simcheck.errors`` stays light (no PyBullet).
"""

from __future__ import annotations

import importlib

__all__ = ["certify", "run_scenario", "assert_certified", "Certificate", "TaskCertificate", "Outcome", "exit_code", "Task",
           "CriteriaConfig", "PhysicsConfig", "DEFAULT_CRITERIA", "DEFAULT_PHYSICS", "CriterionResult", "Rollout",
           "World", "SimRobot", "PlannedTask", "PlannedSegment", "PlanOutcome", "execute_task", "recheck_plan",
           "load_robot_spec", "load_scenario", "SimcheckError", "SimcheckInputError"]

_WHERE = {
    "certify": "simcheck.certification", "PlanOutcome": "simcheck.certification",
    "run_scenario": "simcheck.run", "assert_certified": "simcheck.run",
    "Certificate": "simcheck.certificate", "TaskCertificate": "simcheck.certificate",
    "Outcome": "scenes.outcome", "exit_code": "scenes.outcome",
    "Task": "simcheck.tasks",
    "CriteriaConfig": "simcheck.config", "PhysicsConfig": "simcheck.config", "DEFAULT_CRITERIA": "simcheck.config",
    "DEFAULT_PHYSICS": "simcheck.config",
    "CriterionResult": "simcheck.criteria", "Rollout": "simcheck.rollout", "World": "simcheck.world",
    "SimRobot": "simcheck.robot_binding", "PlannedTask": "simcheck.planned_task", "PlannedSegment": "simcheck.planned_task",
    "execute_task": "simcheck.execute", "recheck_plan": "simcheck.plan_recheck",
    "load_robot_spec": "simcheck.robot_spec_file", "load_scenario": "simcheck.scenario",
    "SimcheckError": "simcheck.errors", "SimcheckInputError": "simcheck.errors",
}


def __getattr__(name: str):
    if name in _WHERE:
        module = importlib.import_module(_WHERE[name])
        value = getattr(module, name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'simcheck' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
