"""Scan reading and validation: formats agree, bad input is refused with a message that names it."""

import json

import numpy as np
import pytest

from recon import ReconError, ScanError
from recon.scan import read_scan, scan_from_arrays


@pytest.fixture(scope="module")
def cab(synth):
    return synth.scan_arrays([synth.cabinet()], points_per_m2=2000)


def _write(synth, tmp_path, props, labels, name="scan.ply", binary=True):
    synth.write_ply(tmp_path / name, props, binary=binary)
    (tmp_path / "labels.json").write_text(json.dumps({"objects": labels}))
    return tmp_path / name, tmp_path / "labels.json"


def test_binary_ascii_and_npz_give_the_same_scan(tmp_path, cab, synth):
    props, labels = cab
    b = read_scan(*_write(synth, tmp_path, props, labels, "b.ply", True))
    a = read_scan(*_write(synth, tmp_path, props, labels, "a.ply", False))
    pts = np.c_[props["x"], props["y"], props["z"]]
    np.savez(tmp_path / "s.npz", points=pts, object_id=props["object_id"], part_id=props["part_id"])
    n = read_scan(tmp_path / "s.npz", tmp_path / "labels.json")
    assert len(b.points) == len(a.points) == len(n.points) == len(pts)
    np.testing.assert_allclose(a.points, b.points, atol=1e-5)   # ascii keeps 6 decimals
    np.testing.assert_allclose(n.points, pts)
    assert [p.part_id for p in b.objects[0].parts] == [101, 102, 103, 104, 105]
    assert b.warnings == ()


def test_nan_points_are_refused_naming_the_point_and_part(cab):
    props, labels = cab
    props = dict(props, x=props["x"].copy())
    i = int(np.flatnonzero(props["part_id"] == 103)[0])
    props["x"][i] = np.nan
    with pytest.raises(ScanError, match=rf"NaN.*point {i}, object 1, part 103"):
        scan_from_arrays(props, labels, source="scan.ply")


def test_millimetre_scan_is_refused_with_a_hint(cab):
    props, labels = cab
    props = dict(props, x=props["x"] * 1000, y=props["y"] * 1000, z=props["z"] * 1000)
    with pytest.raises(ScanError, match="millimetres: divide the coordinates by 1000"):
        scan_from_arrays(props, labels)


def test_empty_scan_and_missing_files(tmp_path, cab):
    props, labels = cab
    empty = {k: v[:0] for k, v in props.items()}
    with pytest.raises(ScanError, match="no points"):
        scan_from_arrays(empty, labels)
    with pytest.raises(ScanError, match="nope.ply: scan file not found"):
        read_scan(tmp_path / "nope.ply", tmp_path / "labels.json")
    (tmp_path / "x.xyz").write_text("1 2 3\n")
    with pytest.raises(ScanError, match="unknown scan format '.xyz'"):
        read_scan(tmp_path / "x.xyz", tmp_path / "labels.json")
    (tmp_path / "junk.ply").write_bytes(b"not a ply at all")
    (tmp_path / "labels.json").write_text(json.dumps({"objects": labels}))
    with pytest.raises(ScanError, match="junk.ply: not a readable PLY"):
        read_scan(tmp_path / "junk.ply", tmp_path / "labels.json")


@pytest.mark.parametrize("doc, message", [
    ("{not json", "not valid JSON"),
    ('{"things": []}', "'objects' list"),
    ('{"objects": [{"id": 1, "parts": []}]}', r"objects\[0\] needs 'id', 'category'"),
    ('{"objects": [{"id": 1, "category": "cabinet", "parts": [{"id": 5}]}]}', r"object 1 parts\[0\] needs 'id' and 'label'"),
    ('{"objects": [{"id": 1, "category": "cabinet", "parts": [{"id": 5, "label": "body"}]},'
     ' {"id": 2, "category": "table", "parts": [{"id": 5, "label": "top"}]}]}', "part id 5 is listed under object 1 and object 2"),
    ('{"objects": [{"id": 1, "category": "a", "parts": []}, {"id": 1, "category": "b", "parts": []}]}', "object id 1 appears twice"),
])
def test_malformed_labels_are_refused(tmp_path, cab, synth, doc, message):
    props, _ = cab
    synth.write_ply(tmp_path / "scan.ply", props)
    (tmp_path / "labels.json").write_text(doc)
    with pytest.raises(ScanError, match=message):
        read_scan(tmp_path / "scan.ply", tmp_path / "labels.json")


def test_part_problems_are_warnings_that_name_object_and_part(cab):
    props, labels = cab
    labels = json.loads(json.dumps(labels))
    labels[0]["parts"].append({"id": 199, "label": "drawer"})          # no points at all
    labels[0]["parts"][2]["label"] = "gizmo"                          # unknown label
    props = dict(props, object_id=props["object_id"].copy(), part_id=props["part_id"].copy())
    props["object_id"][:5] = 42                                        # an object labels.json lacks
    props["part_id"][:5] = 4242
    scan = scan_from_arrays(props, labels, source="s.ply")
    text = "\n".join(scan.warnings)
    assert "object 1 (cabinet) part 199 (drawer): 0 points" in text and "skipped" in text
    assert "object 1 (cabinet) part 103: unknown label 'gizmo'" in text
    assert "object id 42 (5 points) is not in labels.json" in text
    assert [p.part_id for p in scan.objects[0].parts] == [101, 102, 103, 104, 105]


def test_no_usable_object_is_an_error(cab):
    props, labels = cab
    keep = props["part_id"] == 103
    few = {k: v[keep][:5] for k, v in props.items()}
    with pytest.raises(ScanError, match="no labelled object has a part with at least 20 points"):
        scan_from_arrays(few, labels)
    assert issubclass(ScanError, ReconError)
