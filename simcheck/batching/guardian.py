"""A watcher that ends the local Ray processes of a batch driver once the driver is gone, however it
ended (``kill -9`` included: Ray's own agents otherwise linger for a minute or more).

The driver starts it with :func:`start_guardian` right after ``ray.init`` and keeps the write end of
its stdin; the guardian notes the driver's Ray descendants every :data:`POLL_SECONDS` and, when its
stdin closes (the driver stopped it, exited or died), kills those still alive.

    python -m simcheck.batching.guardian DRIVER_PID
"""

from __future__ import annotations

import os
import select
import subprocess
import sys
import time

__all__ = ["start_guardian", "stop_guardian", "POLL_SECONDS"]

#: seconds between two looks at the driver's descendants (a look walks every process of the machine;
#: Ray starts its services at ``ray.init`` and a worker per CPU at the first tasks)
POLL_SECONDS = 2.0
#: seconds the Ray processes get to exit by themselves once the driver is gone
SETTLE_SECONDS = 1.0


def _is_ray(proc) -> bool:
    try:
        cmd = proc.cmdline()
    except Exception:  # noqa: BLE001 - the process is gone or not ours to read
        return False
    return bool(cmd) and (cmd[0].startswith("ray::") or any("/ray/" in part for part in cmd))


def _watch(driver_pid: int) -> None:
    import psutil

    seen: dict[int, psutil.Process] = {}
    try:
        driver = psutil.Process(driver_pid)
    except psutil.NoSuchProcess:
        return
    while True:
        try:
            for child in driver.children(recursive=True):
                if child.pid not in seen and _is_ray(child):
                    seen[child.pid] = child
        except psutil.NoSuchProcess:
            pass
        ready, _, _ = select.select([sys.stdin], [], [], POLL_SECONDS)
        if ready and not sys.stdin.buffer.read1(1024):
            break
    time.sleep(SETTLE_SECONDS)
    for proc in seen.values():
        try:
            if proc.is_running():   # compares the creation time too: a reused pid is not killed
                proc.kill()
        except psutil.Error:
            pass


def start_guardian() -> subprocess.Popen:
    """Start the guardian of this process (in its own session, so a Ctrl-C of the terminal leaves it)."""
    return subprocess.Popen([sys.executable, "-m", "simcheck.batching.guardian", str(os.getpid())],
                            stdin=subprocess.PIPE, start_new_session=True)


def stop_guardian(proc: subprocess.Popen, timeout: float = 10.0) -> None:
    """Close the guardian's stdin (it kills what is left of Ray) and wait for it."""
    try:
        proc.stdin.close()
        proc.wait(timeout)
    except (OSError, subprocess.TimeoutExpired):
        proc.kill()


if __name__ == "__main__":
    _watch(int(sys.argv[1]))
