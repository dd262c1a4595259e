"""``render_report(demo_dir, out_html)``: one self-contained report.html from a demo directory.

Each section is drawn from the artifact it shows (see :mod:`._layout`); an artifact that is absent
gives a visible "not available" note instead of the section, never made-up content. A malformed
artifact raises :class:`ArtifactError` naming the file.
"""

from __future__ import annotations

import json
import logging
import os
import time
from collections.abc import Mapping
from pathlib import Path

from scenes.description import DescriptionError, read_truth_doc, write_text_atomic
from scenes.outcome import Outcome

from ._errors import ArtifactError
from ._html import badge, esc, img, note, num, page, section, table
from ._layout import DemoLayout
from ._part_tree_image import png_of_part_trees, trees_from_scene_json
from ._primitives import solids_from_truth, solids_from_urdf
from ._promises import does_not_promise_html
from ._scan_image import load_scan, png_of_scan
from ._scene_image import png_of_scenes, view_azimuth
from ._tables import (criteria_table, key_value_table, metrics_table, pipeline_table, robust_table,
                      uncertainty_table)
from ._tasks import executed_urdf, task_figures

__all__ = ["render_report", "read_json"]

log = logging.getLogger(__name__)


def read_json(path: Path) -> dict | None:
    """The JSON object in ``path``; ``None`` when the file does not exist; raises when malformed."""
    if not path.exists():
        return None
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise ArtifactError(f"{path}: not valid JSON ({exc})") from exc
    if not isinstance(doc, dict):
        raise ArtifactError(f"{path}: expected a JSON object at the top level, got {type(doc).__name__}")
    return doc


def _read_truth(path: Path) -> dict | None:
    """The ``truth.json`` document in ``path`` (format checked); ``None`` when the file does not exist."""
    if not path.exists():
        return None
    try:
        return read_truth_doc(path)
    except DescriptionError as exc:
        raise ArtifactError(str(exc)) from exc


def _missing(what: str, path: Path) -> str:
    return note(f"Not available: {what} ({path.name} was not found in {path.parent}).")


def _scan_section(lay: DemoLayout, azim: float) -> str:
    if not lay.scan_npz.exists() or not lay.labels_json.exists():
        return _missing("the scan", lay.scan_npz if not lay.scan_npz.exists() else lay.labels_json)
    scan = load_scan(lay.scan_npz, lay.labels_json)
    return img(png_of_scan(scan, azim_deg=azim),
               "The scan: each part in its own colour (left) and by its label (right); unlabelled points faint grey.",
               "scan")


def _scene_section(lay: DemoLayout, truth: dict | None, graph: dict | None) -> str:
    panels = []
    if lay.scene_urdf.exists():
        panels.append(("reconstruction (scene.urdf)", solids_from_urdf(lay.scene_urdf)))
    if truth is not None:
        panels.append(("truth (truth.json)", solids_from_truth(truth, str(lay.truth_json))))
    if not panels:
        return _missing("the reconstruction and the truth", lay.scene_urdf)
    body = img(png_of_scenes(panels, azim_deg=view_azimuth(truth)),
               "Primitive parts of the reconstruction beside the ground truth, "
               "coloured by part label, in the state the scan saw.", "scene")
    if not lay.scene_urdf.exists():
        body = _missing("the reconstruction", lay.scene_urdf) + body
    warnings = graph.get("warnings") if isinstance(graph, Mapping) else None
    if isinstance(warnings, list) and warnings:
        items = "".join(f"<li>{esc(w)}</li>" for w in warnings)
        body += (f"<details><summary>{len(warnings)} reconstruction warnings (graph.json)</summary>"
                 f"<ul>{items}</ul></details>")
    return body


def _tree_section(lay: DemoLayout, graph: dict | None, truth: dict | None) -> str:
    if graph is None and truth is None:
        return _missing("the part trees", lay.graph_json)
    est = {t.name: t for t in trees_from_scene_json(graph, str(lay.graph_json))} if graph else {}
    tru = {t.name: t for t in trees_from_scene_json(truth, str(lay.truth_json))} if truth else {}
    intro = ("Each object's parts (nodes, coloured by label) and joints (arrows parent &rarr; child) as in "
             "the paper's Fig. 3: <b>P</b> prismatic (blue), <b>R</b> revolute (red), <b>F</b> fixed (grey); "
             "for the estimate the number is the contact score (Eq. 1) of the edge the maximum spanning "
             "arborescence (Eq. 4) kept. Dotted: other contacts between parts, not kept in the tree "
             "(for the truth: true contacts that are not joints).")
    figs = []
    for name in list(est) + [n for n in tru if n not in est]:
        panels = [(f"{name}: estimate", est[name])] if name in est else []
        if name in tru:
            panels.append((f"{name}: truth", tru[name]))
        figs.append(img(png_of_part_trees(panels), f"{name}: part tree"
                        + (" (estimate, truth)" if len(panels) == 2 else ""), f"tree.{name}"))
    body = f"<p>{intro}</p>" + (_missing("the estimated part trees", lay.graph_json) if graph is None else "")
    return body + '<div class="grid">' + "".join(figs) + "</div>" + (uncertainty_table(graph) if graph else "")


