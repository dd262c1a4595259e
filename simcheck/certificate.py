"""The certificate: per task a status, a reason and every criterion; plus criteria version, seeds,
software versions and timings. Written as ``certificate.json`` (atomically) and read back.

``certificate.json`` (format ``partscene.certificate/2``; files of format 1 are read too)::

    {"format": "partscene.certificate/2", "ok": false,
     "scene": "scene.urdf", "against": "truth.urdf" | null, "robot": "robot.urdf",
     "criteria": {"name": "partscene-default", "version": "2.0", ...thresholds...},
     "seeds": {"seed": 0}, "versions": {"pybullet": ..., "pinocchio": ..., "ompl": ..., "numpy": ..., "partscene": ...},
     "timings": {"total": s},
     "untested": {joint: "why it was not tested"},     (movable joints left out of an --all-movable run)
     "files": {"scene": {"path": "...", "sha256": "..."}, "against": ..., "robot": ..., "robot_spec" | "scenario" | "plan": ...},
     "robot_joint_stiffness": {robot joint: N*m/rad or N/m, null: held rigidly},   (the arm's simulated joint impedance)
     "tasks": [{"kind": "open-drawer", "joint": "...", "status": "certified" | "failed" | "not_planned" | "unreachable" | ...,
                "reason": "...", "amount": 0.31, "unit": "m", "seed": 0, "rollout": "rollouts/<joint>.npz",
                "plan_status": "OK" | "NO_STAND_POSE" | ..., "start_state": {joint: value},
                "images": ["images/<joint>_start.png", ...], "timings": {"plan": s, "recheck": s, "execute": s},
                "criteria": [{"name", "value", "threshold", "comparison", "unit", "passed", "margin",
                              "description", "detail"}, ...]}]}

``status`` is a :class:`scenes.outcome.Outcome` value; the run's exit code follows from the statuses
(:func:`scenes.outcome.exit_code`).
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from scenes.description import write_text_atomic
from scenes.outcome import Outcome, exit_code
from simcheck.criteria import CriterionResult
from simcheck.errors import SimcheckInputError

__all__ = ["TaskCertificate", "Certificate", "CERTIFICATE_FORMAT", "software_versions",
           "write_json_atomic"]

CERTIFICATE_FORMAT = "partscene.certificate/2"
#: formats :meth:`Certificate.from_dict` reads (format 1 spells not_planned "not-planned" and marks an
#: unreachable object as ``"input_problem": true``)
READABLE_FORMATS = ("partscene.certificate/1", CERTIFICATE_FORMAT)


@dataclass(frozen=True)
class TaskCertificate:
    """The certificate of one task.

    Attributes:
        kind: "open-drawer" or "open-door".
        joint: the task joint (URDF name).
        status: the task's :class:`~scenes.outcome.Outcome` (certified, failed, not_planned, unreachable, ...).
        reason: why (names the failed criteria, the joint and links involved, and with ``--against``
            how the estimate differs from the reference).
        amount: the requested opening, rad or m (``unit``), counted from the joint's start value: negative
            when the joint opens toward its lower limit (a file whose joint opens toward negative values).
        criteria: every criterion judged.
        seed: the planning seed.
        timings: seconds by stage ("plan", "recheck", "execute", "total").
        rollout: path of the saved rollout, relative to the certificate's folder ("" if not executed).
        images: key-frame PNG paths, relative to the certificate's folder.
        plan_status: the planner's status name ("OK", "NO_STAND_POSE", ...).
        start_state: values of the executed scene's movable joints when the task started (a scenario
            carries them over from the previous task), rad or m by joint name.
        start_robot_q: the robot's controlled joints when the task's execution started (its rollout's
            first sample; the robot's configuration when the task began if nothing was executed), rad or m
            by joint name. A scenario's task starts where the previous one ended.
        robust: with ``--robust N``, how the plan fared in N sampled worlds (:mod:`simcheck.robust_verdict`).
        reference_joint: with ``--against``, how the task joint was matched to the reference's
            (:func:`simcheck.estimate_diff.joint_mapping`: its name, type, limits and ``direction`` +1 / -1,
            -1 when the reference's axis is opposite the estimate's); None without a reference or when the
            reference has no joint of that name.
        nearest_miss: for an ``unreachable`` task, the smallest distance (m) between the robot's tool and
            the grasp point over the base poses tried (0 when the handle is within reach but every grasp
            collides); None otherwise.
    """

    kind: str
    joint: str
    status: Outcome
    reason: str
    amount: float
    unit: str
    criteria: tuple[CriterionResult, ...] = ()
    seed: int = 0
    timings: dict = field(default_factory=dict)
    rollout: str = ""
    images: tuple[str, ...] = ()
    plan_status: str = ""
    start_state: dict = field(default_factory=dict)
    start_robot_q: dict = field(default_factory=dict)
    robust: dict | None = None
    reference_joint: dict | None = None
    nearest_miss: float | None = None

    @property
    def ok(self) -> bool:
        return self.status is Outcome.CERTIFIED

    def criterion(self, name: str) -> CriterionResult:
        """The criterion called ``name`` (KeyError naming the task when absent)."""
        for c in self.criteria:
            if c.name == name:
                return c
        raise KeyError(f"task {self.kind}:{self.joint} has no criterion {name!r}")

    @property
    def failed_criteria(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.criteria if not c.passed)

    def to_dict(self) -> dict:
        return {"kind": self.kind, "joint": self.joint, "status": self.status.value, "reason": self.reason,
                "amount": self.amount, "unit": self.unit, "seed": self.seed, "plan_status": self.plan_status,
                "start_state": dict(self.start_state), "start_robot_q": dict(self.start_robot_q),
                "timings": dict(self.timings), "rollout": self.rollout,
                "images": list(self.images), "criteria": [c.to_dict() for c in self.criteria],
                **({} if self.robust is None else {"robust": self.robust}),
                **({} if self.reference_joint is None else {"reference_joint": dict(self.reference_joint)}),
                **({} if self.nearest_miss is None else {"nearest_miss": float(self.nearest_miss)})}

    @classmethod
    def from_dict(cls, d: dict) -> "TaskCertificate":
        status = Outcome(d["status"])
        if status is Outcome.NOT_PLANNED and d.get("input_problem") and d.get("plan_status") == "NO_STAND_POSE":
            status = Outcome.UNREACHABLE   # how format 1 recorded an unreachable object
        return cls(kind=d["kind"], joint=d["joint"], status=status, reason=d["reason"],
                   amount=float(d["amount"]) if d.get("amount") is not None else float("nan"), unit=d.get("unit", ""),
                   criteria=tuple(CriterionResult.from_dict(c) for c in d.get("criteria", [])),
                   seed=int(d.get("seed", 0)), timings=dict(d.get("timings", {})), rollout=d.get("rollout", ""),
                   images=tuple(d.get("images", [])), plan_status=d.get("plan_status", ""),
                   start_state=dict(d.get("start_state", {})), start_robot_q=dict(d.get("start_robot_q", {})),
                   robust=d.get("robust"), reference_joint=d.get("reference_joint"),
                   nearest_miss=None if d.get("nearest_miss") is None else float(d["nearest_miss"]))


@dataclass(frozen=True)
class Certificate:
    """Certificates of every task of one run, with what they were judged by.

    ``cert.ok`` is True when every task is certified; ``cert["JOINT"]`` or ``cert.tasks[i]`` gives a task.
    """

    tasks: tuple[TaskCertificate, ...]
    scene: str
    against: str | None
    robot: str
    criteria: dict
    seeds: dict
    versions: dict
    timings: dict = field(default_factory=dict)
    #: movable joints of the scene that were not tested (``--all-movable``), by name, with why
    untested: dict = field(default_factory=dict)
    #: every file the certificate was judged on, by role ("scene", "against", "robot", "robot_spec",
    #: "scenario", ...): ``{"path": as given (relative to the certificate's folder if inside it),
    #: "sha256": hex digest of the content}``
    files: dict = field(default_factory=dict)
    #: the arm's joint impedance the run simulated, N*m/rad (N/m for a prismatic joint; None: held rigidly), by
    #: robot joint: robots that share one URDF (``--robot default`` and ``compliant``) differ here; empty: no joint
    #: stiffness given (an isotropic grasp spring, ``PhysicsConfig.grasp_stiffness``)
    robot_joint_stiffness: dict = field(default_factory=dict)
    path: Path | None = None

    @property
    def ok(self) -> bool:
        return bool(self.tasks) and all(t.ok for t in self.tasks)

    def __getitem__(self, key: int | str) -> TaskCertificate:
        if isinstance(key, int):
            return self.tasks[key]
        for t in self.tasks:
            if t.joint == key or f"{t.kind}:{t.joint}" == key:
                return t
        raise KeyError(f"certificate has no task for joint {key!r} (tasks: {[t.joint for t in self.tasks]})")

    @property
    def exit_code(self) -> int:
        """The run's exit code, :func:`scenes.outcome.exit_code` of the task statuses (0: all certified)."""
        return exit_code(t.status for t in self.tasks)

    def summary(self) -> str:
        """One line per task: status, joint, reason; then one per untested joint: ``untested``, joint, why."""
        lines = [f"{t.status.value:12s} {t.kind}:{t.joint}  {t.reason}" for t in self.tasks]
        lines += [f"{'untested':12s} {joint}  {why}" for joint, why in self.untested.items()]
        return "\n".join(lines)

    def summary_dict(self) -> dict:
        """The summary as JSON-ready data: ``ok``, ``exit_code``, the scene, reference and certificate path,
        per task its kind, joint, status, reason, amount and unit, and the untested joints with why."""
        return {"ok": self.ok, "exit_code": self.exit_code, "scene": self.scene, "against": self.against,
                "certificate": str(self.path) if self.path is not None else None,
                "tasks": [{"kind": t.kind, "joint": t.joint, "status": t.status.value, "reason": t.reason,
                           "amount": t.amount if math.isfinite(t.amount) else None, "unit": t.unit} for t in self.tasks],
                "untested": dict(self.untested)}

    def to_dict(self) -> dict:
        return {"format": CERTIFICATE_FORMAT, "ok": self.ok, "scene": self.scene, "against": self.against,
                "robot": self.robot, "criteria": dict(self.criteria), "seeds": dict(self.seeds),
                "versions": dict(self.versions), "timings": dict(self.timings),
                "untested": dict(self.untested), "files": {k: dict(v) for k, v in self.files.items()},
                "robot_joint_stiffness": dict(self.robot_joint_stiffness),
                "tasks": [t.to_dict() for t in self.tasks]}

    @classmethod
    def from_dict(cls, d: dict, path: Path | None = None) -> "Certificate":
        if d.get("format") not in READABLE_FORMATS:
            raise SimcheckInputError(f"{path or 'certificate'}: format {d.get('format')!r}, expected one of "
                                     f"{READABLE_FORMATS}")
        return cls(tasks=tuple(TaskCertificate.from_dict(t) for t in d["tasks"]), scene=d["scene"],
                   against=d.get("against"), robot=d.get("robot", ""), criteria=dict(d.get("criteria", {})),
                   seeds=dict(d.get("seeds", {})), versions=dict(d.get("versions", {})),
                   timings=dict(d.get("timings", {})), untested=dict(d.get("untested", {})),
                   files=dict(d.get("files", {})), robot_joint_stiffness=dict(d.get("robot_joint_stiffness", {})),
                   path=path)

    def write(self, out_dir: str | Path) -> Path:
        """Write ``certificate.json`` into ``out_dir`` atomically; returns its path."""
        return write_json_atomic(Path(out_dir) / "certificate.json", self.to_dict())

    @classmethod
    def load(cls, path: str | Path) -> "Certificate":
        path = Path(path)
        if path.is_dir():
            path = path / "certificate.json"
        try:
            return cls.from_dict(json.loads(path.read_text()), path)
        except (OSError, json.JSONDecodeError, KeyError, ValueError) as exc:
            raise SimcheckInputError(f"{path}: not a readable certificate ({exc})") from exc


def write_json_atomic(path: Path, doc: dict) -> Path:
    """Write ``doc`` as JSON to ``path`` through a temporary file in the same folder + rename."""
    return write_text_atomic(path, json.dumps(doc, indent=2, allow_nan=False) + "\n")


def software_versions() -> dict:
    """Versions of the software a certificate was judged with (package metadata; "missing" if absent)."""
    return dict(_software_versions())


@functools.lru_cache(maxsize=1)
def _software_versions() -> dict:
    """:func:`software_versions`, read once per process (each metadata look-up scans site-packages: ~2 ms)."""
    from importlib.metadata import PackageNotFoundError, version
    out = {}
    for key, dist in (("pybullet", "pybullet"), ("pinocchio", "pin"), ("ompl", "ompl"), ("numpy", "numpy"),
                      ("partscene", "partscene")):
        try:
            out[key] = version(dist)
        except PackageNotFoundError:
            out[key] = "missing"
    import sys
    out["python"] = sys.version.split()[0]
    return out
