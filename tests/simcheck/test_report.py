"""report.html, looked at in headless Chromium: every image decodes and is not blank, and every number the
page shows equals the one in certificate.json / metrics.json.

Chromium is driven through its command line only (``--dump-dom`` after a probe script measured the page,
then ``--screenshot``); no selenium. Skipped, with the reason, only when /usr/bin/chromium is absent.
"""

from __future__ import annotations

import base64
import io
import json
import math
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from simcheck.report import ArtifactError, render_report

FIXTURE = Path(__file__).with_name("test_simcheck_report_data")
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--hide-scrollbars", "--force-device-scale-factor=1"]
WIDTH = 1280
#: An image region whose pixel standard deviation (0-255 grey levels) is below this is blank.
MIN_PIXEL_STD = 4.0

# Appended to a COPY of the report (the report itself has no script): measures every image and number.
PROBE = """
<script>
window.addEventListener('load', () => {
  const imgs = [...document.images].map(im => {
    const r = im.getBoundingClientRect();
    return {figure: im.dataset.figure, text: im.dataset.minTextPx, complete: im.complete,
            w: im.naturalWidth, h: im.naturalHeight,
            x: r.left + window.scrollX, y: r.top + window.scrollY, rw: r.width, rh: r.height};
  });
  const nums = [...document.querySelectorAll('[data-key]')].map(e => [e.dataset.key, e.textContent]);
  const fonts = [...document.querySelectorAll('body *')]
    .filter(e => [...e.childNodes].some(n => n.nodeType === 3 && n.textContent.trim()))
    .map(e => [e.tagName + ': ' + e.textContent.trim().slice(0, 40), parseFloat(getComputedStyle(e).fontSize)]);
  const pre = document.createElement('pre');
  pre.id = 'probe';
  pre.textContent = JSON.stringify({imgs, nums, fonts, height: document.documentElement.scrollHeight});
  document.body.appendChild(pre);
});
</script>
"""


