"""``python -m simcheck.demo --out out/demo``: the whole story on the built-in kitchen, end to end.

Stages (each logged on stderr with its time, each recorded in ``OUT/demo.json``)::

    scene        scenes.make_scene("kitchen", seed, preset="realistic")  -> OUT/truth/{truth.urdf, truth.json, scan.*}
    reconstruct  recon.write_reconstruction(recon.reconstruct(scan, labels), OUT) -> OUT/scene.urdf, graph.json
    metrics      recon.metrics against truth.json                          -> OUT/metrics.json
    tasks        open-drawer / open-door tasks picked from the truth, present in the reconstruction
    certify      simcheck.certify(scene.urdf, tasks, against=truth.urdf)  -> OUT/certificate.json, OUT/rollouts/
    report       simcheck.report.render_report(OUT)                        -> OUT/report.html

A stage whose package API is not there (yet) is recorded as ``unavailable`` and names what is
missing; the stages that need its output are ``skipped``. Nothing is made up: the report shows only
what the stages wrote. The report is always rendered from whatever exists.

Exit codes: 0 = every stage ran (whatever the certificate says: a task that failed certification is a
result, shown in the report and on stdout); 1 = a stage failed or was unavailable; 2 = bad arguments
(e.g. a scene that is not built in).
"""

from __future__ import annotations

import argparse
import dataclasses
import enum
import json
import logging
import os
import sys
import time
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from scenes.description import read_truth_doc, write_text_atomic
from scenes.outcome import Outcome
from simcheck.report import DemoLayout, render_report

__all__ = ["DemoConfig", "StageStatus", "StageRecord", "DemoResult", "TaskChoice", "choose_tasks", "usable_tasks",
           "metrics_doc", "run_demo", "main"]

log = logging.getLogger("simcheck.demo")


@dataclass(frozen=True)
class DemoConfig:
    """What the demo builds and how much it certifies.

    scene / seed / preset: the built-in scene, its seed and the scanner preset.
    max_drawers / max_doors: at most this many drawer / door tasks are certified (the demo must stay
        within a few minutes on 2 cores: each task is one OMPL plan + one physics rollout).
    """

    scene: str = "kitchen"
    seed: int = 0
    preset: str = "realistic"
    max_drawers: int = 3
    max_doors: int = 3


class StageStatus(enum.Enum):
    OK = "ok"
    FAILED = "failed"            # the stage ran and raised: a bug or a bad input (message says which)
    UNAVAILABLE = "unavailable"  # the package API this stage calls does not exist yet
    SKIPPED = "skipped"          # an earlier stage it needs did not produce its output


@dataclass
class StageRecord:
    """One row of demo.json: ``name``, ``status``, wall-clock ``seconds`` and a human ``message``."""

    name: str
    status: StageStatus
    seconds: float
    message: str

    def to_json(self) -> dict:
        return {"name": self.name, "status": self.status.value, "seconds": round(self.seconds, 3),
                "message": self.message}


#: Packages whose exceptions are expected, self-explaining failures (no traceback in the log).
_PROJECT_PACKAGES = ("scenes", "recon", "planners", "simcheck")


class StageUnavailable(Exception):
    """Raised by a stage when the API it needs is not importable (the message names it)."""


def _api(module: str, attr: str):
    """``module.attr`` or :class:`StageUnavailable` naming what is missing."""
    import importlib
    try:
        mod = importlib.import_module(module)
        return getattr(mod, attr)
    except (ImportError, AttributeError) as exc:
        raise StageUnavailable(f"{module}.{attr} is not available yet ({exc})") from exc


def _write_json_atomic(path: Path, doc: dict) -> None:
    write_text_atomic(path, json.dumps(doc, indent=2) + "\n")


# ------------------------------------------------------------------------------------------ tasks
@dataclass(frozen=True)
class TaskChoice:
    """The tasks to certify, ``(kind, joint name)`` with kind "open-drawer" / "open-door", and why
    some candidates were left out (``reason``, empty when none were)."""

    tasks: tuple[tuple[str, str], ...]
    reason: str


#: Order in which objects contribute door tasks (one door per object per round).
_DOOR_CATEGORY_ORDER = ("cabinet", "microwave", "refrigerator")


