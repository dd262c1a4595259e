"""The hostile-input corpus: each kind of bad input gets a clean, named input error, never a crash, a hang
or exit 0 on garbage. One parametrised case per kind; everything runs in-process and stops before any
reconstruction or planning work, so the module takes a few seconds."""

import json
from pathlib import Path

import numpy as np
import pytest

from scenes.description import InputError


# --- a small labelled scan: a cabinet body (box surface) and a drawer front ---------------------------

def _box_surface(lo, hi, n, rng):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    pts = rng.uniform(lo, hi, size=(n, 3))
    axis = rng.integers(0, 3, n)
    side = rng.integers(0, 2, n)
    pts[np.arange(n), axis] = np.where(side == 1, hi[axis], lo[axis])
    return pts


def _scan_props():
    rng = np.random.default_rng(0)
    body = _box_surface((0, 0, 0), (0.5, 0.6, 0.8), 3000, rng)
    drawer = _box_surface((-0.02, 0.05, 0.5), (0.0, 0.55, 0.75), 800, rng)
    pts = np.r_[body, drawer]
    return {"x": pts[:, 0], "y": pts[:, 1], "z": pts[:, 2],
            "object_id": np.ones(len(pts), np.int64),
            "part_id": np.r_[np.full(len(body), 101), np.full(len(drawer), 102)]}


LABELS = [{"id": 1, "category": "cabinet", "parts": [{"id": 101, "label": "body"}, {"id": 102, "label": "drawer"}]}]


def _write_ply(path: Path, props, binary=False, declared=None):
    n = len(props["x"])
    header = (f"ply\nformat {'binary_little_endian' if binary else 'ascii'} 1.0\nelement vertex {declared or n}\n"
              "property float x\nproperty float y\nproperty float z\nproperty int object_id\nproperty int part_id\n"
              "end_header\n")
    rows = "\n".join(f"{x:.6f} {y:.6f} {z:.6f} {o} {p}" for x, y, z, o, p in
                     zip(props["x"], props["y"], props["z"], props["object_id"], props["part_id"]))
    path.write_text(header + rows + "\n")
    return path


def _write_labels(path: Path, objects):
    path.write_text(json.dumps({"objects": objects}))
    return path


# --- recon build cases: (files written into tmp) -> CLI exit 2 with a message ------------------------

def _identical_points(tmp):
    props = _scan_props()
    props = dict(props, x=np.full_like(props["x"], 0.3), y=np.full_like(props["y"], 0.3),
                 z=np.full_like(props["z"], 0.3))
    return _write_ply(tmp / "scan.ply", props), _write_labels(tmp / "labels.json", LABELS)


def _two_bodies(tmp):
    labels = [{"id": 1, "category": "cabinet", "parts": [{"id": 101, "label": "body"}, {"id": 102, "label": "body"}]}]
    return _write_ply(tmp / "scan.ply", _scan_props()), _write_labels(tmp / "labels.json", labels)


def _ply_cut_short(tmp):
    props = _scan_props()
    n = len(props["x"])
    short = {k: v[: int(0.6 * n)] for k, v in props.items()}
    return _write_ply(tmp / "scan.ply", short, declared=n), _write_labels(tmp / "labels.json", LABELS)


def _labels_ids(bad_id, where):
    def case(tmp):
        labels = json.loads(json.dumps(LABELS))
        if where == "object":
            labels[0]["id"] = bad_id
        else:
            labels[0]["parts"][1]["id"] = bad_id
        return _write_ply(tmp / "scan.ply", _scan_props()), _write_labels(tmp / "labels.json", labels)
    return case


def _npz(**bad):
    def case(tmp):
        props = _scan_props()
        pts = np.c_[props["x"], props["y"], props["z"]]
        arrays = dict(points=pts, object_id=props["object_id"], part_id=props["part_id"])
        arrays.update({k: v(len(pts)) for k, v in bad.items()})
        np.savez(tmp / "scan.npz", **arrays)
        return tmp / "scan.npz", _write_labels(tmp / "labels.json", LABELS)
    return case


def _long_label(tmp):
    labels = json.loads(json.dumps(LABELS))
    labels[0]["parts"][1]["label"] = "\u00e9tag\u00e8re" * 500
    return _write_ply(tmp / "scan.ply", _scan_props()), _write_labels(tmp / "labels.json", labels)


def _labels_in_out(tmp):
    (tmp / "out").mkdir()
    return _write_ply(tmp / "scan.ply", _scan_props()), _write_labels(tmp / "out" / "graph.json", LABELS)


