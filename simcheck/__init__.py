"""simcheck: certify opening tasks in PyBullet physics with a mobile manipulator.

Python API (for users' own pytest tests)::

    import simcheck
    cert = simcheck.certify("scene.urdf", ["open-drawer:cabinet3_drawer12_joint"], against="truth.urdf", seed=0)
    simcheck.assert_certified(cert)                 # AssertionError listing every failed criterion
    cert.ok, cert.exit_code, cert.tasks[0].criterion("opened_fraction").margin
    cert["cabinet3_drawer12_joint"].status          # an Outcome: certified, failed, not_planned, unreachable, ...

    cert = simcheck.certify_plan("scene.urdf", "my.plan.json")   # a user's own plan (partscene.plan/1), replayed
    cert = simcheck.run_scenario("scenario.yaml")  # tasks in sequence, world state carried over
    result = simcheck.batch("manifest.yaml", out="batch-out")  # every task of a manifest, on Ray

Names are imported on first use, so ``import simcheck.report`` or ``simcheck.errors`` stays light (no PyBullet).
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach(__name__, submod_attrs={
    "certification": ["certify"],
    "given_plan": ["certify_plan"],
    "plan_file": ["read_plan", "write_plan", "plan_from_arrays", "GivenPlan"],
    "run": ["run_scenario", "assert_certified"],
    "certificate": ["Certificate", "TaskCertificate", "Outcome", "exit_code"],
    "config": ["CriteriaConfig", "PhysicsConfig", "DEFAULT_CRITERIA", "DEFAULT_PHYSICS"],
    "criteria": ["CriterionResult"],
    "rollout": ["Rollout"],
    "world": ["World"],
    "robot_binding": ["SimRobot"],
    "execute": ["execute_task"],
    "plan_recheck": ["recheck_plan"],
    "robot_spec_file": ["load_robot_spec"],
    "scenario": ["load_scenario"],
    "errors": ["SimcheckError", "SimcheckInputError"],
    "batching": ["batch"],
})
