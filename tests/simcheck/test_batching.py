"""``simcheck batch`` on a local Ray (started once for the module, 2 CPUs, no dashboard): a 2-scene
manifest end to end (certificates equal to a plain certify), resume after ``kill -9`` of the driver,
faults that stay local to their task, and malformed manifests rejected before anything starts."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest

ray = pytest.importorskip("ray")

import scenes  # noqa: E402
import simcheck  # noqa: E402
from simcheck.batching.manifest import ManifestError, read_manifest  # noqa: E402
from simcheck.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
DRAWER, DOOR = "open-drawer:cabinet1_drawer4_joint", "open-door:cabinet1_door2_joint"


@pytest.fixture(scope="module")
def kitchens(tmp_path_factory):
    d = tmp_path_factory.mktemp("kitchens")
    for seed in (0, 1):   # kitchen 1 is also scanned: the manifest reconstructs it
        scenes.make_scene("kitchen", seed=seed, scan=seed == 1, previews=False, out=d / f"k{seed}")
    return d


@pytest.fixture(scope="module")
def local_ray():
    ray.init(address="local", num_cpus=2, include_dashboard=False, log_to_driver=False, logging_level="ERROR")
    yield
    ray.shutdown()


def _manifest(path: Path, entries: list[dict]) -> Path:
    path.write_text("\n".join(json.dumps(e) for e in entries) + "\n")
    return path


def _movable(urdf: Path, n: int) -> list[str]:
    from simcheck.batching.runner import all_movable_tasks
    return sorted(all_movable_tasks(urdf)[0])[:n]


def test_two_scene_manifest_end_to_end(kitchens, local_ray, tmp_path):
    # the reconstruction's cabinet1_door8 is hinged 0.7 cm off: it pulls 79 N, more than the gripper holds with margin
    tasks1 = [t for t in _movable(kitchens / "k1/truth.urdf", 9) if "door8" not in t and "door21" not in t][:2]
    manifest = tmp_path / "m.yaml"
    manifest.write_text(f"""
- scene: {kitchens}/k0/truth.urdf
  tasks: [{DRAWER}, {DOOR}]
- scan: {kitchens}/k1/scan.ply          # reconstructed once, certified against its truth
  labels: {kitchens}/k1/labels.json
  truth: {kitchens}/k1/truth.urdf
  tasks: [{tasks1[0]}, {tasks1[1]}]
""")
    out = tmp_path / "out"
    result = simcheck.batch(manifest, out, workers=2, junit=tmp_path / "junit.xml", progress=False)
    assert result.exit_code == 0, result.rows
    assert result.totals == {"certified": 4}
    assert (result.computed, result.resumed) == (4, 0)
    doc = json.loads((out / "summary.json").read_text())
    assert [r["task"] for r in doc["rows"]] == [DRAWER, DOOR, *tasks1]
    assert [r["line"] for r in doc["rows"]] == [2, 2, 4, 4]
    assert len(list((out / "scans").glob("*/scene.urdf"))) == 1
    assert doc["totals"] == {"certified": 4}
    assert "<table class='sortable'>" in (out / "summary.html").read_text()
    assert 'tests="4"' in (tmp_path / "junit.xml").read_text()
    # a row's certificate is what a plain certify of that task gives
    row = doc["rows"][1]
    batch_task = simcheck.Certificate.load(out / row["certificate"]).tasks[0]
    plain = simcheck.certify(kitchens / "k0/truth.urdf", [DOOR], seed=0, images=False).tasks[0]
    assert batch_task.status == plain.status
    for a, b in zip(batch_task.criteria, plain.criteria, strict=True):
        assert a.name == b.name and a.value == pytest.approx(b.value, abs=1e-9), a.name
    # a rerun computes nothing, and compares with a baseline
    again = simcheck.batch(manifest, out, workers=2, baseline=out / "summary.json", progress=False)
    assert (again.computed, again.resumed, again.newly_failing) == (0, 4, [])


@pytest.mark.parametrize("chunk", [None, 4])
def test_faults_stay_local_to_their_task(kitchens, local_ray, tmp_path, monkeypatch, chunk):
    """Faults, one task per Ray task (the guided size for 4 tasks) or all four in one: a segfault blames
    only the task that was running (retried once, then recorded); the tasks after it run once."""
    monkeypatch.setenv("SIMCHECK_BATCH_TEST_FAULTS", "1")
    scene = str(kitchens / "k0/truth.urdf")
    manifest = _manifest(tmp_path / "m.jsonl", [
        {"scene": scene, "tasks": [DRAWER]},
        {"scene": scene, "tasks": [DOOR], "_fault": "segfault"},
        {"scene": scene, "tasks": [DOOR], "_fault": "raise", "seed": 1},
        {"scene": scene, "tasks": [DOOR], "_fault": "memory", "seed": 3},
    ])
    result = simcheck.batch(manifest, tmp_path / "out", workers=2, task_memory=1500, retries=1, progress=False,
                            chunk=chunk)
    rows = {(r["line"]): r for r in result.rows}
    assert rows[1]["status"] == "certified" and rows[1]["attempts"] == 1
    assert rows[2]["status"] == "error" and rows[2]["attempts"] == 2 and "worker died" in rows[2]["reason"]
    assert rows[3]["status"] == "error" and rows[3]["attempts"] == 1 and "test fault" in rows[3]["reason"]
    assert rows[4]["status"] == "error" and "--task-memory 1500" in rows[4]["reason"]
    assert result.retried == 1
    assert result.exit_code == 3
    # a task that hangs is stopped at its time budget, and its worker serves the next task
    hang = _manifest(tmp_path / "hang.jsonl", [{"scene": scene, "tasks": [DOOR], "_fault": "hang"}])
    result = simcheck.batch(hang, tmp_path / "out", workers=2, task_timeout=2, progress=False)
    assert result.rows[0]["status"] == "timeout" and "--task-timeout 2" in result.rows[0]["reason"]
    assert result.exit_code == 1


def test_malformed_entry_exits_2_naming_line_and_field(kitchens, tmp_path, capsys):
    manifest = tmp_path / "bad.yaml"
    manifest.write_text(f"""- scene: {kitchens}/k0/truth.urdf
  tasks: [{DRAWER}]