def _empty_ply(tmp):
    return (_write_ply(tmp / "scan.ply", {k: v[:0] for k, v in _scan_props().items()}),
            _write_labels(tmp / "labels.json", LABELS))


def _labels_folder(tmp):
    (tmp / "labels.json").mkdir()
    return _write_ply(tmp / "scan.ply", _scan_props()), tmp / "labels.json"


RECON_CASES = {
    "ply-without-points": (_empty_ply, r"scan.ply: the scan has no points \(the PLY header declares 0 vertices\)"),
    "labels-path-is-a-folder": (_labels_folder, r"labels.json: is a folder; give the labels.json file inside it"),
    "labels-file-is-out-graph-json": (_labels_in_out, r"out/graph.json: this input \(labels\) lies inside --out"),
    "all-points-identical": (_identical_points, r"scan.ply: all \d+ points lie within"),
    "two-body-parts": (_two_bodies, r"labels.json: object 1 has 2 'body' parts \(101, 102\)"),
    "ascii-ply-cut-short": (_ply_cut_short, r"scan.ply: the PLY header declares 3800 vertices but the file holds 2280"),
    "labels-object-id-list": (_labels_ids([1], "object"), r"objects\[0\] id \[1\] must be an integer"),
    "labels-part-id-string": (_labels_ids("102", "part"), r"object 1 parts\[1\] id '102' must be an integer"),
    "npz-normals-wrong-length": (_npz(normals=lambda n: np.zeros((n - 5, 3))), r"scan.npz: 'normals' must be \(3800, 3\)"),
    "npz-colors-wrong-length": (_npz(colors=lambda n: np.zeros((n + 1, 3), np.uint8)), r"scan.npz: 'colors' must be \(3800"),
    "label-thousands-of-characters": (_long_label, r"object 1 part 102 label is 3500 characters long"),
}


