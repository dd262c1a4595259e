"""The report's tables: pipeline stages, reconstruction metrics, certificate criteria, provenance.

Every number is shown through :func:`._html.num` with a ``data-key`` that is the number's path in its
source file (``metrics.<path>`` in metrics.json, ``cert.<task>.<criterion>.<field>`` in
certificate.json), so a test can check that what the page shows is what the file says.
"""

from __future__ import annotations

from collections.abc import Mapping

from ._html import badge, esc, num, table

__all__ = ["flatten_numbers", "pipeline_table", "metrics_table", "criteria_table", "key_value_table",
           "uncertainty_table", "robust_table"]


def flatten_numbers(doc: object, prefix: str = "") -> list[tuple[str, object]]:
    """``(dotted.path, value)`` for every number/bool leaf of a JSON tree, in document order.

    List items are addressed by their ``name``/``joint``/``id`` field when they have one, else by index.
    """
    out: list[tuple[str, object]] = []
    if isinstance(doc, Mapping):
        for k, v in doc.items():
            out += flatten_numbers(v, f"{prefix}.{k}" if prefix else str(k))
    elif isinstance(doc, list):
        for i, v in enumerate(doc):
            tag = i
            if isinstance(v, Mapping):
                tag = v.get("name", v.get("joint", v.get("id", i)))
            out += flatten_numbers(v, f"{prefix}.{tag}" if prefix else str(tag))
    elif isinstance(doc, (int, float)) or doc is None and prefix:
        out.append((prefix, doc))
    return out


def pipeline_table(stages: list[Mapping]) -> str:
    """One row per stage of demo.json: name, status, seconds, message."""
    rows = []
    for st in stages:
        status = str(st.get("status", "?"))
        ok = {"ok": True, "failed": False, "unavailable": False}.get(status)
        rows.append([esc(st.get("name", "?")), badge(status, ok),
                     num(st.get("seconds"), f"demo.{st.get('name')}.seconds", "s"), esc(st.get("message", ""))])
    return table(["stage", "status", "time", "what happened"], rows, "pipeline")


#: What each summary metric of metrics.json means (shown beside it).
METRIC_MEANINGS = {
    "chamfer": "Chamfer distance in the true object's unit box, mean over objects (lower is better)",
    "iou": "volumetric IoU on a 32^3 voxel grid, mean over objects (higher is better)",
    "kinematic_map": "mean average precision of contact edges against the true part contacts",
    "missing_objects": "true objects without a reconstruction",
    "n_joints": "true joints compared (fixed included)",
    "type_accuracy": "fraction of true joints whose estimated type is right",
    "parent_accuracy": "fraction of true joints whose estimated parent part is right",
    "n_movable": "true prismatic / revolute joints",
    "median_axis_error_deg": "median angle between true and estimated axis (sign-aware), degrees",
    "median_axis_error_unsigned_deg": "same, ignoring the axis sign, degrees",
    "n_revolute": "true revolute joints",
    "median_hinge_distance_m": "median distance of the estimated hinge line from the true one, metres",
    "median_prismatic_upper_error_m": "median error of a drawer's travel, metres",
    "median_revolute_upper_error_rad": "median error of a door's opening range, radians",
}


def metrics_table(metrics: Mapping) -> str:
    """metrics.json as tables, every number keyed ``metrics.<path>``.

    Format ``partscene.metrics/1`` (written by :mod:`simcheck.demo`): a summary table, one row per
    object and one row per movable joint. Any other JSON: every numeric leaf, one row each.
    """
    if metrics.get("format") != "partscene.metrics/1":
        rows = [[esc(path), num(value, f"metrics.{path}")] for path, value in flatten_numbers(metrics)]
        return table(["metric", "value"], rows, "metrics")
    summary = metrics.get("summary", {})
    out = "<h3>Scene</h3>" + table(
        ["metric", "value", "meaning"],
        [[esc(k), num(v, f"metrics.summary.{k}", _unit_of_name(k)), esc(METRIC_MEANINGS.get(k, ""))]
         for k, v in summary.items()],
        "metrics")
    cols = ("chamfer", "iou", "ap")
    out += "<h3>Objects</h3>" + table(
        ["object", "category", "status", "Chamfer (unit box)", "IoU", "contact AP"],
        [[esc(o.get("name")), esc(o.get("category", "")), esc(o.get("status", ""))]
         + [num(o.get(c), f"metrics.objects.{o.get('name')}.{c}") for c in cols] for o in metrics.get("objects", [])],
        "metrics")
    jcols = (("axis_error_deg", "deg"), ("hinge_distance_m", "m"), ("upper_error", None))
    out += "<h3>Movable joints</h3>" + table(
        ["joint", "true type", "estimated type", "axis error", "hinge distance", "range error"],
        [[f"<code>{esc(j.get('name'))}</code>", esc(j.get("true_type", "")), esc(j.get("est_type", "") or "missing")]
         + [num(j.get(c), f"metrics.joints.{j.get('name')}.{c}",
                unit or ("m" if j.get("true_type") == "prismatic" else "rad"))
            for c, unit in jcols] for j in metrics.get("joints", [])],
        "metrics")
    return out