def _task_key(task: Mapping, index: int) -> str:
    return str(task.get("joint") or task.get("name") or f"task{index}")


def _tasks_section(lay: DemoLayout, cert: dict | None) -> str:
    if cert is None:
        return _missing("the certificate", lay.certificate_json)
    tasks = cert.get("tasks")
    if not isinstance(tasks, list):
        raise ArtifactError(f"{lay.certificate_json}: expected a list under 'tasks'")
    parts = []
    for i, task in enumerate(tasks):
        key = _task_key(task, i)
        log.info("report: task %d/%d %s", i + 1, len(tasks), key)
        status = str(task.get("status", "?"))
        criteria = task.get("criteria", [])
        if isinstance(criteria, Mapping):  # {name: {...}} form
            criteria = [{"name": k, **v} for k, v in criteria.items()]
        unit = str(task.get("unit", "") or "")
        facts = [f"requested opening {num(task.get('amount'), f'cert.{key}.amount', unit)}"]
        if task.get("plan_status"):
            facts.append(f"planner: {esc(task['plan_status'])}")
        if isinstance(task.get("timings"), Mapping) and "total" in task["timings"]:
            facts.append(f"took {num(task['timings']['total'], f'cert.{key}.timings.total', 's')}")
        head = (f"<h3>{esc(task.get('kind', task.get('task', 'task')))} "
                f"<code>{esc(key)}</code> {badge(status, status == Outcome.CERTIFIED)}</h3>"
                f"<p>{esc(task.get('reason', ''))}</p><p class=\"facts\">{' &middot; '.join(facts)}</p>")
        figs = "".join(img(png, alt, f"task.{key}.{fig}")
                       for fig, alt, png in task_figures(lay, task, key, _required_fraction(cert),
                                                         executed_urdf(lay, cert)))
        if not figs:
            figs = note(f"No recorded rollout for {key} (the task was not executed).", "info")
        parts.append(f'<div class="task" id="task-{esc(key)}">{head}{criteria_table(key, criteria)}{robust_table(key, task.get("robust"))}{figs}</div>')
    where = (f"<p>Each task was planned on <code>{esc(Path(str(cert.get('scene', '?'))).name)}</code>"
             + (f" and executed with physics on <code>{esc(Path(str(cert['against'])).name)}</code> "
                "(the reference: joints matched by name)" if cert.get("against") else " and executed on it")
             + f", robot <code>{esc(Path(str(cert.get('robot', '?'))).name)}</code>.</p>")
    summary = where + table(["task", "status", "failed criteria"],
                    [[f'<a href="#task-{esc(_task_key(t, i))}">{esc(t.get("kind", ""))}:{esc(_task_key(t, i))}</a>',
                      badge(str(t.get("status", "?")), t.get("status") == Outcome.CERTIFIED),
                      esc(", ".join(c.get("name", "?") for c in t.get("criteria", [])
                                    if isinstance(c, Mapping) and c.get("passed") is False) or "none")]
                     for i, t in enumerate(tasks)], "summary")
    return summary + _untested_table(lay, cert, tasks) + "".join(parts)


def _untested_table(lay: DemoLayout, cert: Mapping, tasks: list) -> str:
    """The movable joints that were not tested, each with why: the certificate's ``untested`` (with why),
    then any other movable joint of the planned scene ("not requested")."""
    untested = dict(cert.get("untested") or {})
    tested = {str(t.get("joint")) for t in tasks if isinstance(t, Mapping)}
    scene = _file_of(lay, cert.get("scene"))
    if scene is not None:
        from simcheck.scene_joints import read_scene_joints
        try:
            joints = read_scene_joints(scene)
        except Exception as exc:  # noqa: BLE001 -- a scene the report cannot read is named, not fatal
            log.warning("report: cannot list the movable joints of %s: %s", scene, exc)
            joints = {}
        for name, j in joints.items():
            if j.type in ("prismatic", "revolute", "continuous") and name not in tested and name not in untested:
                untested[name] = "not requested (no task names it)"
    if not untested:
        return "<h3>Movable joints not tested</h3><p>None: every movable joint of the scene was tested.</p>"
    return ("<h3>Movable joints not tested</h3>"
            + table(["joint", "why"], [[f"<code>{esc(j)}</code>", esc(why)] for j, why in untested.items()],
                    "untested"))