- scene: {kitchens}/k0/truth.urdf
  seed: 0
  tasks: [open-drawer:no_such_joint]
""")
    out = tmp_path / "out"
    assert main(["batch", str(manifest), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{manifest}:5: field 'tasks'" in err and "no_such_joint" in err
    assert not out.exists()   # nothing started


@pytest.mark.parametrize("text,where", [
    ("- scene: {k}/k0/truth.urdf\n  tasks: all-movable\n  sede: 1\n", r":3: field 'sede': unknown field \(did you mean 'seed'\?\)"),
    ("- scene: {k}/k0/missing.urdf\n", ":1: field 'scene': file"),
    ("- scene: {k}/k0\n", ":1: field 'scene': .*/k0 is a folder, not a file"),
    ("- scan: {k}/k0/truth.urdf\n  tasks: all-movable\n", ":1: field 'labels' is missing"),
    ("- scene: {k}/k0/truth.urdf\n  seed: -1\n", ":2: field 'seed'"),
    ("- scene: {k}/k0/truth.urdf\n  _fault: segfault\n", ":2: field '_fault': unknown field"),
    ("- scene: {k}/k0/truth.urdf\n  robust: 0\n", ":2: field 'robust'"),
    ("- scene: {k}/k0/truth.urdf\n  robust: 5\n  min_success: 2\n", ":3: field 'min_success'"),
])
def test_manifest_errors_name_line_and_field(kitchens, tmp_path, text, where):
    manifest = tmp_path / "m.yaml"
    manifest.write_text(text.format(k=kitchens))
    with pytest.raises(ManifestError, match=f"{manifest}{where}"):
        read_manifest(manifest)


def test_json_lines_manifest_and_all_movable(kitchens, tmp_path):
    manifest = _manifest(tmp_path / "m.jsonl", [{"scene": str(kitchens / "k0/truth.urdf"), "tasks": "all-movable"}])
    (entry,) = read_manifest(manifest)
    assert entry.line == 1 and entry.tasks is None and entry.seed == 0


def _ray_descendants(pid: int) -> list[psutil.Process]:
    try:
        return [p for p in psutil.Process(pid).children(recursive=True)]
    except psutil.NoSuchProcess:
        return []


def _cmdline(proc: psutil.Process) -> str:
    try:
        return " ".join(proc.cmdline())
    except psutil.Error:    # it ended in between
        return ""


def test_resume_after_the_driver_is_killed(kitchens, local_ray, tmp_path):
    scene = kitchens / "k1/truth.urdf"
    tasks = _movable(scene, 6)
    manifest = _manifest(tmp_path / "m.jsonl", [{"scene": str(scene), "tasks": tasks}])
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    driver = subprocess.Popen([sys.executable, "-m", "simcheck", "batch", str(manifest), "--out", str(out),
                               "--workers", "2", "-q"], env=env, cwd=tmp_path,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    results = out / "results"
    deadline = time.monotonic() + 240
    while time.monotonic() < deadline and len(list(results.glob("*/result.json"))) < 2:
        assert driver.poll() is None, "the driver ended before it was killed"
        time.sleep(0.2)
    ray_procs = _ray_descendants(driver.pid)
    # the local Ray runs without the autoscaler's monitor and the log monitor (runner._without_monitors)
    assert ray_procs and not [c for c in map(_cmdline, ray_procs) if "monitor.py" in c]
    driver.send_signal(signal.SIGKILL)
    driver.wait()
    # no Ray process of the killed driver outlives it (its guardian ends them)
    gone, alive = psutil.wait_procs(ray_procs, timeout=20)
    assert not alive, [p.cmdline()[:1] for p in alive]
    before = {p.parent.name: p.stat().st_mtime_ns for p in results.glob("*/result.json")}
    assert 2 <= len(before) < len(tasks)

    result = simcheck.batch(manifest, out, workers=2, progress=False)
    after = {p.parent.name: p.stat().st_mtime_ns for p in results.glob("*/result.json")}
    assert result.resumed == len(before) and result.computed == len(tasks) - len(before)   # none done twice
    assert len(after) == len(tasks) and {k: after[k] for k in before} == before              # none lost
    assert result.totals == {"certified": len(tasks)}
    assert not list(results.glob(".tmp-*"))


def test_a_robust_entry_runs_certify_robustly_with_certifys_own_settings(tmp_path, monkeypatch):
    """A manifest entry with ``robust: N`` calls certify_robustly with every setting plain certify would use
    (criteria, physics, planner_config: certify's defaults), in the worker's one process slot."""
    import inspect

    import simcheck.robust
    from simcheck.batching.worker import certify_job
    from simcheck.certification import certify
    from simcheck.errors import SimcheckInputError

    real, seen = simcheck.robust.certify_robustly, {}

    def fake(*args, **kwargs):
        seen.update(inspect.signature(real).bind(*args, **kwargs).arguments)   # TypeError if one is missing
        raise SimcheckInputError("reached certify_robustly")

    monkeypatch.setattr(simcheck.robust, "certify_robustly", fake)
    job = {"store": str(tmp_path / "store"), "key": "k", "scene": str(tmp_path / "scene.urdf"), "against": None,
           "task": DRAWER, "robot": "default", "seed": 0, "amount": None, "images": False, "timeout": None,
           "memory_mb": None, "attempt": 1, "robust": 3, "min_success": 0.9, "fault": None, "row": {}}
    rec = certify_job(job)
    assert (rec["status"], rec["reason"]) == ("unusable", "reached certify_robustly")
    defaults = inspect.signature(certify).parameters
    for name in ("criteria", "physics", "planner_config"):
        assert seen[name] == defaults[name].default
    assert (seen["robust"], seen["workers"]) == (3, 1)


def test_all_movable_records_a_joint_without_opening_range_as_unusable(kitchens, tmp_path):
    """``tasks: all-movable`` expands with planners.movable_joint_tasks; a movable joint it leaves out (no
    opening range) becomes an ``unusable`` row naming why, decided without running."""
    from simcheck.batching.runner import RunSettings, jobs_for_entries
    from simcheck.batching.store import Store

    text = (kitchens / "k0/truth.urdf").read_text()
    joint = text.index('<joint name="cabinet1_door2_joint"')
    limit = text.index("<limit", joint)
    end = text.index("/>", limit)
    scene = tmp_path / "scene.urdf"
    scene.write_text(text[:limit] + '<limit lower="0" upper="0" effort="50" velocity="1"' + text[end:])
    jobs = jobs_for_entries(read_manifest(_manifest(tmp_path / "m.jsonl", [{"scene": str(scene)}])),
                            Store(tmp_path / "out"), RunSettings())
    rows = {j.row["task"]: j.fixed for j in jobs}
    assert len(rows) == 7 and rows[DRAWER] is None
    assert rows[DOOR]["status"] == "unusable" and "no opening range" in rows[DOOR]["reason"]


def test_chunks_are_guided_by_the_queue_and_keep_to_one_scene():
    from collections import deque

    from simcheck.batching.runner import MAX_CHUNK, Job, _next_chunk, chunk_size

    assert chunk_size(1000, 2) == MAX_CHUNK and chunk_size(40, 2) == 5 and chunk_size(7, 2) == 1
    queue = deque(Job(str(i), {}, {"scene": "a" if i < 3 else "b", "against": None}) for i in range(6))
    assert [j.key for j in _next_chunk(queue, 5)] == ["0", "1", "2"]      # the scene ends the chunk
    assert [j.key for j in _next_chunk(queue, 2)] == ["3", "4"] and len(queue) == 1
