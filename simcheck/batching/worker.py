"""What runs in a Ray worker: one certification (or one reconstruction) in a fresh world, guarded by a
time and memory budget, its result written into the batch's store.

:func:`certify_job` calls :func:`simcheck.certify` with exactly the settings a plain ``simcheck certify``
of that one task would use (so the certificate is the same), in its own PyBullet DIRECT client, and
turns every way it can end into a stored record: the certificate's outcome; ``unusable`` for input
errors; ``error`` for an exception or a blown memory budget; ``timeout`` for a blown time budget.

The budget (:class:`Budget`) is a watchdog thread: past the time budget, or when the worker process's
resident memory passes the memory budget, it raises :class:`TaskTimeout` / :class:`TaskMemoryExceeded`
in the task's thread (at its next Python bytecode); if the task is still running
:data:`GRACE_SECONDS` later (stuck in C code), the watchdog stores the record itself and ends the worker
process, which Ray replaces. Without a memory budget the watchdog only waits for the time budget (it
reads no memory beside the task); a record's ``peak_rss_mb`` is then the worker process's peak resident
memory since it started (the kernel's high-water mark).
"""

from __future__ import annotations

import ctypes
import inspect
import os
import resource
import signal
import socket
import threading
import time
import traceback
from pathlib import Path

__all__ = ["certify_job", "certify_chunk", "reconstruct_job", "Budget", "TaskTimeout", "TaskMemoryExceeded", "GRACE_SECONDS"]

#: seconds a task gets to unwind after its budget is blown before the worker process is ended
GRACE_SECONDS = 10.0
#: seconds between two looks of the watchdog
_POLL_SECONDS = 0.05


class TaskTimeout(BaseException):
    """Raised in a task's thread when it ran past its time budget (a BaseException, so ``except
    Exception`` inside the certification does not swallow it)."""


class TaskMemoryExceeded(BaseException):
    """Raised in a task's thread when its worker's resident memory passed the memory budget."""


class Budget:
    """A watchdog over the calling thread: ``seconds`` of wall time and ``memory_mb`` of the process's
    resident memory (None: no limit; the memory is then not polled). Use as a context manager around the
    task; ``on_kill(status, reason)`` is called before the process is ended when the task does not unwind
    in time. ``peak_mb`` after the block: the largest resident memory polled, or the process's peak
    resident memory since it started (``getrusage``), whichever is larger, MB."""

    def __init__(self, seconds: float | None, memory_mb: float | None, on_kill=None) -> None:
        self.seconds, self.memory_mb, self.on_kill = seconds, memory_mb, on_kill
        self.reason = ""
        self.peak_mb = 0.0
        self._stop = threading.Event()
        self._tid = threading.get_ident()
        self._thread = threading.Thread(target=self._watch, daemon=True, name="simcheck-batch-budget")

    def __enter__(self) -> "Budget":
        self._t0 = time.monotonic()
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join()
        self.peak_mb = max(self.peak_mb, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)

    def _watch(self) -> None:
        if self.memory_mb is None:      # a time budget alone: one wait, no polling beside the task
            if not self._stop.wait(self.seconds) and self.seconds is not None:
                self._fire(TaskTimeout, "timeout", f"still running after --task-timeout {self.seconds:g} s")
            return
        import psutil

        proc = psutil.Process()
        while not self._stop.wait(_POLL_SECONDS):
            rss_mb = proc.memory_info().rss / 2**20
            self.peak_mb = max(self.peak_mb, rss_mb)
            if self.memory_mb is not None and rss_mb > self.memory_mb:
                self._fire(TaskMemoryExceeded, "error",
                           f"worker memory {rss_mb:.0f} MB passed --task-memory {self.memory_mb:.0f} MB")
                return
            if self.seconds is not None and time.monotonic() - self._t0 > self.seconds:
                self._fire(TaskTimeout, "timeout", f"still running after --task-timeout {self.seconds:g} s")
                return

    def _fire(self, exc: type, status: str, reason: str) -> None:
        self.reason = reason
        ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(self._tid), ctypes.py_object(exc))
        if self._stop.wait(GRACE_SECONDS):
            return
        if self.on_kill is not None:
            self.on_kill(status, f"{reason}; stuck for {GRACE_SECONDS:g} s more, its worker process was ended")
        os._exit(70)


def _fault(kind: str | None) -> None:
    """The internal test hook of the manifest's ``_fault`` field."""
    if kind == "raise":
        raise RuntimeError("test fault: the task raised")
    if kind == "segfault":
        os.kill(os.getpid(), signal.SIGSEGV)
    if kind == "exit":
        os._exit(3)
    if kind == "hang":
        while True:
            time.sleep(0.01)
    if kind == "memory":
        hog = []
        while True:
            hog.append(b"x" * (32 << 20))
            time.sleep(0.01)


def _where() -> dict:
    return {"pid": os.getpid(), "host": socket.gethostname()}