def _file_of(lay: DemoLayout, ref) -> Path | None:
    """A path the certificate records: as written, relative to the certificate's folder, or by name there."""
    if not isinstance(ref, str) or not ref:
        return None
    for p in (Path(ref), lay.root / ref, lay.root / Path(ref).name):
        if p.is_file():
            return p
    return None


def _required_fraction(cert: Mapping) -> float | None:
    """The certificate's ``opened_fraction`` criterion threshold (the level drawn on the opening plot)."""
    crit = cert.get("criteria")
    if isinstance(crit, Mapping) and isinstance(crit.get("opened_fraction"), (int, float)):
        return float(crit["opened_fraction"])
    return None


def _provenance_section(cert: dict | None) -> str:
    if cert is None:
        return ""
    body = ""
    files = cert.get("files")
    if isinstance(files, Mapping) and files:
        body += ("<h3>files certified</h3><p>The content hash (SHA-256) of every file the certificate was judged "
                 "on: the certificate holds for these bytes only.</p>"
                 + table(["role", "file", "sha256"],
                         [[esc(role), f"<code>{esc(f.get('path', ''))}</code>", f"<code>{esc(f.get('sha256', ''))}</code>"]
                          for role, f in files.items() if isinstance(f, Mapping)], "files"))
    from simcheck.config import CRITERIA_UNITS

    units = {"criteria": CRITERIA_UNITS, "timings": {k: "s" for k in (cert.get("timings") or {})}}
    for field in ("criteria", "seeds", "versions", "timings"):
        value = cert.get(field)
        if isinstance(value, Mapping) and value:
            body += f"<h3>{esc(field)}</h3>" + key_value_table(value, f"cert.{field}", units.get(field))
    return body


def render_report(demo_dir: str | os.PathLike, out_html: str | os.PathLike | None = None) -> Path:
    """Render ``DEMO_DIR/report.html`` (or ``out_html``) from the artifacts in ``demo_dir``.

    The page is one file: PNG figures inline as base64 data URIs, inline CSS, no script, no URL. It is
    written atomically (temp file + rename). Returns the path written. Raises :class:`ArtifactError`
    when an artifact exists but is malformed (the message names it).
    """
    t0 = time.perf_counter()
    lay = DemoLayout(Path(demo_dir))
    if not lay.root.is_dir():
        raise ArtifactError(f"{lay.root}: demo directory does not exist")
    out = Path(out_html) if out_html is not None else lay.report_html
    truth, graph = _read_truth(lay.truth_json), read_json(lay.graph_json)
    metrics, cert, demo = read_json(lay.metrics_json), read_json(lay.certificate_json), read_json(lay.demo_json)

    if cert is not None and not isinstance(cert.get("tasks"), list):  # fail before drawing anything
        raise ArtifactError(f"{lay.certificate_json}: expected a list under 'tasks'")
    log.info("report: drawing the scan, the scenes and the part trees of %s", lay.root)
    sections = []
    if demo is not None:
        sections.append(("pipeline", "Pipeline", pipeline_table(demo.get("stages", []))))
    sections += [
        ("scan", "1. The scan, coloured by part", _scan_section(lay, view_azimuth(truth))),
        ("scene", "2. Reconstruction beside truth", _scene_section(lay, truth, graph)),
        ("trees", "3. Part trees and joints", _tree_section(lay, graph, truth)),
        ("metrics", "4. Reconstruction metrics",
         metrics_table(metrics) if metrics is not None else _missing("the metrics", lay.metrics_json)),
        ("tasks", "5. Tasks and certificate criteria", _tasks_section(lay, cert)),
    ]
    prov = _provenance_section(cert)
    if prov:
        sections.append(("provenance", "6. Files, criteria, seeds, versions, timings", prov))
    sections.append(("promise", f"{len(sections) - (1 if demo is not None else 0) + 1}. What a certificate does "
                     "not promise", does_not_promise_html()))

    title = "partscene report"
    if truth is not None:
        title += f": {truth.get('scene', '?')} (seed {truth.get('seed', '?')})"
    lead = _lead(cert)
    html = page(title, lead, [(a, t) for a, t, _ in sections],
                "".join(section(a, t, b) for a, t, b in sections))
    write_text_atomic(out, html)
    log.info("report: wrote %s (%.0f kB) in %.1f s", out, out.stat().st_size / 1e3, time.perf_counter() - t0)
    return out


def _lead(cert: dict | None) -> str:
    if cert is None:
        return "Scan &rarr; parts &rarr; joints &rarr; robot &rarr; certificate. No certificate yet."
    tasks = cert.get("tasks", []) if isinstance(cert.get("tasks"), list) else []
    n_ok = sum(1 for t in tasks if t.get("status") == Outcome.CERTIFIED)
    return (f"Scan &rarr; parts &rarr; joints &rarr; robot &rarr; certificate: "
            f"<b>{n_ok} of {len(tasks)} tasks certified</b>.")