def _unit_of_name(name: str) -> str:
    """The unit a metric's name ends with (``..._deg``, ``..._m``, ``..._rad``), else ""."""
    for suffix, unit in (("_deg", "deg"), ("_m", "m"), ("_rad", "rad")):
        if name.endswith(suffix):
            return unit
    return ""


def key_value_table(doc: Mapping, key_prefix: str, units: Mapping[str, str] | None = None) -> str:
    """A two-column table of a flat-ish mapping (numbers tagged, with their unit from ``units``; other
    values as text)."""
    rows = []
    for k, v in doc.items():
        if isinstance(v, (int, float)) or v is None:
            rows.append([esc(k), num(v, f"{key_prefix}.{k}", (units or {}).get(k, ""))])
        else:
            rows.append([esc(k), esc(v)])
    return table(["", ""], rows, "kv")


def criteria_table(task_key: str, criteria: list[Mapping]) -> str:
    """One row per certificate criterion: passed, value, threshold, margin (+ what it means)."""
    rows = []
    for c in criteria:
        name = str(c.get("name", "?"))
        key = f"cert.{task_key}.{name}"
        passed = c.get("passed")
        unit = str(c.get("unit", "") or "").replace("|", " or ")   # "rad|m" in certificates before units per joint
        result = badge("n/a", None) if passed is None else badge("pass" if passed else "fail", passed)
        rows.append([esc(name), result,
                     num(c.get("value"), key + ".value", unit), esc(c.get("comparison", "")),
                     num(c.get("threshold"), key + ".threshold", unit), num(c.get("margin"), key + ".margin", unit),
                     esc(c.get("description", "")) + (f"<br><i>{esc(c['detail'])}</i>" if c.get("detail") else "")])
    return table(["criterion", "result", "value", "", "threshold", "margin", "meaning"], rows, "criteria")


def uncertainty_table(graph: Mapping) -> str:
    """One row per movable joint of graph.json with an ``uncertainty`` block (recon's bootstrap spreads),
    every number keyed ``graph.<joint>.uncertainty.<field>``; "" when no joint has one."""
    rows = []
    for obj in graph.get("objects", []) if isinstance(graph, Mapping) else []:
        for j in obj.get("joints", []):
            u = j.get("uncertainty")
            if not isinstance(u, Mapping):
                continue
            key = f"graph.{j.get('name')}.uncertainty"
            unit = "m" if j.get("type") == "prismatic" else "rad"
            rows.append([f"<code>{esc(j.get('name'))}</code>", esc(j.get("type", "")),
                         num(u.get("axis_deg"), key + ".axis_deg", "deg"), num(u.get("origin_m"), key + ".origin_m", "m"),
                         num(u.get("upper"), key + ".upper", unit),
                         "undecided" if u.get("side_undecided") is True else "",
                         num(u.get("samples"), key + ".samples"), esc(u.get("method", ""))])
    if not rows:
        return ""
    return ("<h3>How sure the reconstruction is of each joint</h3>"
            "<p>RMS spread over resamplings of the scan points (recon's bootstrap): axis direction, axis "
            "position across the axis, upper limit; a door's hinge side when the scan does not decide it (a "
            "robust certificate hinges half of its worlds at the other edge).</p>"
            + table(["joint", "type", "axis", "position", "upper limit", "hinge side", "samples", "method"], rows,
                    "uncertainty"))


def _other_side(failure: Mapping) -> str:
    p = failure.get("perturbation")
    return ("<b>hinged at the door's other edge</b> (the scan does not decide its side): "
            if isinstance(p, Mapping) and p.get("hinge_side") == "other" else "")


def robust_table(task_key: str, robust: Mapping | None) -> str:
    """A task's ``robust`` block (``--robust N``): successes, the 95 % lower bound, the worst margin of each
    criterion and one row per failing sample (replay it with ``--replay-sample``); "" without one."""
    if not isinstance(robust, Mapping):
        return ""
    key = f"cert.{task_key}.robust"
    head = (f"<p>Robust: {num(robust.get('successes'), key + '.successes')} of "
            f"{num(robust.get('samples'), key + '.samples')} sampled worlds opened it; with "
            f"{num(robust.get('confidence'), key + '.confidence')} confidence at least "
            f"{num(robust.get('success_lower_bound'), key + '.success_lower_bound')} of the worlds consistent "
            "with the scan do.</p>")
    worst = robust.get("worst_margins") or {}
    out = head + table(["criterion", "worst margin over the samples"],
                       [[esc(k), num(v, f"{key}.worst_margins.{k}")] for k, v in worst.items()], "robust")
    fails = [f for f in robust.get("failures", []) if isinstance(f, Mapping)]
    if fails:
        out += table(["failing sample", "outcome", "reason (replay with --replay-sample)"],
                     [[esc(f.get("sample")), esc(f.get("outcome", "")), _other_side(f) + esc(f.get("reason", ""))]
                      for f in fails], "robust")
    return out