def certify_job(job: dict) -> dict:
    """Certify one task and store its result; returns the stored record.

    ``job`` (JSON-ready): ``store`` (the batch folder), ``key``, ``scene``, ``against`` (or None), ``task``
    ("open-drawer:JOINT"), ``robot`` ("default" or a spec file), ``seed``, ``amount`` (or None),
    ``images`` (bool), ``timeout`` (s or None), ``memory_mb`` (or None), ``attempt`` (1-based),
    ``robust``/``min_success`` (sampled worlds, or None), ``fault`` (internal test hook or None), ``row`` (scene name, task, line: copied into the record).
    """
    from simcheck.batching.store import Store

    store = Store(job["store"])
    start = time.time()
    holder: dict = {}

    def record(status: str, reason: str, **extra) -> dict:
        return {**job["row"], "status": status, "reason": reason, "start": start, "end": time.time(),
                "attempts": job["attempt"], "worker": {**_where(), "peak_rss_mb": round(holder["budget"].peak_mb, 1) if "budget" in holder else None},
                **extra}

    def on_kill(status: str, reason: str) -> None:
        store.put_result(job["key"], lambda tmp: record(status, reason, certificate="", worker_ended=True))

    def certified(tmp: Path) -> dict:
        from simcheck.certification import certify
        from simcheck.robot_spec_file import load_robot_spec

        holder["budget"] = Budget(job["timeout"], job["memory_mb"], on_kill)
        cpu0 = time.process_time()
        with holder["budget"]:
            _fault(job.get("fault"))
            kwargs = dict(against=job["against"], seed=job["seed"], out=tmp, robot=load_robot_spec(job["robot"]),
                          amounts=[job["amount"]] if job["amount"] is not None else None, images=job["images"])
            if job.get("robust") is None:
                cert = certify(job["scene"], [job["task"]], **kwargs)
            else:   # certify(robust=N) with its sampled worlds run in this worker's one process-pool slot
                from simcheck.robust import certify_robustly

                defaults = inspect.signature(certify).parameters     # a batch takes certify's own settings
                cert = certify_robustly(certify, job["scene"], [job["task"]], robust=job["robust"],
                                        min_success=job["min_success"], replay_sample=None, planner=None,
                                        criteria=defaults["criteria"].default, physics=defaults["physics"].default,
                                        planner_config=defaults["planner_config"].default, video=False, gui=False,
                                        workers=1, engine="processes", **kwargs)
        t = cert.tasks[0]
        from scenes.outcome import Outcome

        return record(Outcome(t.status.value).value, t.reason, certificate="certificate.json",
                      criteria={c.name: c.value for c in t.criteria}, failed_criteria=list(t.failed_criteria),
                      seconds=t.timings.get("total"), cpu_seconds=time.process_time() - cpu0, amount=t.amount,
                      unit=t.unit)

    try:
        store.put_result(job["key"], certified)
    except (TaskTimeout, TaskMemoryExceeded) as exc:
        status = "timeout" if isinstance(exc, TaskTimeout) else "error"
        reason = holder["budget"].reason if "budget" in holder and holder["budget"].reason else _budget_reason(exc)
        store.put_result(job["key"], lambda tmp: record(status, reason, certificate=""))
    except BaseException as exc:  # noqa: BLE001 - every way a task ends becomes its recorded outcome
        if isinstance(exc, (KeyboardInterrupt, SystemExit)):
            raise
        status = "unusable" if _is_input_error(exc) else "error"
        reason = f"{type(exc).__name__}: {exc}" if status == "error" else str(exc)
        store.put_result(job["key"], lambda tmp: record(status, reason, certificate="",
                                                        traceback=traceback.format_exc(limit=8)))
    return store.load(job["key"])


def certify_chunk(jobs: list[dict]) -> list[dict]:
    """:func:`certify_job` of each of ``jobs`` in turn (one Ray task for several certifications, each
    stored as soon as it is done); returns their stored records."""
    return [certify_job(job) for job in jobs]


def _budget_reason(exc: BaseException) -> str:
    return str(exc) or ("still running after its --task-timeout" if isinstance(exc, TaskTimeout)
                        else "passed its --task-memory")


def _is_input_error(exc: BaseException) -> bool:
    from simcheck.errors import SimcheckInputError

    try:
        from planners.errors import PlannerInputError
    except ImportError:  # pragma: no cover - planners is part of the package
        PlannerInputError = SimcheckInputError  # noqa: N806
    return isinstance(exc, (SimcheckInputError, PlannerInputError))


def reconstruct_job(job: dict) -> dict:
    """Reconstruct one scan into ``store/scans/<key>/`` (scene.urdf, graph.json, reconstruction.json);
    returns ``{"status": "ok" | "unusable" | "error", "reason": ..., "seconds": ...}`` (also stored).

    ``job``: ``store``, ``key``, ``scan``, ``labels``, ``seed``.
    """
    import json

    from scenes.description import write_text_atomic
    from simcheck.batching.store import Store

    store = Store(job["store"])
    t0 = time.perf_counter()
    outcome: dict = {}

    def build(tmp: Path) -> None:
        import recon

        try:
            rec = recon.reconstruct(job["scan"], job["labels"], seed=job["seed"])
            recon.write_reconstruction(rec, tmp)
            outcome.update(status="ok", reason=f"{len(rec.objects)} objects", warnings=list(rec.warnings))
        except Exception as exc:  # noqa: BLE001 - a reconstruction failure is that scan's outcome
            bad_input = isinstance(exc, (recon.ScanError,)) or _is_input_error(exc)
            outcome.update(status="unusable" if bad_input else "error", reason=f"{type(exc).__name__}: {exc}",
                           traceback=traceback.format_exc(limit=8))
        outcome.update(seconds=time.perf_counter() - t0, **_where())
        write_text_atomic(tmp / "reconstruction.json", json.dumps(outcome, indent=2) + "\n")

    store.commit(store.scans, job["key"], build)
    return json.loads((store.scans / job["key"] / "reconstruction.json").read_text())