@pytest.mark.parametrize("case", sorted(RECON_CASES))
def test_recon_build_refuses_with_exit_2(case, tmp_path, capsys):
    from recon.cli import main

    make, message = RECON_CASES[case]
    scan, labels = make(tmp_path)
    code = main(["build", str(scan), "--labels", str(labels), "--out", str(tmp_path / "out"), "--no-preview", "-q"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "Traceback" not in err
    assert __import__("re").search(message, err), err
    assert not (tmp_path / "out" / "scene.urdf").exists()
    if case == "labels-file-is-out-graph-json":
        assert json.loads((tmp_path / "out" / "graph.json").read_text()) == {"objects": LABELS}


def test_a_part_collapsed_to_a_point_is_a_warning_and_a_skipped_part():
    from recon.scan import scan_from_arrays

    props = _scan_props()
    props = {k: v.copy() for k, v in props.items()}
    drawer = props["part_id"] == 102
    for k in ("x", "y", "z"):
        props[k][drawer] = props[k][drawer][0]
    scan = scan_from_arrays(props, LABELS, source="scan.ply")
    assert [p.part_id for p in scan.objects[0].parts] == [101]
    assert [p.part_id for p in scan.objects[0].skipped] == [102]
    assert any("part 102 (drawer)" in w and "skipped" in w for w in scan.warnings)


# --- scene URDF cases: read_urdf / the planner raise an InputError naming the link or joint ------------

def _urdf(tmp: Path, link="drawer", joint="drawer_joint", upper=0.4, mass="1", ixx="0.1", velocity="1") -> Path:
    box = '<collision><geometry><box size="0.4 0.5 0.2"/></geometry></collision>'
    inertial = '<inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
    moving = (f'<inertial><mass value="{mass}"/><inertia ixx="{ixx}" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>'
              '</inertial>')
    text = f"""<robot name="s">
  <link name="world"/>
  <link name="body">{inertial}{box}</link>
  <link name="{link}">{moving}{box}</link>
  <joint name="body_joint" type="fixed"><parent link="world"/><child link="body"/></joint>
  <joint name="{joint}" type="prismatic"><parent link="body"/><child link="{link}"/>
    <origin xyz="-0.3 0 0.5"/><axis xyz="-1 0 0"/><limit lower="0" upper="{upper}" effort="10" velocity="{velocity}"/></joint>
</robot>"""
    (tmp / "scene.urdf").write_text(text)
    return tmp / "scene.urdf"


def _long_link(tmp):
    from scenes.description import read_urdf
    read_urdf(_urdf(tmp, link="d" * 3000))


def _long_joint(tmp):
    from scenes.description import read_urdf
    read_urdf(_urdf(tmp, joint="j" * 2100))


def _huge_drawer(tmp):
    from planners.plan import plan_open_task
    from planners.task import parse_task
    plan_open_task(None, _urdf(tmp, upper=1e6), parse_task("open-drawer:drawer_joint"))


def _huge_amount(tmp):
    from planners.plan import plan_open_task
    from planners.task import parse_task
    plan_open_task(None, _urdf(tmp, upper=1e6), parse_task("open-drawer:drawer_joint", amount=5e5))


def _huge_negative_drawer(tmp):
    from planners.plan import plan_open_task
    from planners.task import parse_task
    (tmp / "scene.urdf").write_text(_urdf(tmp).read_text().replace('lower="0" upper="0.4"', 'lower="-1e6" upper="0"'))
    plan_open_task(None, tmp / "scene.urdf", parse_task("open-drawer:drawer_joint"))


def _read_drawer(**kw):
    def case(tmp):
        from scenes.description import read_urdf
        read_urdf(_urdf(tmp, **kw))
    return case


SCENE_CASES = {
    "drawer-mass-0": (_read_drawer(mass="0"), r"link 'drawer' \(child of prismatic joint 'drawer_joint'\) has mass 0"),
    "drawer-inertia-nan": (_read_drawer(ixx="nan"), r"link 'drawer' inertia: expected finite numbers"),
    "drawer-inertia-negative": (_read_drawer(ixx="-1"), r"link 'drawer' \(child of prismatic joint 'drawer_joint'\) "
                                r"has an inertia that has principal moment -1 kg m\^2"),
    "drawer-velocity-negative": (_read_drawer(velocity="-1"), r"joint 'drawer_joint' has limit effort 10 and velocity -1"),
    "drawer-lower-minus-1e6-m": (_huge_negative_drawer, r"joint 'drawer_joint': opening by -.* m is beyond"),
    "link-name-3000-chars": (_long_link, r"scene.urdf: link 'ddd.*has a name of 3000 characters \(at most 255\)"),
    "joint-name-2100-chars": (_long_joint, r"scene.urdf: joint 'jjj.*has a name of 2100 characters"),
    "drawer-upper-1e6-m": (_huge_drawer, r"scene.urdf: joint 'drawer_joint': opening by .* m is beyond the physical bound"),
    "drawer-amount-5e5-m": (_huge_amount, r"joint 'drawer_joint': opening by 5e\+05 m is beyond"),
}


@pytest.mark.parametrize("case", sorted(SCENE_CASES))
def test_scene_inputs_raise_a_named_input_error(case, tmp_path):
    run, message = SCENE_CASES[case]
    with pytest.raises(InputError, match=message):
        run(tmp_path)


SIMCHECK_CASES = {
    "link-name-3000-chars": (dict(link="d" * 3000), r"link 'ddd.*has a name of 3000 characters"),
    "drawer-upper-1e6-m": (dict(upper=1e6), r"joint 'drawer_joint': opening by .* m is beyond the physical bound"),
    "drawer-mass-0": (dict(mass="0"), r"link 'drawer' \(child of prismatic joint 'drawer_joint'\) has mass 0"),
    "drawer-inertia-nan": (dict(ixx="nan"), r"link 'drawer' inertia: expected finite numbers"),
}


@pytest.mark.parametrize("case", sorted(SIMCHECK_CASES))
def test_simcheck_certify_refuses_with_exit_2(case, tmp_path, capsys):
    from simcheck.cli import main

    urdf_args, message = SIMCHECK_CASES[case]
    code = main(["certify", str(_urdf(tmp_path, **urdf_args)), "--task", "open-drawer:drawer_joint",
                 "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "Traceback" not in err
    assert __import__("re").search(message, err), err


@pytest.mark.parametrize("a, b", [("door:1", "door_1"), ("door:1", "door/1"), ("d" * 300, "d" * 301), ("..", "__")])
def test_joints_whose_names_sanitise_alike_get_different_rollout_files(a, b):
    from scenes.description import file_stem

    assert file_stem(a) != file_stem(b)
    assert all(len(file_stem(n)) <= 109 and "/" not in file_stem(n) and ":" not in file_stem(n) for n in (a, b))
    assert file_stem("cabinet1_drawer2_joint") == "cabinet1_drawer2_joint"


def test_a_crashed_certify_leaves_no_previous_verdict(tmp_path):
    import importlib.util

    from simcheck.certification import certify

    spec = importlib.util.spec_from_file_location(
        "simcheck_fixture_plans", Path(__file__).parent / "simcheck" / "simcheck_fixture_plans.py")
    fixture = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fixture)
    (tmp_path / "certificate.json").write_text('{"ok": true}')

    def crashing_planner(*args, **kwargs):
        raise RuntimeError("planner crashed")

    with pytest.raises(RuntimeError, match="planner crashed"):
        certify(fixture.CABINET, [f"open-drawer:{fixture.DRAWER}"], robot=fixture.ROBOT, out=tmp_path,
                planner=crashing_planner, images=False)
    assert not (tmp_path / "certificate.json").exists()


# --- the output folder: written as a whole, never over a user's files, nothing partial -----------------

def _recon(tmp, *extra):
    from recon.cli import main

    scan = _write_ply(tmp / "scan.ply", _scan_props())
    labels = _write_labels(tmp / "labels.json", LABELS)
    return main(["build", str(scan), "--labels", str(labels), "--out", str(tmp / "out"), "--no-preview", "-q", *extra])


@pytest.mark.parametrize("name", ["scene.urdf", "truth.urdf", "graph.json"])
def test_recon_build_refuses_an_out_holding_a_users_file(name, tmp_path, capsys):
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / name).write_text("the user's")
    assert _recon(tmp_path) == 2
    err = capsys.readouterr().err
    assert f"out/{name}: --out" in err and "--overwrite" in err and "Traceback" not in err
    assert (tmp_path / "out" / name).read_text() == "the user's"


def test_recon_build_rerun_replaces_a_different_run_is_refused_unless_overwrite(tmp_path, capsys):
    assert _recon(tmp_path) == 0
    assert _recon(tmp_path) == 0                       # the same inputs: replaced
    assert _recon(tmp_path, "--seed", "1") == 2        # another run: refused
    assert "it holds a run with seed = 0 (this run: 1)" in capsys.readouterr().err
    assert _recon(tmp_path, "--seed", "1", "--overwrite") == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["labels.json", "out", "scan.ply"]   # no temporary folder


def test_recon_build_on_a_full_disk_exits_2_and_writes_nothing(tmp_path, capsys, monkeypatch):
    import errno
    import os

    import recon.output

    def full_disk(path, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    monkeypatch.setattr(recon.output, "write_bytes_atomic", full_disk)
    assert _recon(tmp_path) == 2
    assert "cannot write (No space left on device); nothing was written" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["labels.json", "scan.ply"]


@pytest.mark.parametrize("name", ["truth.urdf", "labels.json"])
def test_scenes_make_refuses_an_out_holding_a_users_file(name, tmp_path, capsys):
    from scenes.cli import main

    (tmp_path / "out").mkdir()
    (tmp_path / "out" / name).write_text("the user's")
    assert main(["make", "kitchen", "--no-scan", "--no-previews", "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert f"out/{name}: --out" in err and "Traceback" not in err, err
    assert (tmp_path / "out" / name).read_text() == "the user's"


@pytest.mark.parametrize("name", ["scene.urdf", "truth.urdf"])
def test_simcheck_certify_refuses_an_out_holding_a_users_file(name, tmp_path, capsys):
    from simcheck.cli import main

    scene = _urdf(tmp_path)
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / name).write_text("the user's")
    code = main(["certify", str(scene), "--task", "open-drawer:drawer_joint", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and f"out/{name}: --out" in err and "Traceback" not in err, err
    assert (tmp_path / "out" / name).read_text() == "the user's"


def test_recon_build_interrupted_by_ctrl_c_leaves_nothing(tmp_path):
    """SIGINT in the middle of a real `recon build` (its reconstruction made to wait so the signal lands
    mid-run): exit 130, no --out, no temporary folder."""
    import signal
    import subprocess
    import sys
    import time

    scan = _write_ply(tmp_path / "scan.ply", _scan_props())
    labels = _write_labels(tmp_path / "labels.json", LABELS)
    # a shell starts background jobs with SIGINT ignored, and children inherit that: give the child the
    # handler an interactive user's Ctrl-C meets
    code = ("import signal, sys, time, recon.pipeline as p\n"
            "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
            "p.reconstruct_scan = lambda *a, **k: time.sleep(60)\n"
            "from recon.cli import main\nsys.exit(main(sys.argv[1:]))\n")
    proc = subprocess.Popen([sys.executable, "-c", code, "build", str(scan), "--labels", str(labels),
                             "--out", str(tmp_path / "out")], stderr=subprocess.PIPE, text=True,
                            env={**__import__("os").environ, "PYTHONPATH": str(Path(__file__).parents[1])})
    t0 = time.monotonic()
    while not any(".partial-" in p.name for p in tmp_path.iterdir()):
        assert proc.poll() is None and time.monotonic() - t0 < 120, proc.stderr.read() if proc.poll() else "slow"
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    err = proc.communicate(timeout=60)[1]
    assert proc.returncode == 130, err
    assert "interrupted; nothing was written" in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["labels.json", "scan.ply"]
