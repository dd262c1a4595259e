"""The certificate: per task a status, a reason and every criterion; plus criteria version, seeds,
software versions and timings. Written as ``certificate.json`` (atomically) and read back.

``certificate.json`` (format ``partscene.certificate/1``)::

    {"format": "partscene.certificate/1", "ok": false,
     "scene": "scene.urdf", "against": "truth.urdf" | null, "robot": "robot.urdf",
     "criteria": {"name": "partscene-default", "version": "1.0", ...thresholds...},
     "seeds": {"seed": 0}, "versions": {"pybullet": ..., "pinocchio": ..., "ompl": ..., "numpy": ..., "partscene": ...},
     "timings": {"total": s},
     "tasks": [{"kind": "open-drawer", "joint": "...", "status": "certified" | "failed" | "not-planned",
                "reason": "...", "amount": 0.31, "unit": "m", "seed": 0, "rollout": "rollouts/<joint>.npz",
                "images": ["images/<joint>_start.png", ...], "timings": {"plan": s, "recheck": s, "execute": s},
                "criteria": [{"name", "value", "threshold", "comparison", "unit", "passed", "margin",
                              "description", "detail"}, ...]}]}
"""

from __future__ import annotations

import enum
import json
from dataclasses import dataclass, field
from pathlib import Path

from scenes.atomic_write import write_text_atomic
from simcheck.criteria import CriterionResult
from simcheck.errors import SimcheckInputError

__all__ = ["TaskStatus", "TaskCertificate", "Certificate", "CERTIFICATE_FORMAT", "software_versions",
           "write_json_atomic"]

CERTIFICATE_FORMAT = "partscene.certificate/1"


class TaskStatus(enum.Enum):
    """Outcome of one task."""

    CERTIFIED = "certified"
    FAILED = "failed"
    NOT_PLANNED = "not-planned"


@dataclass(frozen=True)
class TaskCertificate:
    """The certificate of one task.

    Attributes:
        kind: "open-drawer" or "open-door".
        joint: the task joint (URDF name).
        status: certified / failed / not-planned.
        reason: why (names the failed criteria, the joint and links involved, and with ``--against``
            how the estimate differs from the reference).
        amount: the requested opening, rad or m (``unit``).
        criteria: every criterion judged.
        seed: the planning seed.
        timings: seconds by stage ("plan", "recheck", "execute", "total").
        rollout: path of the saved rollout, relative to the certificate's folder ("" if not executed).
        images: key-frame PNG paths, relative to the certificate's folder.
        plan_status: the planner's status name ("OK", "NO_STAND_POSE", ...).
        input_problem: True when the task failed because its input was unusable (e.g. the object is
            unreachable): the CLI then exits with code 2.
        start_state: values of the executed scene's movable joints when the task started (a scenario
            carries them over from the previous task), rad or m by joint name.
    """

    kind: str
    joint: str
    status: TaskStatus
    reason: str
    amount: float
    unit: str
    criteria: tuple[CriterionResult, ...] = ()
    seed: int = 0
    timings: dict = field(default_factory=dict)
    rollout: str = ""
    images: tuple[str, ...] = ()
    plan_status: str = ""
    input_problem: bool = False
    start_state: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return self.status is TaskStatus.CERTIFIED

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
                "input_problem": self.input_problem, "start_state": dict(self.start_state),
                "timings": dict(self.timings), "rollout": self.rollout,
                "images": list(self.images), "criteria": [c.to_dict() for c in self.criteria]}

    @classmethod
    def from_dict(cls, d: dict) -> "TaskCertificate":
        return cls(kind=d["kind"], joint=d["joint"], status=TaskStatus(d["status"]), reason=d["reason"],
                   amount=float(d["amount"]) if d.get("amount") is not None else float("nan"), unit=d.get("unit", ""),
                   criteria=tuple(CriterionResult.from_dict(c) for c in d.get("criteria", [])),
                   seed=int(d.get("seed", 0)), timings=dict(d.get("timings", {})), rollout=d.get("rollout", ""),
                   images=tuple(d.get("images", [])), plan_status=d.get("plan_status", ""),
                   input_problem=bool(d.get("input_problem", False)), start_state=dict(d.get("start_state", {})))


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
        """0: every task certified; 1: some task failed certification; 2: some task's input was unusable."""
        if any(t.input_problem for t in self.tasks):
            return 2
        return 0 if self.ok else 1

    def summary(self) -> str:
        """One line per task: status, joint, reason."""
        return "\n".join(f"{t.status.value:12s} {t.kind}:{t.joint}  {t.reason}" for t in self.tasks)

    def to_dict(self) -> dict:
        return {"format": CERTIFICATE_FORMAT, "ok": self.ok, "scene": self.scene, "against": self.against,
                "robot": self.robot, "criteria": dict(self.criteria), "seeds": dict(self.seeds),
                "versions": dict(self.versions), "timings": dict(self.timings),
                "tasks": [t.to_dict() for t in self.tasks]}

    @classmethod
    def from_dict(cls, d: dict, path: Path | None = None) -> "Certificate":
        if d.get("format") != CERTIFICATE_FORMAT:
            raise SimcheckInputError(f"{path or 'certificate'}: format {d.get('format')!r}, expected {CERTIFICATE_FORMAT!r}")
        return cls(tasks=tuple(TaskCertificate.from_dict(t) for t in d["tasks"]), scene=d["scene"],
                   against=d.get("against"), robot=d.get("robot", ""), criteria=dict(d.get("criteria", {})),
                   seeds=dict(d.get("seeds", {})), versions=dict(d.get("versions", {})),
                   timings=dict(d.get("timings", {})), path=path)

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
        except (OSError, json.JSONDecodeError, KeyError) as exc:
            raise SimcheckInputError(f"{path}: not a readable certificate ({exc})") from exc


def write_json_atomic(path: Path, doc: dict) -> Path:
    """Write ``doc`` as JSON to ``path`` through a temporary file in the same folder + rename."""
    return write_text_atomic(path, json.dumps(doc, indent=2, allow_nan=False) + "\n")


def software_versions() -> dict:
    """Versions of the software a certificate was judged with (package metadata; "missing" if absent)."""
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
