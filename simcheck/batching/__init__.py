"""Batch certification on Ray: every (scene, task) of a manifest, resumable, on one machine or a cluster.

    result = simcheck.batch("manifest.yaml", out="batch-out", workers=2)
    result.exit_code, result.totals, result.rows[0]["status"], result.summary_path

Modules: ``manifest`` (parse + check, errors name the line and field), ``keys`` (content hashes of the
inputs), ``store`` (atomic result folders under the output folder), ``worker`` (one certification in a
Ray worker, with its time and memory budget), ``runner`` (the Ray driver), ``summary`` (summary.json,
summary.html, JUnit XML, baseline comparison), ``guardian`` (ends Ray's processes if the driver dies).
Ray is imported only when a batch runs.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass
from pathlib import Path

__all__ = ["batch", "BatchResult", "DEFAULT_TASK_TIMEOUT"]

log = logging.getLogger(__name__)

#: seconds a task may run before it is recorded as ``timeout`` (a kitchen drawer or door takes ~1 s)
DEFAULT_TASK_TIMEOUT = 300.0


@dataclass(frozen=True)
class BatchResult:
    """The outcome of a batch run.

    Attributes:
        rows: one dict per task (the rows of summary.json).
        totals: tasks by status.
        exit_code: as for ``simcheck certify`` (scenes.outcome.exit_code of the rows' statuses).
        summary_path: DIR/summary.json.
        computed: tasks run (or decided) in this run; resumed: tasks found in the store; retried: worker
            deaths that were retried.
        newly_failing: tasks certified in the baseline and not now (None without a baseline).
        run: what summary.json records of the run: ``computed``, ``resumed``, ``retried``, ``slots``,
            ``seconds`` (wall) and ``cpu_seconds`` (``driver``: this process during the call; with a local
            Ray also ``ray_services`` and ``workers``, its processes' CPU time up to its shutdown, and
            ``per_worker``).
    """

    rows: list
    totals: dict
    exit_code: int
    summary_path: Path
    computed: int
    resumed: int
    retried: int
    newly_failing: list | None = None
    run: dict | None = None


def batch(manifest, out, *, workers: int | None = None, address: str | None = None,
          task_timeout: float | None = DEFAULT_TASK_TIMEOUT, task_memory: float | None = None, retries: int = 1,
          images: bool = False, junit=None, baseline=None, progress: bool = True, chunk: int | None = None) -> BatchResult:
    """Certify every task of ``manifest`` into the folder ``out`` (see :mod:`simcheck.batching.manifest`
    for the manifest and :mod:`simcheck.batching.store` for the folder); what ``out`` already holds for
    the same inputs is not computed again.

    Args:
        workers: local Ray CPUs (default: all); ignored with ``address``.
        address: a running Ray cluster ("auto", "host:6379" or "ray://host:10001").
        task_timeout: seconds per task before it is stopped and recorded as ``timeout`` (None: no limit).
        task_memory: MB of resident memory of a task's worker before it is stopped as ``error`` (None: no limit).
        retries: how often a task whose worker died is run again.
        images: also render the key-frame PNGs of each task.
        junit: write JUnit XML there; baseline: an older summary.json to list newly failing tasks against.
        progress: show a progress bar (on a terminal).
        chunk: certifications of one scene per Ray task (None: chosen from the number of tasks and CPUs,
            :func:`simcheck.batching.runner.chunk_size`).

    Raises:
        ManifestError: a malformed manifest entry (names the line and field); nothing was started.
    """
    from scenes.outcome import exit_code
    from simcheck.batching.manifest import read_manifest
    from simcheck.batching.runner import (RunSettings, jobs_for_entries, ray_session, run_reconstructions,
                                          scans_to_reconstruct)
    from simcheck.batching.store import Store
    from simcheck.batching.summary import newly_failing, rows_from_store, write_junit, write_summary

    t0, cpu0 = time.perf_counter(), time.process_time()
    entries = read_manifest(manifest)
    if baseline is not None:
        newly_failing([], baseline)  # a bad baseline is an input error before anything starts
    store = Store(out)
    if store.remove_partial():
        log.info("removed the partial results of an interrupted run")
    if chunk is not None and chunk < 1:
        from simcheck.errors import SimcheckInputError
        raise SimcheckInputError(f"chunk must be at least 1 task, got {chunk}")
    settings = RunSettings(task_timeout, task_memory, retries, images, chunk)
    need = scans_to_reconstruct(entries, store)
    jobs = [] if need else jobs_for_entries(entries, store, settings)
    slots, usage = 0, {}
    if need or any(not store.has(j.key) for j in jobs):
        with ray_session(workers, address, usage) as slots:
            if need:
                run_reconstructions(need, store)
                jobs = jobs_for_entries(entries, store, settings)
            counts = _run(jobs, store, settings, slots, progress)
    else:  # everything is stored: no Ray
        counts = _run(jobs, store, settings, slots, progress)
    rows = rows_from_store([j.key for j in jobs], store)
    newly = newly_failing(rows, baseline) if baseline is not None else None
    run = {"computed": counts.computed, "resumed": counts.resumed, "retried": counts.retried, "slots": slots,
           "seconds": time.perf_counter() - t0, "cpu_seconds": {"driver": time.process_time() - cpu0, **usage}}
    path = write_summary(store.root, rows, str(manifest), newly, run)
    if junit is not None:
        write_junit(junit, rows)
    totals = dict(sorted({s: sum(r["status"] == s for r in rows) for s in {r["status"] for r in rows}}.items()))
    return BatchResult(rows, totals, exit_code(r["status"] for r in rows), path, counts.computed, counts.resumed,
                       counts.retried, newly, run)


def _run(jobs, store, settings, slots: int, progress: bool):
    from simcheck.batching.runner import run_jobs

    return run_jobs(jobs, store, settings, slots, _bar if progress else None)


def _bar(total: int, done: int):
    from tqdm import tqdm

    return tqdm(total=total, initial=done, unit="task", desc="certifying", dynamic_ncols=True, disable=None)
