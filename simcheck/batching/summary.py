"""What a batch run leaves for people and CI: ``summary.json``, ``summary.html``, JUnit XML, and the
tasks that newly fail against a baseline summary.

``summary.json`` (format ``partscene.batch-summary/1``)::

    {"format": ..., "manifest": "...", "rows": [{"scene", "task", "status", "reason", "criteria": {name: value},
     "failed_criteria": [...], "start", "end" (unix s), "seconds", "attempts", "line", "key",
     "certificate": "results/<key>/certificate.json" | ""}, ...],
     "totals": {status: count}, "newly_failing": [{"scene", "task", "status", "was"}] (with a baseline)}
"""

from __future__ import annotations

import html
import json
import xml.etree.ElementTree as ET
from collections import Counter, defaultdict
from pathlib import Path

from scenes.description import write_text_atomic

__all__ = ["rows_from_store", "write_summary", "write_junit", "newly_failing", "SUMMARY_FORMAT"]

SUMMARY_FORMAT = "partscene.batch-summary/1"
_ROW_FIELDS = ("scene", "task", "status", "reason", "criteria", "failed_criteria", "start", "end", "seconds",
               "cpu_seconds", "attempts", "line", "key")


def rows_from_store(keys: list[str], store) -> list[dict]:
    """One row per key (in that order) from the stored records."""
    rows = []
    for key in keys:
        rec = store.load(key)
        row = {f: rec.get(f) for f in _ROW_FIELDS}
        row["criteria"] = rec.get("criteria") or {}
        row["failed_criteria"] = rec.get("failed_criteria") or []
        row["certificate"] = f"results/{key}/{rec['certificate']}" if rec.get("certificate") else ""
        rows.append(row)
    return rows


def newly_failing(rows: list[dict], baseline: str | Path) -> list[dict]:
    """Tasks certified in the ``baseline`` summary.json and not certified in ``rows`` (matched by scene
    and task)."""
    from simcheck.batching.manifest import ManifestError

    try:
        old = json.loads(Path(baseline).read_text())
        was = {(r["scene"], r["task"]): r["status"] for r in old["rows"]}
    except (OSError, json.JSONDecodeError, KeyError, TypeError) as exc:
        raise ManifestError(f"--baseline {baseline}: not a readable summary.json ({exc})") from exc
    return [{"scene": r["scene"], "task": r["task"], "status": r["status"], "was": "certified"}
            for r in rows if was.get((r["scene"], r["task"])) == "certified" and r["status"] != "certified"]


def write_summary(out: Path, rows: list[dict], manifest: str, newly: list[dict] | None = None,
                  run: dict | None = None) -> Path:
    """Write ``summary.json`` and ``summary.html`` into ``out``; returns the JSON's path."""
    totals = dict(sorted(Counter(r["status"] for r in rows).items()))
    doc = {"format": SUMMARY_FORMAT, "manifest": manifest, "rows": rows, "totals": totals, "run": run or {}}
    if newly is not None:
        doc["newly_failing"] = newly
    path = write_text_atomic(out / "summary.json", json.dumps(doc, indent=2, allow_nan=False) + "\n")
    write_text_atomic(out / "summary.html", _html(doc))
    return path


def _reason_key(row: dict) -> str:
    if row["status"] == "certified":
        return "certified"
    if row["failed_criteria"]:
        return f"{row['status']}: " + ", ".join(row["failed_criteria"])
    reason = (row["reason"] or "").split(":")[0]
    return f"{row['status']}: {reason[:80]}"


_SORT_JS = """
document.querySelectorAll('table.sortable th').forEach((th, i) => th.addEventListener('click', () => {
  const body = th.closest('table').tBodies[0], up = th.dataset.dir !== 'up';
  const key = r => { const t = r.cells[i].dataset.v ?? r.cells[i].textContent; const n = parseFloat(t);
                     return isNaN(n) ? t : n; };
  [...body.rows].sort((a, b) => (key(a) > key(b) ? 1 : key(a) < key(b) ? -1 : 0) * (up ? 1 : -1))
    .forEach(r => body.appendChild(r));
  th.dataset.dir = up ? 'up' : 'down';
}));
"""