def choose_tasks(truth: dict, graph: dict, max_drawers: int, max_doors: int) -> TaskChoice:
    """Drawer and door tasks of the truth whose joint (same URDF name) the reconstruction made movable.

    Drawers: prismatic truth joints whose child part is a ``drawer``, cabinets first, at most
    ``max_drawers``. Doors: revolute truth joints whose child is a ``door``, taken round-robin over
    cabinet, microwave, refrigerator (one per object per round), at most ``max_doors``.
    """
    movable_est = {j.get("name"): j.get("type") for o in graph.get("objects", []) for j in o.get("joints", [])
                   if j.get("type") in ("prismatic", "revolute")}
    drawers: list[tuple[bool, str]] = []  # (not a cabinet, joint name): cabinets sort first
    doors_by_object: dict[str, list[str]] = {}
    category_of: dict[str, str] = {}
    left_out: list[str] = []
    for obj in truth.get("objects", []):
        label_of = {p["id"]: p.get("label") for p in obj.get("parts", [])}
        for j in obj.get("joints", []):
            label = label_of.get(j.get("child_part_id"))
            kind = ("drawer" if j.get("type") == "prismatic" and label == "drawer" else
                    "door" if j.get("type") == "revolute" and label == "door" else None)
            if kind is None:
                continue
            if j["name"] not in movable_est:
                left_out.append(f"{j['name']} (not movable in the reconstruction)")
                continue
            if kind == "drawer":
                drawers.append((obj.get("category") != "cabinet", j["name"]))
            else:
                doors_by_object.setdefault(obj["name"], []).append(j["name"])
                category_of[obj["name"]] = str(obj.get("category"))
    rank = {c: i for i, c in enumerate(_DOOR_CATEGORY_ORDER)}
    objects = sorted(doors_by_object, key=lambda n: (rank.get(category_of[n], len(rank)), n))
    doors: list[str] = []
    while len(doors) < max_doors and any(doors_by_object[n] for n in objects):
        for n in objects:
            if doors_by_object[n] and len(doors) < max_doors:
                doors.append(doors_by_object[n].pop(0))
    tasks = tuple(("open-drawer", j) for _, j in sorted(drawers)[:max_drawers]) + tuple(("open-door", j) for j in doors)
    return TaskChoice(tasks, "; ".join(left_out))