def _chromium(args: list[str], profile: Path, timeout: float = 90) -> subprocess.CompletedProcess:
    return subprocess.run([CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", *args],
                          capture_output=True, text=True, timeout=timeout, check=False)


def _demo_dir(tmp_path: Path) -> Path:
    """A copy of the committed demo artifacts (the renderer must not need to write beside inputs)."""
    dst = tmp_path / "demo"
    shutil.copytree(FIXTURE, dst)
    return dst


@pytest.fixture(scope="module")
def rendered(tmp_path_factory) -> dict:
    """Render the fixture demo once, then probe it in Chromium and screenshot it."""
    if CHROMIUM is None:
        pytest.skip("chromium is not installed (apt-get install chromium chromium-driver; `make setup` does)")
    tmp = tmp_path_factory.mktemp("report")
    demo = _demo_dir(tmp)
    before = {p: p.read_bytes() for p in demo.rglob("*") if p.is_file()}
    html_path = render_report(demo)
    after = {p: p.read_bytes() for p in demo.rglob("*") if p.is_file() and p != html_path}
    html = html_path.read_text()
    probe_path = demo / "probe.html"
    probe_path.write_text(html.replace("</body>", PROBE + "</body>"))
    with tempfile.TemporaryDirectory() as profile:
        dom = _chromium([f"--window-size={WIDTH},2000", "--virtual-time-budget=10000", "--dump-dom",
                         probe_path.as_uri()], Path(profile))
    m = re.search(r'<pre id="probe">(.*?)</pre>', dom.stdout, re.S)
    assert m, f"chromium did not run the probe: rc={dom.returncode} stderr={dom.stderr[-2000:]}"
    probe = json.loads(m.group(1).replace("&quot;", '"').replace("&lt;", "<").replace("&gt;", ">")
                       .replace("&amp;", "&"))
    height = int(probe["height"]) + 10
    shot = tmp / "report.png"
    with tempfile.TemporaryDirectory() as profile:
        res = _chromium([f"--window-size={WIDTH},{height}", f"--screenshot={shot}", html_path.as_uri()],
                        Path(profile))
    assert shot.exists(), f"no screenshot: rc={res.returncode} stderr={res.stderr[-2000:]}"
    return {"demo": demo, "html": html, "probe": probe, "screenshot": Image.open(shot).convert("RGB"),
            "inputs_before": before, "inputs_after": after}


def test_report_is_self_contained(rendered):
    html = rendered["html"]
    assert "<script" not in html.lower(), "the report must work without JavaScript"
    assert not re.search(r'(src|href)\s*=\s*"(?!data:|#)', html), "every src/href must be a data URI or an anchor"
    assert "http://" not in html and "https://" not in html


def test_every_image_decodes_and_is_not_blank_in_chromium(rendered):
    imgs, shot = rendered["probe"]["imgs"], rendered["screenshot"]
    figures = {im["figure"] for im in imgs}
    # the story: scan, recon beside truth, a part tree per object, and per task an opening plot + key frames
    assert {"scan", "scene"} <= figures
    assert any(f.startswith("tree.") for f in figures)
    cert = json.loads((rendered["demo"] / "certificate.json").read_text())
    assert any(t.get("rollout") for t in cert["tasks"]), "the fixture must hold an executed task"
    for task in cert["tasks"]:
        if task.get("rollout"):
            assert f"task.{task['joint']}.opening" in figures, task["joint"]
            assert f"task.{task['joint']}.frames" in figures, task["joint"]
    assert shot.width == WIDTH
    for im in imgs:
        assert im["complete"] and im["w"] > 0 and im["h"] > 0, f"image {im['figure']} did not decode: {im}"
        assert im["rw"] > 50 and im["rh"] > 50, f"image {im['figure']} is drawn too small: {im}"
        box = (int(im["x"]), int(im["y"]), int(im["x"] + im["rw"]), int(im["y"] + im["rh"]))
        assert box[3] <= shot.height, f"image {im['figure']} is outside the screenshot {shot.size}"
        region = np.asarray(shot.crop(box).convert("L"), dtype=float)
        assert region.std() > MIN_PIXEL_STD, f"image {im['figure']} looks blank on screen (std {region.std():.2f})"


def test_every_image_data_uri_is_a_non_blank_png(rendered):
    uris = re.findall(r'<img src="data:image/png;base64,([^"]+)"', rendered["html"])
    assert len(uris) == len(rendered["probe"]["imgs"])
    for b64 in uris:
        im = Image.open(io.BytesIO(base64.b64decode(b64)))
        assert im.format == "PNG"
        assert np.asarray(im.convert("L"), dtype=float).std() > MIN_PIXEL_STD


def _lookup(doc, path: list[str]):
    """Walk a JSON tree by dotted components; list items match their name/joint/id field, else index."""
    for comp in path:
        if isinstance(doc, dict):
            assert comp in doc, f"key {comp!r} not in {sorted(doc)}"
            doc = doc[comp]
        else:
            match = [x for x in doc if isinstance(x, dict) and str(x.get("name", x.get("joint", x.get("id")))) == comp]
            doc = match[0] if match else doc[int(comp)]
    return doc


def _shown_equals(text: str, value) -> bool:
    if value is None:
        return text == "–"
    if isinstance(value, bool):
        return text == ("yes" if value else "no")
    if isinstance(value, float) and math.isinf(value):
        return text == ("inf" if value > 0 else "-inf")
    shown = float(text)
    return math.isclose(shown, float(value), rel_tol=5e-4, abs_tol=1e-12)  # 4 significant digits


def test_numbers_shown_equal_the_certificate_and_metrics(rendered):
    demo = rendered["demo"]
    cert = json.loads((demo / "certificate.json").read_text())
    metrics = json.loads((demo / "metrics.json").read_text())
    shown = dict(rendered["probe"]["nums"])
    assert len(shown) == len(rendered["probe"]["nums"]), "two numbers share one data-key"
    # every criterion of every task is on the page with its value, threshold and margin ...
    for task in cert["tasks"]:
        for crit in task["criteria"]:
            for fld in ("value", "threshold", "margin"):
                key = f"cert.{task['joint']}.{crit['name']}.{fld}"
                assert key in shown, f"{key} is not shown"
                assert _shown_equals(shown[key], crit[fld]), f"{key}: page shows {shown[key]!r}, file has {crit[fld]!r}"
    # ... and every number on the page is the one in its file
    n_checked = 0
    for key, text in shown.items():
        source, *path = key.split(".")
        if source == "cert" and path[0] not in ("criteria", "seeds", "versions", "timings"):
            task = next(t for t in cert["tasks"] if t["joint"] == path[0])
            if path[1] in task and not isinstance(task[path[1]], list):  # a task field: amount, timings.total
                value = _lookup(task, path[1:])
            else:
                crit = next(c for c in task["criteria"] if c["name"] == path[1])
                value = crit[path[2]]
        elif source == "cert":
            value = _lookup(cert, path)
        elif source == "metrics":
            value = _lookup(metrics, path)
        else:
            continue  # demo.* stage timings come from demo.json
        assert _shown_equals(text, value), f"{key}: page shows {text!r}, file has {value!r}"
        n_checked += 1
    assert n_checked >= 10


def test_screenshot_is_the_report_not_an_error_page(rendered):
    shot = np.asarray(rendered["screenshot"].convert("L"), dtype=float)
    assert shot.shape[0] > 2000, "the report should be a long page of figures and tables"
    assert shot.std() > 20


def test_malformed_certificate_is_rejected_naming_the_file(tmp_path):
    demo = _demo_dir(tmp_path)
    (demo / "certificate.json").write_text(json.dumps({"tasks": {"not": "a list"}}))
    with pytest.raises(ArtifactError, match=r"certificate\.json.*'tasks'"):
        render_report(demo)


def test_invalid_json_is_rejected_naming_the_file(tmp_path):
    demo = _demo_dir(tmp_path)
    (demo / "metrics.json").write_text("{not json")
    with pytest.raises(ArtifactError, match=r"metrics\.json: not valid JSON"):
        render_report(demo)


def test_bad_truth_shape_is_rejected_naming_object_and_part(tmp_path):
    demo = _demo_dir(tmp_path)
    truth = json.loads((demo / "truth" / "truth.json").read_text())
    obj = truth["objects"][0]
    part = obj["parts"][0]
    part["shapes"][0] = {"type": "box", "size": [0.1, -0.2, 0.3], "T_part_shape": np.eye(4).tolist()}
    (demo / "truth" / "truth.json").write_text(json.dumps(truth))
    with pytest.raises(ArtifactError, match=rf"truth\.json: object {obj['name']} part {part['link']} shape 0: bad box shape"):
        render_report(demo)


def test_missing_demo_dir_is_rejected(tmp_path):
    with pytest.raises(ArtifactError, match="demo directory does not exist"):
        render_report(tmp_path / "nope")


def test_missing_artifacts_are_announced_not_invented(tmp_path):
    demo = _demo_dir(tmp_path)
    for name in ("certificate.json", "graph.json", "scene.urdf", "metrics.json", "truth/scan.npz"):
        (demo / name).unlink()
    shutil.rmtree(demo / "rollouts", ignore_errors=True)
    html = render_report(demo).read_text()
    for what, name in (("the certificate", "certificate.json"), ("the scan", "scan.npz"),
                       ("the reconstruction", "scene.urdf"), ("the estimated part trees", "graph.json"),
                       ("the metrics", "metrics.json")):
        assert f"Not available: {what} ({name} was not found" in html, what
    assert 'data-key="cert.' not in html and 'data-key="metrics.' not in html
    assert 'data-figure="scene"' in html  # the truth alone is still drawn


def test_inputs_are_not_modified(rendered):
    assert rendered["inputs_before"] == rendered["inputs_after"]


def test_part_tree_reads_joints_and_keeps_non_tree_contacts_apart():
    from simcheck.report._part_tree_image import trees_from_scene_json

    doc = {"objects": [{"name": "cabinet3", "category": "cabinet",
                        "parts": [{"part_id": 11, "label": "body"}, {"part_id": 12, "label": "drawer"},
                                  {"part_id": 13, "label": "handle"}],
                        "joints": [{"name": "cabinet3_body11_joint", "type": "fixed", "parent_part_id": None,
                                    "child_part_id": 11},
                                   {"name": "cabinet3_drawer12_joint", "type": "prismatic", "parent_part_id": 11,
                                    "child_part_id": 12, "contact_score": 0.9},
                                   {"name": "cabinet3_handle13_joint", "type": "fixed", "parent_part_id": 12,
                                    "child_part_id": 13, "contact_score": 0.7}],
                        "contacts": [{"parent_part_id": 11, "child_part_id": 12, "score": 0.9},
                                     {"parent_part_id": 11, "child_part_id": 13, "score": 0.2},
                                     {"parent_part_id": 13, "child_part_id": 11, "score": 0.4}]}]}
    (tree,) = trees_from_scene_json(doc, "graph.json")
    assert sorted(tree.graph.edges(data="type")) == [(11, 12, "prismatic"), (12, 13, "fixed")]
    assert tree.graph.edges[11, 12]["score"] == pytest.approx(0.9)
    assert tree.other_contacts == ((11, 13, 0.4),)  # best score of the pair, tree edges left out


def test_part_tree_rejects_a_joint_naming_a_missing_part():
    from simcheck.report._part_tree_image import trees_from_scene_json

    doc = {"objects": [{"name": "cabinet3", "parts": [{"id": 11, "label": "body"}],
                        "joints": [{"name": "cabinet3_drawer12_joint", "type": "prismatic", "parent_part_id": 11,
                                    "child_part_id": 12}]}]}
    with pytest.raises(ArtifactError,
                       match=r"graph\.json: object cabinet3: joint 'cabinet3_drawer12_joint' names part 12"):
        trees_from_scene_json(doc, "graph.json")


def test_all_text_is_at_least_12_px_at_100_percent_zoom(rendered):
    """Page text by its computed font size; text inside a figure by the PNG's smallest text (recorded
    when it was drawn) times how much the page scales the image."""
    from simcheck.report._figure import MIN_TEXT_PX

    small = [(what, px) for what, px in rendered["probe"]["fonts"] if px < MIN_TEXT_PX]
    assert not small, f"page text under {MIN_TEXT_PX} px: {small[:5]}"
    for im in rendered["probe"]["imgs"]:
        assert im["text"], f"figure {im['figure']} does not record its smallest text"
        shown = float(im["text"]) * im["rw"] / im["w"]
        assert shown >= MIN_TEXT_PX - 0.01, f"figure {im['figure']}: smallest text {shown:.1f} px on the page"


def test_units_are_shown_and_small_values_are_readable(rendered):
    html = rendered["html"]
    assert "rad|m" not in html
    shown = [text for _, text in rendered["probe"]["nums"]]
    assert not [t for t in shown if re.search(r"e-(0[7-9]|[1-9]\d)", t)], "a value below 1e-6 in e-notation"
    assert 'data-key="cert.cabinet1_drawer4_joint.settled_linear_speed.value"' in html
    m = re.search(r'data-key="cert.cabinet1_drawer4_joint.handle_path_deviation.value">[^<]*</span>&nbsp;(\w+)', html)
    assert m and m.group(1) == "m"


def test_the_report_lists_the_movable_joints_not_tested_and_why(rendered):
    from simcheck.scene_joints import read_scene_joints

    html = rendered["html"]
    cert = json.loads((rendered["demo"] / "certificate.json").read_text())
    tested = {t["joint"] for t in cert["tasks"]}
    movable = {n for n, j in read_scene_joints(rendered["demo"] / "scene.urdf").items()
               if j.type in ("prismatic", "revolute")}
    assert "<h3>Movable joints not tested</h3>" in html
    assert movable - tested, "the fixture tests every joint: nothing to list"
    for joint in movable - tested:
        assert f"<td><code>{joint}</code></td><td>not requested (no task names it)</td>" in html


def test_the_report_says_what_a_certificate_does_not_promise_as_the_readme_does(rendered):
    from simcheck.report._promises import DOES_NOT_PROMISE

    readme = " ".join((Path(__file__).parents[2] / "README.md").read_text().split())
    assert " ".join(DOES_NOT_PROMISE.split()) in readme
    assert "What a certificate does not promise</h2><p>A certificate does <b>not</b> promise" in rendered["html"]
