"""The batch driver on Ray: reconstruct the manifest's scans once, then certify every (scene, task),
skipping what the store already holds. The tasks of one scene are sent in chunks (one Ray task runs a
chunk's certifications one after the other, each stored as soon as it is done), sized from the tasks
still queued (:func:`chunk_size`: large at first, single tasks at the end, so the CPUs finish together),
at most one chunk in flight per CPU of the cluster.

Faults stay local to their task: an exception, a blown budget (see :mod:`simcheck.batching.worker`) or
a worker that died (a segfault, ``os._exit``, a lost node) becomes that task's stored ``error`` or
``timeout``. When a chunk's worker dies, its first task without a stored result is the one that was
running: only that task is retried (``retries`` times, counted in the record's ``attempts``) or recorded;
the chunk's tasks after it are sent again as they were. An exception or a timeout is not retried (it
would recur with the same seed). A chunk running :data:`BACKSTOP_FACTOR` x its tasks' time budget +
:data:`BACKSTOP_SECONDS` (its worker did not even manage to end itself) is cancelled with
``ray.cancel(force=True)``.

Ray is started locally (``num_cpus=workers``) unless ``address`` names a cluster (``auto``, or
``ray://host:10001``); a Ray already initialised by the caller is used as it is and left running.
A local Ray starts without the autoscaler's monitor and the log monitor, which one machine and a driver
taking no worker output do not use. A Ray started here is shut down when the run ends, on Ctrl-C or
SIGTERM, and, through :mod:`simcheck.batching.guardian`, when the driver is killed outright.
"""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import signal
import time
from collections import Counter, deque
from dataclasses import dataclass, field
from pathlib import Path

from simcheck.batching.keys import file_digest, scan_key, task_key
from simcheck.batching.manifest import Entry
from simcheck.batching.store import Store
from simcheck.robot_spec_file import is_named_robot

__all__ = ["Job", "RunSettings", "run_jobs", "worker_args", "jobs_for_entries", "all_movable_tasks", "chunk_size", "MAX_CHUNK", "ray_session", "ray_cpu_seconds", "BACKSTOP_FACTOR", "BACKSTOP_SECONDS"]

log = logging.getLogger(__name__)

#: the driver cancels a task after BACKSTOP_FACTOR x task_timeout + BACKSTOP_SECONDS in flight
BACKSTOP_FACTOR = 1.5
BACKSTOP_SECONDS = 60.0


@dataclass(frozen=True)
class RunSettings:
    """How tasks are run (the parts that change a result are in its key)."""

    task_timeout: float | None = 300.0
    task_memory_mb: float | None = None
    retries: int = 1
    images: bool = False
    chunk: int | None = None       # tasks per Ray task (None: :func:`chunk_size`)


#: the most tasks one Ray task runs when the chunk size is chosen automatically
MAX_CHUNK = 16


