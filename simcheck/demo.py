"""``python -m simcheck.demo --out out/demo``: the whole story on the built-in kitchen, end to end.

Stages (each logged on stderr with its time, each recorded in ``OUT/demo.json``)::

    scene        scenes.make_scene("kitchen", seed, preset="realistic")  -> OUT/truth/{truth.urdf, truth.json, scan.*}
    reconstruct  recon.write_reconstruction(recon.reconstruct(scan, labels), OUT) -> OUT/scene.urdf, graph.json
    metrics      recon.metrics.reconstruction_metrics_doc against truth.json -> OUT/metrics.json
    tasks        drawers and doors of the truth (scenes.openings) usable on scene.urdf (planners.check_task)
    certify      simcheck.certify(scene.urdf, tasks, against=truth.urdf)  -> OUT/certificate.json, OUT/rollouts/
    report       simcheck.report.render_report(OUT)                        -> OUT/report.html

A stage that fails is recorded as ``failed`` with its error, and the stages that need its output as
``skipped``; the report is always rendered from whatever exists. Nothing is made up: the report shows
only what the stages wrote.

Exit code (:func:`scenes.outcome.exit_code`): over the certified tasks' outcomes, plus ``unusable`` for a
stage that failed with a partscene error (it names the input that was wrong, as the packages' command
lines treat it) and ``error`` for one that failed otherwise (a bug; its traceback is logged): 0 when every task is
certified, 2 on unusable input (also bad arguments, e.g. a scene that is not built in, or an ``--out``
holding something else: :mod:`scenes.output_folder`), 3 on an internal error, 130 interrupted, otherwise 1.
``--out`` is written as a whole (a temporary folder renamed into place).
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

from scenes.command_line import add_output_arguments
from scenes.description import InputError, PartsceneError, write_text_atomic
from scenes.outcome import Outcome, exit_code
from simcheck.report import DemoLayout, render_report

__all__ = ["DemoConfig", "StageStatus", "StageRecord", "DemoResult", "TaskChoice", "choose_tasks", "usable_openings",
           "untested_joints", "run_demo", "main"]

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
    """What became of one stage of the demo."""

    OK = "ok"
    FAILED = "failed"            # the stage ran and raised: a bug or a bad input (message says which)
    SKIPPED = "skipped"          # an earlier stage it needs did not produce its output


@dataclass
class StageRecord:
    """One row of demo.json: ``name``, ``status``, wall-clock ``seconds``, a human ``message`` and, for a
    failed stage, the task ``outcome`` the failure stands for (unusable input or an internal error)."""

    name: str
    status: StageStatus
    seconds: float
    message: str
    outcome: Outcome | None = None

    def to_json(self) -> dict:
        return {"name": self.name, "status": self.status.value, "seconds": round(self.seconds, 3),
                "message": self.message}


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


def choose_tasks(openings, max_drawers: int, max_doors: int, reason: str = "") -> TaskChoice:
    """A small, varied set of drawers and doors (:class:`scenes.openings.Opening`, in scene order), with
    ``reason`` saying which were left out before.

    Drawers: cabinets first, at most ``max_drawers``. Doors: taken round-robin over cabinet, microwave,
    refrigerator (one per object per round), at most ``max_doors``.
    """
    drawers = sorted((o.category != "cabinet", o.joint) for o in openings if o.kind == "drawer")
    doors_by_object: dict[str, list[str]] = {}
    category_of: dict[str, str] = {}
    for o in openings:
        if o.kind == "door":
            doors_by_object.setdefault(o.object, []).append(o.joint)
            category_of[o.object] = o.category
    rank = {c: i for i, c in enumerate(_DOOR_CATEGORY_ORDER)}
    objects = sorted(doors_by_object, key=lambda n: (rank.get(category_of[n], len(rank)), n))
    doors: list[str] = []
    while len(doors) < max_doors and any(doors_by_object[n] for n in objects):
        for n in objects:
            if doors_by_object[n] and len(doors) < max_doors:
                doors.append(doors_by_object[n].pop(0))
    tasks = tuple(("open-drawer", j) for _, j in drawers[:max_drawers]) + tuple(("open-door", j) for j in doors)
    return TaskChoice(tasks, reason)


def usable_openings(openings, scene_urdf: Path) -> tuple[tuple, str]:
    """The ``openings`` whose task simcheck accepts as input on ``scene_urdf``, and why the others were
    left out (a joint the reconstruction left fixed or missing, with no opening range, or of the wrong
    type: :func:`planners.task.check_task`'s reason, joined by "; ")."""
    from planners.errors import TaskSpecError
    from planners.task import check_task, parse_task
    from simcheck.scene_joints import read_scene_joints

    joints = read_scene_joints(scene_urdf)
    kept, left_out = [], []
    for o in openings:
        try:
            check_task(parse_task(o.task), joints, scene_urdf)
            kept.append(o)
        except TaskSpecError as exc:
            left_out.append(f"{o.joint} (rejected: {exc})")
    return tuple(kept), "; ".join(left_out)


def untested_joints(scene, scene_urdf: Path, choice: TaskChoice, cfg: DemoConfig) -> dict[str, str]:
    """Every movable joint the demo did not certify, with why: the truth's drawers and doors that were
    rejected on ``scene_urdf`` (:func:`planners.task.check_task`'s reason) or beyond ``cfg``'s caps, then
    the movable joints of ``scene_urdf`` that no drawer or door of the truth names."""
    from planners.errors import TaskSpecError
    from planners.task import check_task, parse_task
    from scenes.openings import openings
    from simcheck.scene_joints import read_scene_joints

    joints = read_scene_joints(scene_urdf)
    tasked = {joint for _, joint in choice.tasks}
    untested: dict[str, str] = {}
    for o in openings(scene):
        if o.joint in tasked:
            continue
        try:
            check_task(parse_task(o.task), joints, scene_urdf)
            cap = cfg.max_drawers if o.kind == "drawer" else cfg.max_doors
            untested[o.joint] = f"the demo certifies at most {cap} {o.kind}s"
        except TaskSpecError as exc:
            untested[o.joint] = f"rejected: {exc}"
    for name, j in joints.items():
        if j.type in ("prismatic", "revolute", "continuous") and name not in tasked and name not in untested:
            untested[name] = "movable in the reconstruction, but no drawer or door of the truth has this name"
    return untested


# ------------------------------------------------------------------------------------------ stages
def _stage_scene(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    from scenes import make_scene

    made = make_scene(cfg.scene, seed=cfg.seed, preset=cfg.preset, out=lay.truth_dir)
    state["scene"] = made.scene
    n_parts = sum(len(o.parts) for o in made.scene.objects)
    return f"{cfg.scene} seed {cfg.seed}: {len(made.scene.objects)} objects, {n_parts} parts; " \
           f"scanned with preset {cfg.preset!r}"


def _stage_reconstruct(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    from recon import reconstruct, write_reconstruction
    from recon.model import JointType

    rec = reconstruct(lay.scan_ply, lay.labels_json, seed=cfg.seed)
    write_reconstruction(rec, lay.root)
    state["reconstruction"] = rec
    n_joints = sum(1 for o in rec.objects for j in o.joints if j.type is not JointType.FIXED)
    return f"{len(rec.objects)} objects, {n_joints} movable joints estimated, {len(rec.warnings)} warnings"


def _stage_metrics(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    from recon.metrics import MetricsConfig, read_truth, reconstruction_metrics_doc, write_metrics_json

    doc = reconstruction_metrics_doc(read_truth(lay.truth_json), state["reconstruction"], MetricsConfig(seed=cfg.seed))
    write_metrics_json(doc, lay.metrics_json)
    s = doc["summary"]

    def g(x):
        return "n/a" if x is None else f"{x:.3g}"
    return (f"Chamfer {g(s['chamfer'])}, IoU {g(s['iou'])}, kinematic mAP {g(s['kinematic_map'])}, "
            f"joint type accuracy {g(s.get('type_accuracy'))}")


def _stage_tasks(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    from scenes.openings import openings

    usable, left_out = usable_openings(openings(state["scene"]), lay.scene_urdf)
    choice = choose_tasks(usable, cfg.max_drawers, cfg.max_doors, left_out)
    state["tasks"] = choice
    if not choice.tasks:
        raise InputError(f"no drawer or door of {lay.truth_json} can be certified on {lay.scene_urdf}: "
                           f"{choice.reason}")
    return "; ".join(f"{kind}:{joint}" for kind, joint in choice.tasks) + (
        f" -- left out: {choice.reason}" if choice.reason else "")


def _stage_certify(cfg: DemoConfig, lay: DemoLayout, state: dict) -> str:
    from simcheck.certification import certify

    choice: TaskChoice = state["tasks"]
    cert = certify(lay.scene_urdf, [f"{kind}:{joint}" for kind, joint in choice.tasks], against=lay.truth_urdf,
                   out=lay.root, seed=cfg.seed)
    untested = untested_joints(state["scene"], lay.scene_urdf, choice, cfg)
    if untested:
        cert = dataclasses.replace(cert, untested=untested)
        cert.write(lay.root)
    state["certificate"] = cert
    n_ok = sum(1 for t in cert.tasks if t.status is Outcome.CERTIFIED)
    return f"{n_ok} of {len(cert.tasks)} tasks certified"


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
    """What :func:`run_demo` did: one record per stage, and the certificate (:class:`simcheck.Certificate`,
    ``None`` when the certify stage did not run)."""

    out: Path
    stages: list[StageRecord] = field(default_factory=list)
    certificate: object | None = None

    @property
    def complete(self) -> bool:
        """Every stage ran."""
        return all(s.status is StageStatus.OK for s in self.stages)

    @property
    def outcomes(self) -> list[Outcome]:
        """The certified tasks' outcomes, and the outcome each failed stage stands for."""
        tasks = [t.status for t in self.certificate.tasks] if self.certificate is not None else []
        return tasks + [s.outcome for s in self.stages if s.outcome is not None]

    @property
    def exit_code(self) -> int:
        """The run's exit code (:func:`scenes.outcome.exit_code` of :attr:`outcomes`)."""
        return exit_code(self.outcomes)


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
            except Exception as exc:  # noqa: BLE001 -- a stage's failure is reported, the rest still runs
                # a partscene error names the input that was wrong (as the packages' command lines treat
                # it: unusable); anything else is a bug: show where it happened
                unusable = isinstance(exc, PartsceneError)
                rec = StageRecord(name, StageStatus.FAILED, time.perf_counter() - t0, f"{type(exc).__name__}: {exc}",
                                  Outcome.UNUSABLE if unusable else Outcome.ERROR)
                log.error("[%s] FAILED after %.1f s: %s%s", name, rec.seconds, rec.message,
                          "" if unusable else "\n" + traceback.format_exc())
        result.stages.append(rec)
        result.certificate = state.get("certificate")
        _write_json_atomic(lay.demo_json, {"format": "partscene.demo/1", "config": config.__dict__,
                                           "seconds": round(time.perf_counter() - t_start, 3),
                                           "stages": [s.to_json() for s in result.stages]})
    return result


def _task_lines(cert) -> list[str]:
    """One line per task of certificate ``cert`` (none when there is none): outcome, task, reason (cut)."""
    lines = []
    for t in cert.tasks if cert is not None else ():
        reason = t.reason if len(t.reason) <= _REASON_CHARS else t.reason[:_REASON_CHARS - 3] + "..."
        lines.append(f"  {t.status.value:<12} {t.kind}:{t.joint}  {reason}")
    return lines


#: A task's reason is cut to this many characters on stdout (report.html and certificate.json have it all).
_REASON_CHARS = 160


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m simcheck.demo",
                                description="Make, scan, reconstruct and certify a built-in scene; write report.html.")
    add_output_arguments(p, "truth/, scene.urdf, graph.json, metrics.json, certificate.json, rollouts/, report.html",
                         default="out/demo")
    p.add_argument("--scene", default=DemoConfig.scene, help="built-in scene (default: kitchen)")
    p.add_argument("--seed", type=int, default=DemoConfig.seed, help="scene, scan, recon and planning seed")
    p.add_argument("--preset", default=DemoConfig.preset, help="scanner preset (default: realistic)")
    p.add_argument("--max-drawers", type=int, default=DemoConfig.max_drawers, help="at most this many drawer tasks")
    p.add_argument("--max-doors", type=int, default=DemoConfig.max_doors, help="at most this many door tasks")
    p.add_argument("-v", "--verbose", action="store_true", help="debug logging")
    p.add_argument("-q", "--quiet", action="store_true", help="warnings only")
    args = p.parse_args(argv)
    from scenes import list_scenes

    if args.scene not in list_scenes():
        p.error(f"unknown scene {args.scene!r}; built-in scenes: {', '.join(list_scenes())}")
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.WARNING if args.quiet else logging.INFO,
                        format="%(asctime)s %(name)s: %(message)s", datefmt="%H:%M:%S", stream=sys.stderr)
    if not args.verbose:
        for noisy in ("matplotlib", "PIL", "trimesh"):
            logging.getLogger(noisy).setLevel(logging.WARNING)
    cfg = DemoConfig(args.scene, args.seed, args.preset, args.max_drawers, args.max_doors)
    from scenes.outcome import interrupted
    from scenes.output_folder import output_folder
    try:
        with output_folder(args.out, "simcheck demo", inputs={}, settings=dataclasses.asdict(cfg),
                           overwrite=args.overwrite, verdict="certificate.json") as staging:
            result = run_demo(staging, cfg)
    except InputError as exc:
        print(f"simcheck demo: error: {exc}", file=sys.stderr)
        return exit_code([Outcome.UNUSABLE])
    except KeyboardInterrupt:
        return interrupted("simcheck demo", args.out)
    lay = DemoLayout(Path(args.out))
    total = sum(s.seconds for s in result.stages)
    tasks = _task_lines(result.certificate)
    print(f"partscene demo: {cfg.scene} seed {cfg.seed}, {total:.0f} s, {len(tasks)} tasks:")
    for line in tasks:
        print(line)
    for s in result.stages:
        if s.status is not StageStatus.OK:
            print(f"  stage {s.name}: {s.status.value}: {s.message}")
    print(f"report: {lay.report_html.resolve()}")
    return result.exit_code


if __name__ == "__main__":
    sys.exit(main())
