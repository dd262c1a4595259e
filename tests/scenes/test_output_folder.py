"""scenes.output_folder: --out written as a whole; a same-input rerun replaces it, anything else is refused
unless overwrite; a failure, Ctrl-C or a full disk leaves no partial file and the folder as it was."""

import errno
import hashlib
import json
import os

import pytest

from scenes.output_folder import RUN_RECORD, OutputFolderError, output_folder


@pytest.fixture
def scan(tmp_path):
    p = tmp_path / "scan.ply"
    p.write_text("points")
    return p


def _run(out, scan, files=("scene.urdf",), seed=0, overwrite=False, verdict=None):
    with output_folder(out, "recon build", inputs={"scan": scan, "labels": None}, settings={"seed": seed},
                       overwrite=overwrite, verdict=verdict) as staging:
        assert staging != out and staging.parent == out.parent
        for name in files:
            (staging / name).parent.mkdir(parents=True, exist_ok=True)
            (staging / name).write_text(f"{name} seed {seed}")
    return out


def _leftovers(tmp_path):
    return [p.name for p in tmp_path.iterdir() if ".partial-" in p.name or ".old-" in p.name]


def test_a_new_folder_holds_the_files_and_the_run_record(tmp_path, scan):
    out = _run(tmp_path / "out", scan, files=("scene.urdf", "rollouts/a.npz"))
    record = json.loads((out / RUN_RECORD).read_text())
    assert record["command"] == "recon build" and record["settings"] == {"seed": 0}
    assert record["inputs"]["scan"]["sha256"] == hashlib.sha256(b"points").hexdigest()
    assert sorted(record["files"]) == ["rollouts/a.npz", "scene.urdf"]
    umask = os.umask(0)
    os.umask(umask)
    assert os.stat(out).st_mode & 0o777 == 0o777 & ~umask     # an ordinary folder, not mkdtemp's 0700
    assert _leftovers(tmp_path) == []


def test_a_rerun_with_the_same_inputs_replaces_the_folder_and_leaves_no_stale_file(tmp_path, scan):
    out = _run(tmp_path / "out", scan, files=("certificate.json", "images/door_start.png"))
    _run(out, scan, files=("certificate.json",))
    assert sorted(p.name for p in out.rglob("*")) == sorted([RUN_RECORD, "certificate.json"])
    assert _leftovers(tmp_path) == []


@pytest.mark.parametrize("change, message", [
    ("content", r"it holds a run on another scan \(.*scan.ply\)"),
    ("seed", r"it holds a run with seed = 0 \(this run: 1\)"),
])
def test_a_different_earlier_run_is_refused_unless_overwrite(tmp_path, scan, change, message):
    out = _run(tmp_path / "out", scan)
    seed = 0
    if change == "content":
        scan.write_text("other points")
    else:
        seed = 1
    with pytest.raises(OutputFolderError, match=message):
        _run(out, scan, seed=seed)
    assert (out / "scene.urdf").read_text() == "scene.urdf seed 0"
    _run(out, scan, seed=seed, overwrite=True)
    assert (out / "scene.urdf").read_text() == f"scene.urdf seed {seed}"


@pytest.mark.parametrize("name", ["scene.urdf", "truth.urdf", "graph.json"])
def test_a_users_file_in_out_is_refused_by_name_and_kept(tmp_path, scan, name):
    out = tmp_path / "out"
    out.mkdir()
    (out / name).write_text("the user's")
    with pytest.raises(OutputFolderError, match=rf"out/{name}: --out .* holds files that no partscene run wrote"):
        _run(out, scan)
    assert (out / name).read_text() == "the user's"
    assert _leftovers(tmp_path) == []


def test_a_foreign_file_beside_an_earlier_run_is_refused_by_name(tmp_path, scan):
    out = _run(tmp_path / "out", scan)
    (out / "truth.urdf").write_text("the user's")
    with pytest.raises(OutputFolderError, match=r"out/truth.urdf: this file in --out .* was not written by the earlier"):
        _run(out, scan)
    assert (out / "truth.urdf").read_text() == "the user's"


def test_an_empty_folder_is_used(tmp_path, scan):
    (tmp_path / "out").mkdir()
    assert (_run(tmp_path / "out", scan) / "scene.urdf").is_file()


@pytest.mark.parametrize("where", ["inside", "cwd", "file"])
def test_unusable_out_folders_are_refused(tmp_path, scan, where, monkeypatch):
    if where == "inside":
        out = tmp_path
        match = r"scan.ply: this input \(scan\) lies inside --out"
    elif where == "cwd":
        (tmp_path / "sub").mkdir()
        monkeypatch.chdir(tmp_path / "sub")
        out = tmp_path
        match = "is the current folder, one above it or the home folder"
    else:
        out = tmp_path / "out"
        out.write_text("a file")
        match = "exists and is not a folder"
    with pytest.raises(OutputFolderError, match=match):
        _run(out, scan if where != "cwd" else tmp_path / "elsewhere.ply")


def test_a_failure_leaves_the_folder_as_it_was_but_withdraws_the_earlier_verdict(tmp_path, scan):
    out = _run(tmp_path / "out", scan, files=("certificate.json", "rollouts/a.npz"))
    with pytest.raises(RuntimeError, match="crash"):
        with output_folder(out, "recon build", inputs={"scan": scan}, settings={"seed": 0},
                           verdict="certificate.json") as staging:
            (staging / "certificate.json").write_text("half")
            raise RuntimeError("crash")
    assert not (out / "certificate.json").exists()       # no verdict that looks like this run's
    assert (out / "rollouts" / "a.npz").is_file()
    assert _leftovers(tmp_path) == []


def test_ctrl_c_leaves_no_partial_file(tmp_path, scan):
    with pytest.raises(KeyboardInterrupt):
        with output_folder(tmp_path / "out", "recon build", inputs={"scan": scan}, settings={}) as staging:
            (staging / "video.gif").write_bytes(b"GIF89a partial")
            raise KeyboardInterrupt
    assert not (tmp_path / "out").exists() and _leftovers(tmp_path) == []


def test_a_full_disk_is_a_named_error_and_leaves_nothing(tmp_path, scan):
    with pytest.raises(OutputFolderError, match=r"--out .*out: cannot write \(No space left on device\); nothing was"):
        with output_folder(tmp_path / "out", "recon build", inputs={"scan": scan}, settings={}) as staging:
            (staging / "scene.urdf").write_text("complete")
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    assert not (tmp_path / "out").exists() and _leftovers(tmp_path) == []
