"""Where the sampled executions of a robust certificate run: worker processes on this machine, or tasks
on the Ray batch engine (:mod:`simcheck.batching`).

* ``"processes"``: a :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` processes (default one
  per CPU), forked where the platform can (no re-import, no ``__main__`` guard needed in a caller's script),
  spawned elsewhere. No start-up cost beyond the fork.
* ``"ray"``: one Ray task per sample (``num_cpus=1``), on the Ray this process is connected to, else on
  the cluster at ``address`` (``auto``, ``ray://host:10001``), else on a local Ray of ``workers`` CPUs started
  for the run and shut down after it (:func:`simcheck.batching.runner.ray_session`; a local start costs
  about 10 s, so ``--robust 30`` on one task is faster with processes on one machine). The scene files must
  be readable at the same path on every node (as for ``simcheck batch``).
* ``"auto"`` (default): Ray when it is there to be used -- this process is already connected to a Ray
  (``ray.init`` by the caller), or ``address`` is given or ``RAY_ADDRESS`` is set -- else processes.

A sample whose worker dies (a segfault, a lost node) is that sample's ``error`` with the reason; the
others stand (with processes, the samples of the broken pool are run again one process each to find it).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence

from scenes.outcome import Outcome
from simcheck.errors import SimcheckInputError
from simcheck.robust_verdict import SampleResult

__all__ = ["ENGINES", "choose_engine", "run_samples"]

ENGINES = ("auto", "processes", "ray")


def _ray_connected() -> bool:
    import sys

    if "ray" not in sys.modules:        # never imported: nobody connected it
        return False
    import ray

    return ray.is_initialized()


def choose_engine(engine: str, address: str | None = None) -> str:
    """``"processes"`` or ``"ray"`` for ``engine`` (module docstring). Raises :class:`SimcheckInputError`
    naming ``engine`` for an unknown one, or Ray asked for where it is not installed."""
    if engine not in ENGINES:
        raise SimcheckInputError(f"engine: must be one of {', '.join(ENGINES)}, got {engine!r}")
    if engine == "auto":
        return "ray" if (_ray_connected() or address or os.environ.get("RAY_ADDRESS")) else "processes"
    if engine == "ray":
        try:
            import ray  # noqa: F401
        except ImportError as exc:
            raise SimcheckInputError("engine: 'ray' needs the ray package (pip install 'ray[default]'); "
                                     "use --engine processes") from exc
    return engine


def _context():
    import multiprocessing

    return multiprocessing.get_context("fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn")


def _failed(args, exc) -> SampleResult:
    p = args[1]
    return SampleResult(p, Outcome.ERROR, f"sample {p.index} could not be executed: its worker failed ({exc})", {})


def run_samples(fn: Callable, args: Sequence[tuple], engine: str = "auto", workers: int | None = None,
                address: str | None = None) -> list[SampleResult]:
    """``[fn(*a) for a in args]`` in parallel on ``engine`` (module docstring), in the order of ``args``.

    fn : a module-level function (picklable) returning a :class:`SampleResult`; each ``a[1]`` is the
    sample's :class:`~simcheck.perturbations.Perturbation`. workers : processes, or CPUs of a local Ray
    (default: this machine's CPUs, at most one per sample).
    """
    if not args:
        return []
    n_workers = max(1, min(len(args), workers or os.cpu_count() or 1))
    if choose_engine(engine, address) == "processes":
        from concurrent.futures import ProcessPoolExecutor
        from concurrent.futures.process import BrokenProcessPool

        out: list[SampleResult | None] = [None] * len(args)
        with ProcessPoolExecutor(n_workers, mp_context=_context()) as pool:
            futures = [pool.submit(fn, *a) for a in args]
            for i, f in enumerate(futures):
                try:
                    out[i] = f.result()
                except BrokenProcessPool:
                    pass        # a dead worker breaks the whole pool: its samples are run again one by one
        for i, a in enumerate(args):
            if out[i] is None:
                with ProcessPoolExecutor(1, mp_context=_context()) as pool:
                    try:
                        out[i] = pool.submit(fn, *a).result()
                    except BrokenProcessPool as exc:
                        out[i] = _failed(a, exc)
        return out
    import ray

    from simcheck.batching.runner import ray_session

    with ray_session(n_workers, address):
        remote = ray.remote(num_cpus=1, max_retries=0)(fn)
        refs = [remote.remote(*a) for a in args]
        out = []
        for a, ref in zip(args, refs):
            try:
                out.append(ray.get(ref))
            except ray.exceptions.RayError as exc:
                out.append(_failed(a, exc))
        return out