def _html(doc: dict) -> str:
    e = html.escape
    rows = doc["rows"]
    statuses = sorted({r["status"] for r in rows})
    per_scene: dict = defaultdict(Counter)
    for r in rows:
        per_scene[r["scene"]][r["status"]] += 1
    reasons = Counter(_reason_key(r) for r in rows)
    out = ["<!doctype html><html><head><meta charset='utf-8'><title>simcheck batch</title><style>",
           "body{font-family:sans-serif;margin:1.5em} table{border-collapse:collapse;margin-bottom:1.5em}"
           "td,th{border:1px solid #ccc;padding:3px 6px;font-size:13px;vertical-align:top} th{background:#eee;"
           "cursor:pointer} .certified{color:#070} .failed,.error,.timeout,.unusable{color:#b00}</style></head><body>",
           f"<h1>simcheck batch: {e(str(doc['manifest']))}</h1>",
           "<p>" + ", ".join(f"<b>{e(k)}</b> {v}" for k, v in doc["totals"].items()) + f" (of {len(rows)} tasks)</p>"]
    if doc.get("newly_failing"):
        out.append("<h2>Newly failing (certified in the baseline)</h2><ul>")
        out += [f"<li>{e(n['scene'])} {e(n['task'])}: {e(n['status'])}</li>" for n in doc["newly_failing"]]
        out.append("</ul>")
    out.append("<h2>Per scene</h2><table class='sortable'><thead><tr><th>scene</th>"
               + "".join(f"<th>{e(s)}</th>" for s in statuses) + "</tr></thead><tbody>")
    for scene, c in per_scene.items():
        out.append(f"<tr><td>{e(scene)}</td>" + "".join(f"<td>{c.get(s, 0)}</td>" for s in statuses) + "</tr>")
    out.append("</tbody></table><h2>Per outcome and reason</h2><table class='sortable'><thead><tr><th>outcome: "
               "reason or failed criteria</th><th>tasks</th></tr></thead><tbody>")
    for key, n in reasons.most_common():
        out.append(f"<tr><td>{e(key)}</td><td>{n}</td></tr>")
    out.append("</tbody></table><h2>Tasks</h2><table class='sortable'><thead><tr><th>scene</th><th>task</th>"
               "<th>status</th><th>reason</th><th>opened fraction</th><th>seconds</th><th>attempts</th>"
               "<th>certificate</th></tr></thead><tbody>")
    for r in rows:
        opened = r["criteria"].get("opened_fraction")
        opened = "" if opened is None else f"{opened:.3f}"
        seconds = "" if r["seconds"] is None else f"{r['seconds']:.2f}"
        link = (f"<a href='{e(r['certificate'])}'>certificate</a> <a href='results/{e(r['key'])}/'>files</a>"
                if r["certificate"] else f"<a href='results/{e(r['key'])}/result.json'>record</a>")
        out.append(f"<tr><td>{e(r['scene'])}</td><td>{e(r['task'])}</td><td class='{e(r['status'])}'>"
                   f"{e(r['status'])}</td><td>{e(r['reason'] or '')}</td>"
                   f"<td>{opened}</td><td>{seconds}</td><td>{r['attempts']}</td>"
                   f"<td>{link}</td></tr>")
    out.append(f"</tbody></table><script>{_SORT_JS}</script></body></html>\n")
    return "\n".join(out)


def write_junit(path: str | Path, rows: list[dict]) -> Path:
    """JUnit XML: one testcase per task (classname = scene); ``failed``, ``not_planned``, ``unreachable``
    and ``timeout`` are failures, ``error`` and ``unusable`` errors."""
    totals = Counter(r["status"] for r in rows)
    failures = sum(totals[s] for s in ("failed", "not_planned", "unreachable", "timeout"))
    errors = totals["error"] + totals["unusable"]
    suite = ET.Element("testsuite", name="simcheck batch", tests=str(len(rows)), failures=str(failures),
                       errors=str(errors), time=f"{sum(r['seconds'] or 0.0 for r in rows):.3f}")
    for r in rows:
        case = ET.SubElement(suite, "testcase", classname=str(r["scene"]), name=str(r["task"]),
                             time=f"{r['seconds'] or 0.0:.3f}")
        if r["status"] == "certified":
            continue
        tag = "error" if r["status"] in ("error", "unusable") else "failure"
        ET.SubElement(case, tag, type=r["status"], message=(r["reason"] or "")[:500]).text = r["reason"] or ""
    text = ET.tostring(ET.ElementTree(suite).getroot(), encoding="unicode")
    return write_text_atomic(path, '<?xml version="1.0" encoding="UTF-8"?>\n' + text + "\n")