# ------------------------------------------------------------------------------------------ stages
def _stage_scene(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    make_scene = _api("scenes", "make_scene")
    make_scene(cfg.scene, seed=cfg.seed, preset=cfg.preset, out=lay.truth_dir)
    truth = read_truth_doc(lay.truth_json)
    n_parts = sum(len(o.get("parts", [])) for o in truth.get("objects", []))
    return f"{cfg.scene} seed {cfg.seed}: {len(truth.get('objects', []))} objects, {n_parts} parts; " \
           f"scanned with preset {cfg.preset!r}"


def _stage_reconstruct(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    reconstruct = _api("recon", "reconstruct")
    write_reconstruction = _api("recon", "write_reconstruction")
    rec = reconstruct(lay.scan_ply, lay.labels_json, seed=cfg.seed)
    write_reconstruction(rec, lay.root)
    state["reconstruction"] = rec
    n_joints = sum(1 for o in rec.objects for j in o.joints if str(getattr(j.type, "value", j.type)) != "fixed")
    n_warn = len(getattr(rec, "warnings", ()))
    return f"{len(rec.objects)} objects, {n_joints} movable joints estimated, {n_warn} warnings"


def _finite_or_none(x: float) -> float | None:
    """JSON has no NaN: an undefined metric is written as null (shown as "–")."""
    return float(x) if x is not None and np.isfinite(x) else None


def metrics_doc(scene_metrics, summary) -> dict:
    """``metrics.json`` (format ``partscene.metrics/1``) from ``recon.metrics`` results.

    ``summary``: scene means (Chamfer in the unit box, voxel IoU, kinematic mAP over objects) and the
    pooled joint summary; ``objects``: one row per true object; ``joints``: one row per true movable joint.
    """
    from recon.metrics import mean_average_precision

    objs = scene_metrics.objects
    doc = {"format": "partscene.metrics/1", "scene": scene_metrics.scene,
           "summary": {"chamfer": _finite_or_none(scene_metrics.chamfer), "iou": _finite_or_none(scene_metrics.iou),
                       "kinematic_map": _finite_or_none(mean_average_precision(o.ap for o in objs)),
                       "missing_objects": int(scene_metrics.missing)},
           "objects": [], "joints": []}
    for field_name, value in dataclasses.asdict(summary).items():
        doc["summary"][field_name] = value if isinstance(value, int) else _finite_or_none(value)
    for o in objs:
        doc["objects"].append({"name": o.name, "category": o.category, "status": o.status.value,
                               "chamfer": _finite_or_none(o.chamfer), "iou": _finite_or_none(o.iou),
                               "ap": _finite_or_none(o.ap)})
        for j in o.joints:
            if j.true_type == "fixed":
                continue
            doc["joints"].append({"name": j.name, "true_type": j.true_type, "est_type": j.est_type,
                                  "match": j.match.value, "axis_error_deg": _finite_or_none(j.axis_error_deg),
                                  "hinge_distance_m": _finite_or_none(j.hinge_distance_m),
                                  "upper_error": _finite_or_none(j.upper_error)})
    return doc


def _stage_metrics(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    read_truth = _api("recon.metrics", "read_truth")
    estimate_from_reconstruction = _api("recon.metrics", "estimate_from_reconstruction")
    evaluate_scene = _api("recon.metrics", "evaluate_scene")
    joint_summary = _api("recon.metrics", "joint_summary")
    metrics_config = _api("recon.metrics", "MetricsConfig")
    truth = read_truth(lay.truth_json)
    rec = state["reconstruction"]
    estimates = [estimate_from_reconstruction(o, rec.config) for o in rec.objects]
    scene_metrics = evaluate_scene(truth, estimates, metrics_config(seed=cfg.seed))
    summary = joint_summary([c for o in scene_metrics.objects for c in o.joints])
    doc = metrics_doc(scene_metrics, summary)
    _write_json_atomic(lay.metrics_json, doc)
    s = doc["summary"]

    def g(x):
        return "n/a" if x is None else f"{x:.3g}"
    return (f"Chamfer {g(s['chamfer'])}, IoU {g(s['iou'])}, kinematic mAP {g(s['kinematic_map'])}, "
            f"joint type accuracy {g(s.get('type_accuracy'))}")


def usable_tasks(choice: TaskChoice, scene_urdf: Path) -> TaskChoice:
    """``choice`` without the tasks simcheck would reject as input on ``scene_urdf`` (a joint with no
    opening range, or of the wrong type for the task), each named with simcheck's reason in ``reason``."""
    parse_task = _api("planners.task", "parse_task")
    check_task = _api("planners.task", "check_task")
    read_scene_joints = _api("simcheck.scene_joints", "read_scene_joints")
    input_error = _api("planners.errors", "TaskSpecError")
    joints = read_scene_joints(scene_urdf)
    kept, left_out = [], [choice.reason] if choice.reason else []
    for kind, joint in choice.tasks:
        try:
            check_task(parse_task(f"{kind}:{joint}"), joints, scene_urdf)
            kept.append((kind, joint))
        except input_error as exc:
            left_out.append(f"{joint} (rejected: {exc})")
    return TaskChoice(tuple(kept), "; ".join(left_out))


def _stage_tasks(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    truth = read_truth_doc(lay.truth_json)
    graph = json.loads(lay.graph_json.read_text())
    choice = usable_tasks(choose_tasks(truth, graph, cfg.max_drawers, cfg.max_doors), lay.scene_urdf)
    state["tasks"] = choice
    if not choice.tasks:
        raise RuntimeError(f"no drawer or door of {lay.truth_json} can be certified on {lay.scene_urdf}: "
                           f"{choice.reason}")
    return "; ".join(f"{kind}:{joint}" for kind, joint in choice.tasks) + (
        f" -- left out: {choice.reason}" if choice.reason else "")


def _stage_certify(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    certify = _api("simcheck", "certify")
    choice: TaskChoice = state["tasks"]
    cert = certify(lay.scene_urdf, [f"{kind}:{joint}" for kind, joint in choice.tasks], against=lay.truth_urdf,
                   out=lay.root, seed=cfg.seed)
    state["certificate"] = cert
    doc = json.loads(lay.certificate_json.read_text())
    n_ok = sum(1 for t in doc.get("tasks", []) if t.get("status") == Outcome.CERTIFIED)
    return f"{n_ok} of {len(doc.get('tasks', []))} tasks certified"


def _stage_report(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    path = render_report(lay.root)
    return f"{path} ({path.stat().st_size / 1e3:.0f} kB)"


#: (name, function, names of the stages whose output it needs)
STAGES: tuple[tuple[str, Callable[[DemoConfig, DemoLayout, dict], str], tuple[str, ...]], ...] = (
    ("scene", _stage_scene, ()),
    ("reconstruct", _stage_reconstruct, ("scene",)),
    ("metrics", _stage_metrics, ("scene", "reconstruct")),
    ("tasks", _stage_tasks, ("scene", "reconstruct")),
    ("certify", _stage_certify, ("tasks",)),
    ("report", _stage_report, ()),
)


@dataclass
class DemoResult:
    """What :func:`run_demo` did: one record per stage, the report path and the certificate (if any)."""

    out: Path
    stages: list[StageRecord] = field(default_factory=list)

    @property
    def complete(self) -> bool:
        return all(s.status is StageStatus.OK for s in self.stages)


def run_demo(out: str | os.PathLike, config: DemoConfig = DemoConfig()) -> DemoResult:
    """Run every stage into ``out`` (created), logging progress; never raises for a stage's failure."""
    lay = DemoLayout(Path(out))
    lay.root.mkdir(parents=True, exist_ok=True)
    result = DemoResult(lay.root)
    state: dict = {}
    done: set[str] = set()
    t_start = time.perf_counter()
    for name, func, needs in STAGES:
        missing = [n for n in needs if n not in done]
        if missing:
            rec = StageRecord(name, StageStatus.SKIPPED, 0.0, f"needs the output of: {', '.join(missing)}")
            log.warning("[%s] skipped: %s", name, rec.message)
        else:
            log.info("[%s] ...", name)
            t0 = time.perf_counter()
            try:
                msg = func(config, lay, state)
                rec = StageRecord(name, StageStatus.OK, time.perf_counter() - t0, msg)
                done.add(name)
                log.info("[%s] ok in %.1f s: %s", name, rec.seconds, msg)
            except StageUnavailable as exc:
                rec = StageRecord(name, StageStatus.UNAVAILABLE, time.perf_counter() - t0, str(exc))
                log.warning("[%s] NOT AVAILABLE: %s", name, exc)
            except Exception as exc:  # noqa: BLE001 -- a stage's bug is reported, the rest still runs
                rec = StageRecord(name, StageStatus.FAILED, time.perf_counter() - t0,
                                  f"{type(exc).__name__}: {exc}")
                # a project error names what was wrong; anything else is a bug: show where it happened
                ours = type(exc).__module__.split(".")[0] in _PROJECT_PACKAGES
                log.error("[%s] FAILED after %.1f s: %s%s", name, rec.seconds, rec.message,
                          "" if ours else "\n" + traceback.format_exc())
        result.stages.append(rec)
        _write_json_atomic(lay.demo_json, {"format": "partscene.demo/1", "config": config.__dict__,
                                           "seconds": round(time.perf_counter() - t_start, 3),
                                           "stages": [s.to_json() for s in result.stages]})
    return result


def _task_lines(lay: DemoLayout) -> list[str]:
    if not lay.certificate_json.exists():
        return []
    doc = json.loads(lay.certificate_json.read_text())
    lines = []
    for t in doc.get("tasks", []):
        reason = str(t.get("reason", ""))
        if len(reason) > _REASON_CHARS:
            reason = reason[:_REASON_CHARS - 3] + "..."
        lines.append(f"  {t.get('status', '?'):<12} {t.get('kind', t.get('task', ''))}:{t.get('joint', '?')}"
                     f"  {reason}")
    return lines


#: A task's reason is cut to this many characters on stdout (report.html and certificate.json have it all).
_REASON_CHARS = 160


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m simcheck.demo",
                                description="Make, scan, reconstruct and certify a built-in scene; write report.html.")
    p.add_argument("--out", default="out/demo", help="output directory (default: out/demo)")
    p.add_argument("--scene", default=DemoConfig.scene, help="built-in scene (default: kitchen)")
    p.add_argument("--seed", type=int, default=DemoConfig.seed, help="scene, scan, recon and planning seed")
    p.add_argument("--preset", default=DemoConfig.preset, help="scanner preset (default: realistic)")
    p.add_argument("--max-drawers", type=int, default=DemoConfig.max_drawers, help="at most this many drawer tasks")
    p.add_argument("--max-doors", type=int, default=DemoConfig.max_doors, help="at most this many door tasks")
    p.add_argument("-v", "--verbose", action="store_true", help="debug logging")
    p.add_argument("-q", "--quiet", action="store_true", help="warnings only")
    args = p.parse_args(argv)
    try:
        from scenes import list_scenes
    except ImportError:
        list_scenes = None
    if list_scenes is not None and args.scene not in list_scenes():
        p.error(f"unknown scene {args.scene!r}; built-in scenes: {', '.join(list_scenes())}")
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.WARNING if args.quiet else logging.INFO,
                        format="%(asctime)s %(name)s: %(message)s", datefmt="%H:%M:%S", stream=sys.stderr)
    if not args.verbose:
        for noisy in ("matplotlib", "PIL", "trimesh"):
            logging.getLogger(noisy).setLevel(logging.WARNING)
    cfg = DemoConfig(args.scene, args.seed, args.preset, args.max_drawers, args.max_doors)
    result = run_demo(args.out, cfg)
    lay = DemoLayout(Path(args.out))
    total = sum(s.seconds for s in result.stages)
    tasks = _task_lines(lay)
    print(f"partscene demo: {cfg.scene} seed {cfg.seed}, {total:.0f} s, {len(tasks)} tasks:")
    for line in tasks:
        print(line)
    for s in result.stages:
        if s.status is not StageStatus.OK:
            print(f"  stage {s.name}: {s.status.value}: {s.message}")
    print(f"report: {lay.report_html.resolve()}")
    return 0 if result.complete else 1


if __name__ == "__main__":
    sys.exit(main())