def chunk_size(queued: int, slots: int) -> int:
    """Tasks in the next Ray task when ``queued`` tasks wait for ``slots`` CPUs: a quarter of a CPU's
    share of them (guided self-scheduling), between 1 and :data:`MAX_CHUNK`. The driver then handles a
    few Ray tasks per CPU instead of one per certification, and the last ones are single tasks."""
    return max(1, min(MAX_CHUNK, queued // (4 * max(slots, 1))))


@dataclass
class Job:
    """One certification to run (or already stored): its row fields and the worker's arguments."""

    key: str
    row: dict                 # scene (manifest name), task, line
    args: dict                # certify_job arguments without store/attempt/budget
    fixed: dict | None = None  # a record decided without running (e.g. the reconstruction lacks the joint)
    attempt: int = 1


def all_movable_tasks(urdf: Path) -> tuple[list[str], dict[str, str]]:
    """The tasks ``tasks: all-movable`` means on the scene ``urdf`` (:func:`planners.task.movable_joint_tasks`:
    prismatic -> open-drawer, revolute or continuous -> open-door), in file order, including those of the
    movable joints it leaves out; and those left out (task string -> why: no opening range), which a batch
    records as rows rather than skipping them silently."""
    from planners.task import OPENING_KINDS, OpenTask, movable_joint_tasks
    from simcheck.scene_joints import read_scene_joints

    joints = read_scene_joints(urdf)
    tasks, skipped = movable_joint_tasks(joints, urdf)
    ok = {t.joint: str(t) for t in tasks}
    left = {str(OpenTask(OPENING_KINDS[joints[n].type], n)): why for n, why in skipped.items()}
    order = [ok.get(n) or str(OpenTask(OPENING_KINDS[joints[n].type], n)) for n in joints if n in ok or n in skipped]
    return order, left


def _settings(entry: Entry, settings: RunSettings) -> dict:
    from simcheck.config import DEFAULT_CRITERIA, DEFAULT_PHYSICS

    out = {"seed": entry.seed, "amount": entry.amount, "criteria": DEFAULT_CRITERIA.to_dict(),
           "physics": dataclasses.asdict(DEFAULT_PHYSICS), "images": settings.images}
    if entry.robust is not None:
        out.update(robust=entry.robust, min_success=entry.min_success)
    if entry.fault:
        out["fault"] = entry.fault
    return out


def _scene_jobs(entry: Entry, scene: Path, against: Path | None, tasks: list[str], settings: RunSettings,
                missing: dict[str, str] | None = None, unusable: dict[str, str] | None = None) -> list[Job]:
    """One job per task; a task in ``missing`` (a wrong reconstruction) is recorded ``failed`` and one in
    ``unusable`` (no opening range to certify) ``unusable``, each with its reason, without running."""
    digests = (file_digest(scene), file_digest(against),
               entry.robot if is_named_robot(entry.robot) else file_digest(entry.robot))
    jobs = []
    for task in tasks:
        key = task_key(digests[0], digests[1], task, digests[2], _settings(entry, settings))
        row = {"scene": entry.name, "task": task, "line": entry.line}
        args = {"scene": str(scene), "against": str(against) if against else None, "task": task,
                "robot": entry.robot, "seed": entry.seed, "amount": entry.amount, "fault": entry.fault,
                "robust": entry.robust, "min_success": entry.min_success}
        fixed = None
        if missing and task in missing:
            fixed = {"status": "failed", "reason": missing[task], "certificate": "", "attempts": 0}
        elif unusable and task in unusable:
            fixed = {"status": "unusable", "reason": unusable[task], "certificate": "", "attempts": 0}
        jobs.append(Job(key, row, args, fixed))
    return jobs


def _scan_tasks(entry: Entry, scene: Path) -> tuple[list[str], dict[str, str], dict[str, str]]:
    """A reconstructed scan's tasks, why those its reconstruction cannot run fail (it lacks the joint,
    models it with another type, or gives it no opening range: the estimate is wrong, so the task
    fails), and why those of the truth's joints without an opening range are unusable.

    ``tasks: all-movable`` means every movable joint of the reconstruction, plus, with a ``truth``,
    every movable joint of the truth that the reconstruction lacks."""
    from planners.task import KINDS, parse_task
    from scenes.description import InputError
    from simcheck.scene_joints import read_scene_joints

    joints = read_scene_joints(scene)
    have, no_range = all_movable_tasks(scene)
    unusable: dict[str, str] = {}
    if entry.tasks is None:
        wanted = list(have)
        if entry.against is not None:
            truth, unusable = all_movable_tasks(entry.against)
            names = {t.split(":", 1)[1] for t in have}
            wanted += [t for t in truth if t.split(":", 1)[1] not in names]
            unusable = {t: why for t, why in unusable.items() if t not in have or t in no_range}
    else:
        wanted = list(entry.tasks)
    missing = {}
    for task in wanted:
        if task in unusable:
            continue
        if task in no_range:
            missing[task] = f"the reconstruction of {entry.name}: {no_range[task]}: {task} cannot be certified"
            continue
        try:
            parsed = parse_task(task)
        except InputError as exc:
            missing[task] = str(exc)
            continue
        j = joints.get(parsed.joint)
        if j is None or KINDS[parsed.kind] != j.type and not (parsed.kind == "door" and j.type == "continuous"):
            what = "no joint" if j is None else f"a {j.type} joint"
            missing[task] = (f"the reconstruction of {entry.name} has {what} {parsed.joint!r}: {parsed.action} "
                             "cannot be certified")
    return wanted, missing, unusable


def scans_to_reconstruct(entries: list[Entry], store: Store) -> list[Entry]:
    """The scan entries whose reconstruction is not in ``store`` yet."""
    return [e for e in entries if e.scan is not None and not (store.scans / _scan_key(e) / "reconstruction.json").is_file()]


def jobs_for_entries(entries: list[Entry], store: Store, settings: RunSettings) -> list[Job]:
    """Every job of the manifest (its scans must be reconstructed in ``store`` already: see
    :func:`scans_to_reconstruct`); a scan whose reconstruction failed gives one row for the scan itself."""
    jobs: list[Job] = []
    for e in entries:
        if e.scene is not None:
            tasks, unusable = (list(e.tasks), {}) if e.tasks else all_movable_tasks(e.scene)
            jobs += _scene_jobs(e, e.scene, e.against, tasks, settings, unusable=unusable)
            continue
        folder = store.scans / _scan_key(e)
        import json

        rec = json.loads((folder / "reconstruction.json").read_text())
        if rec["status"] != "ok":
            key = task_key(_scan_key(e), "", "reconstruct", "", {})
            jobs.append(Job(key, {"scene": e.name, "task": "reconstruct", "line": e.line}, {},
                            {"status": rec["status"], "reason": f"reconstruction failed: {rec['reason']}",
                             "certificate": "", "attempts": 1}))
            continue
        tasks, missing, unusable = _scan_tasks(e, folder / "scene.urdf")
        jobs += _scene_jobs(e, folder / "scene.urdf", e.against, tasks, settings, missing, unusable)
    return jobs


def _scan_key(entry: Entry) -> str:
    return scan_key(file_digest(entry.scan), file_digest(entry.labels), entry.seed)


class _Stop(Exception):
    """SIGTERM / SIGHUP received: end the run like Ctrl-C."""


def ray_session(workers: int | None, address: str | None, usage: dict | None = None):
    """Context manager: a Ray connection for the run (see the module docstring); yields the number of
    CPUs of the cluster. With a Ray started here, ``usage`` (if given) receives the CPU time of its
    processes just before it is shut down (see :func:`ray_cpu_seconds`)."""

    @contextlib.contextmanager
    def session():
        import ray

        if ray.is_initialized():
            yield int(ray.cluster_resources().get("CPU", 1))
            return
        guardian = None
        kwargs = dict(include_dashboard=False, log_to_driver=False, logging_level=logging.ERROR,
                      configure_logging=True)
        if address:
            try:
                ray.init(address=address, **({} if address.startswith("ray://") else kwargs))
            except (ConnectionError, ValueError, RuntimeError) as exc:
                from simcheck.errors import SimcheckInputError
                raise SimcheckInputError(f"--address {address}: no Ray cluster could be joined ({exc}); start "
                                         "one with `ray start --head`, or leave --address out for a local Ray") from exc
        else:
            with _without_monitors():
                ray.init(address="local", num_cpus=workers, **kwargs)
            from simcheck.batching.guardian import start_guardian
            guardian = start_guardian()
        previous = {s: signal.getsignal(s) for s in (signal.SIGTERM, signal.SIGHUP)}

        def stop(signum, frame):
            raise _Stop(f"signal {signal.Signals(signum).name}")

        for s in previous:
            signal.signal(s, stop)
        try:
            yield int(ray.cluster_resources().get("CPU", 1))
        finally:
            for s, h in previous.items():
                signal.signal(s, h)
            if guardian is not None and usage is not None:
                usage.update(ray_cpu_seconds())
            ray.shutdown()
            if guardian is not None:
                from simcheck.batching.guardian import stop_guardian
                stop_guardian(guardian)

    return session()


@contextlib.contextmanager
def _without_monitors():
    """While a local Ray starts: its node is asked for neither the autoscaler's monitor (one machine does
    not scale) nor the log monitor (the driver takes no worker output: ``log_to_driver=False``), as
    ``ray start --no-monitor --include-log-monitor=False`` would; ``ray.init`` has no switch for them (their
    cost: docs/decisions.md, "Ray's local start without its monitors"). A Ray whose node parameters lack
    those fields starts as it is."""
    try:
        from ray._private.parameter import RayParams
    except ImportError:
        yield
        return
    init = RayParams.__init__

    def lean(self, *args, **kwargs):
        init(self, *args, **kwargs)
        if hasattr(self, "no_monitor") and hasattr(self, "include_log_monitor"):
            self.no_monitor, self.include_log_monitor = True, False

    RayParams.__init__ = lean
    try:
        yield
    finally:
        RayParams.__init__ = init


def ray_cpu_seconds() -> dict:
    """CPU time (user + system, s) so far of this process's descendants, which are a local Ray's processes
    and the guardian: ``workers`` (Ray's ``ray::`` worker processes, imports included), ``ray_services``
    (the GCS, raylet, dashboard, monitors, agents and the guardian, with the children they reaped) and
    ``per_worker`` (a list, largest first). A process that ended earlier is counted only through the
    parent that reaped it."""
    import psutil

    workers, services = [], 0.0
    for p in psutil.Process().children(recursive=True):
        try:
            t, name = p.cpu_times(), p.name()
        except psutil.Error:
            continue
        own = t.user + t.system
        if name.startswith("ray::") and "Agent" not in name:
            workers.append(own)
        else:
            services += own + t.children_user + t.children_system
    return {"ray_services": services, "workers": sum(workers), "per_worker": sorted(workers, reverse=True)}


def run_reconstructions(entries: list[Entry], store: Store) -> None:
    """Reconstruct the scans of ``entries`` in parallel on Ray (results in ``store.scans``)."""
    import ray

    from simcheck.batching.worker import reconstruct_job

    remote = ray.remote(max_retries=1)(reconstruct_job)
    refs = {}
    for e in entries:
        key = _scan_key(e)
        if key in {r["key"] for r in refs.values()}:
            continue
        refs[remote.remote({"store": str(store.root), "key": key, "scan": str(e.scan), "labels": str(e.labels),
                            "seed": e.seed})] = {"key": key, "entry": e}
    for ref, what in refs.items():
        try:
            out = ray.get(ref)
            log.info("reconstructed %s: %s (%s)", what["entry"].name, out["status"], out["reason"])
        except ray.exceptions.RayError as exc:
            import json

            from scenes.description import write_text_atomic

            def build(tmp, exc=exc):
                write_text_atomic(tmp / "reconstruction.json", json.dumps(
                    {"status": "error", "reason": f"its worker died: {type(exc).__name__}"}) + "\n")
            store.commit(store.scans, what["key"], build)


@dataclass
class Progress:
    """Counts of a run by status (what the progress bar shows)."""

    counts: Counter = field(default_factory=Counter)
    computed: int = 0
    resumed: int = 0
    retried: int = 0


def run_jobs(jobs: list[Job], store: Store, settings: RunSettings, slots: int, make_bar=None) -> Progress:
    """Run every job not yet in ``store`` (at most ``slots`` in flight); returns the counts.
    ``make_bar(total, done)``: a progress bar with ``update(n)``, ``set_postfix_str(text)`` and
    ``close()`` (tqdm's), started at the jobs already done, or None for no bar."""
    progress = Progress()
    pending = []
    for job in jobs:
        if store.has(job.key):
            progress.resumed += 1
            progress.counts[store.load(job.key)["status"]] += 1
        elif job.fixed is not None:
            store.put_result(job.key, lambda tmp, job=job: {**job.row, **job.fixed, "start": time.time(),
                                                            "end": time.time()})
            progress.counts[job.fixed["status"]] += 1
            progress.computed += 1
        else:
            pending.append(job)
    if not pending:
        return progress
    bar = make_bar(len(jobs), len(jobs) - len(pending)) if make_bar is not None else None
    if bar is not None:
        bar.set_postfix_str(_counts_text(progress.counts))
    try:
        _dispatch(pending, store, settings, slots, bar, progress)
    finally:
        if bar is not None:
            bar.close()
    return progress


def worker_args(job: Job, store: Store, settings: RunSettings) -> dict:
    """What a worker gets for ``job`` (:func:`simcheck.batching.worker.certify_job`'s ``job``)."""
    return {**job.args, "store": str(store.root), "key": job.key, "row": job.row, "attempt": job.attempt,
            "timeout": settings.task_timeout, "memory_mb": settings.task_memory_mb, "images": settings.images}


def _next_chunk(queue: deque, size: int) -> list[Job]:
    """Take up to ``size`` jobs of one scene (and reference) from the front of ``queue``."""
    chunk = [queue.popleft()]
    scene = (chunk[0].args["scene"], chunk[0].args["against"])
    while queue and len(chunk) < size and (queue[0].args["scene"], queue[0].args["against"]) == scene:
        chunk.append(queue.popleft())
    return chunk


def _dispatch(pending: list[Job], store: Store, settings: RunSettings, slots: int, bar, progress: Progress) -> None:
    import ray

    from simcheck.batching.worker import certify_chunk

    # with a memory budget, Ray also reserves it (its ``memory`` resource is admission control only: a
    # node runs no more tasks than its memory holds; the budget itself is enforced by the worker's watchdog)
    memory = {"memory": int(settings.task_memory_mb * 2**20)} if settings.task_memory_mb else {}
    remote = ray.remote(max_retries=0, num_cpus=1, **memory)(certify_chunk)
    inflight: dict = {}
    cancelled: set = set()
    backstop = (BACKSTOP_FACTOR * settings.task_timeout) if settings.task_timeout else None
    queue = deque(pending)
    while queue or inflight:
        while queue and len(inflight) < slots:
            chunk = _next_chunk(queue, settings.chunk or chunk_size(len(queue), slots))
            args = [worker_args(job, store, settings) for job in chunk]
            inflight[remote.remote(args)] = (chunk, time.monotonic())
        refs = list(inflight)
        ready, _ = ray.wait(refs, num_returns=1, timeout=1.0)
        if ready and len(refs) > 1:   # collect every finished chunk at once (one wait per batch, not per chunk)
            ready, _ = ray.wait(refs, num_returns=len(refs), timeout=0)
        for ref in ready:
            chunk, _t0 = inflight.pop(ref)
            statuses = _collect(ref, chunk, store, settings, ref in cancelled, queue, progress)
            for status in statuses:
                progress.counts[status] += 1
                progress.computed += 1
            if bar is not None and statuses:
                bar.update(len(statuses))
                bar.set_postfix_str(_counts_text(progress.counts))
        if backstop is not None:
            now = time.monotonic()
            for ref, (chunk, t0) in inflight.items():
                if ref not in cancelled and now - t0 > backstop * len(chunk) + BACKSTOP_SECONDS:
                    log.warning("%s %s: no answer after %.0f s, cancelling its worker", chunk[0].row["scene"],
                                ", ".join(j.row["task"] for j in chunk), now - t0)
                    ray.cancel(ref, force=True)
                    cancelled.add(ref)


def _collect(ref, chunk: list[Job], store: Store, settings: RunSettings, cancelled: bool, queue: deque,
             progress: Progress) -> list[str]:
    """The statuses of a finished chunk's jobs that are done (their records are in the store); the others
    are queued again at the front of ``queue``: after a dead worker, the task that was running is retried or recorded
    (see the module docstring) and the ones after it are queued unchanged."""
    import ray

    try:
        return [record["status"] for record in ray.get(ref)]
    except ray.exceptions.RayError as exc:
        records = [store.load(job.key) if store.has(job.key) else None for job in chunk]
        done = [r["status"] for r in records if r is not None]
        rest = [job for job, r in zip(chunk, records) if r is None]
        last = max((i for i, r in enumerate(records) if r is not None), default=None)
        if not rest or (last is not None and records[last].get("worker_ended")):
            queue.extendleft(reversed(rest))   # the task that ended its worker stored its own outcome
            return done
        job, after = rest[0], rest[1:]
        if after:
            queue.extendleft(reversed(after))
        if cancelled:
            status, reason = "timeout", (f"no answer after {BACKSTOP_FACTOR:g} x --task-timeout "
                                         f"{settings.task_timeout:g} s + {BACKSTOP_SECONDS:g} s; its worker was killed")
        elif isinstance(exc, (ray.exceptions.WorkerCrashedError, ray.exceptions.NodeDiedError,
                              ray.exceptions.LocalRayletDiedError)) and job.attempt <= settings.retries:
            log.warning("%s %s: its worker died (attempt %d); retrying", job.row["scene"], job.row["task"], job.attempt)
            job.attempt += 1
            progress.retried += 1
            queue.appendleft(job)
            return done
        elif isinstance(exc, ray.exceptions.OutOfMemoryError):
            status, reason = "error", f"killed by Ray's memory monitor (the node ran out of memory): {_first_line(exc)}"
        else:
            status = "error"
            reason = (f"its worker died {job.attempt} time(s) (a crash such as a segfault, or a lost node): "
                      f"{type(exc).__name__}: {_first_line(exc)}")
        now = time.time()
        store.put_result(job.key, lambda tmp: {**job.row, "status": status, "reason": reason, "start": now,
                                               "end": now, "attempts": job.attempt, "certificate": ""})
        return done + [status]


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else ""


def _counts_text(counts: Counter) -> str:
    return " ".join(f"{k}={v}" for k, v in sorted(counts.items()))
