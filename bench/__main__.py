"""Run every partscene benchmark in turn: ``python -m bench [NAME ...]``.

Each benchmark is a module ``bench/<name>_bench.py`` with a ``main(argv) -> int`` that prints tables.
Benchmarks measure speed, memory and accuracy against the targets of the issues; they are not tests.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys
import time

import bench


def main(argv: list[str] | None = None) -> int:
    names = list(argv if argv is not None else sys.argv[1:])
    available = sorted(m.name for m in pkgutil.iter_modules(bench.__path__) if m.name.endswith("_bench"))
    unknown = [n for n in names if n not in available and f"{n}_bench" not in available]
    if unknown:
        print(f"bench: unknown benchmark(s) {unknown}; available: {available}", file=sys.stderr)
        return 2
    chosen = [n if n in available else f"{n}_bench" for n in names] or available
    status = 0
    for name in chosen:
        print(f"\n=== {name} ===", flush=True)
        t0 = time.perf_counter()
        rc = importlib.import_module(f"bench.{name}").main([])
        print(f"=== {name}: exit {rc}, {time.perf_counter() - t0:.1f} s ===", flush=True)
        status = status or int(rc or 0)
    return status


if __name__ == "__main__":
    sys.exit(main())
