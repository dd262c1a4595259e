"""Every recon module imports on its own, and the package's imports form no cycle.

The cycle check reads the source (every ``import`` and ``from ... import``, also those inside functions),
so a cycle hidden behind a lazy import counts too.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import networkx as nx

import recon

ROOT = Path(recon.__file__).parent


def _modules() -> dict[str, Path]:
    """{dotted name: path} of every module of the recon package (packages as their __init__)."""
    out = {}
    for f in sorted(ROOT.rglob("*.py")):
        parts = ["recon", *f.relative_to(ROOT).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = f
    return out


def _imported(module: str, path: Path, known: set[str]) -> set[str]:
    """The recon modules that ``module`` imports anywhere in its source."""
    is_package = path.name == "__init__.py"
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = module.split(".") if is_package else module.split(".")[:-1]
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            names = [target] + [f"{target}.{a.name}" for a in node.names]
        else:
            continue
        found |= {n for n in names if n in known and n != module}
    return found


def import_graph() -> nx.DiGraph:
    mods = _modules()
    g = nx.DiGraph()
    for name, path in mods.items():
        g.add_node(name)
        g.add_edges_from((name, t) for t in _imported(name, path, set(mods)))
    return g


def test_recon_imports_have_no_cycle():
    cycles = list(nx.simple_cycles(import_graph()))
    assert not cycles, "import cycles: " + "; ".join(" -> ".join(c + [c[0]]) for c in cycles)


def test_the_cycle_check_sees_a_lazy_import_cycle(tmp_path):
    pkg = tmp_path / "recon"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from recon.b import f\n")
    (pkg / "b.py").write_text("def f():\n    from recon import a\n")
    mods = {"recon": pkg / "__init__.py", "recon.a": pkg / "a.py", "recon.b": pkg / "b.py"}
    assert _imported("recon.a", mods["recon.a"], set(mods)) == {"recon.b"}
    assert _imported("recon.b", mods["recon.b"], set(mods)) == {"recon", "recon.a"}


def test_every_recon_module_imports_first_in_a_fresh_interpreter():
    # one interpreter; before each module every recon.* module is forgotten, so each is imported first
    names = sorted(n for n in _modules() if n != "recon.__main__")
    code = ("import importlib, sys\n"
            f"for name in {names!r}:\n"
            "    for k in [k for k in sys.modules if k == 'recon' or k.startswith('recon.')]:\n"
            "        del sys.modules[k]\n"
            "    importlib.import_module(name)\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                         cwd=ROOT.parent)
    assert res.returncode == 0, res.stderr[-2000:]
