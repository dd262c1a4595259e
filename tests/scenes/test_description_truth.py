"""scenes.description: the one truth.json reader/writer (format tag checked, atomic write, round trip)."""

from __future__ import annotations

import json

import pytest

from scenes.description import TRUTH_FORMAT, DescriptionError, read_truth_doc, write_truth_doc
from scenes.truth_json import read_truth_json, truth_dict_from_scene, write_truth_json


def test_truth_json_round_trip(tmp_path, kitchen):
    path = write_truth_json(kitchen, tmp_path / "truth.json")
    doc = read_truth_doc(path)
    assert doc["format"] == TRUTH_FORMAT and doc == json.loads(json.dumps(truth_dict_from_scene(kitchen)))
    assert read_truth_json(path).isclose(kitchen, atol=1e-12)
    again = write_truth_doc(doc, tmp_path / "again.json")
    assert again.read_text() == path.read_text()


def test_other_formats_and_broken_files_are_named(tmp_path):
    with pytest.raises(DescriptionError, match=r"x.json: format is 'other/2', expected 'partscene.truth/1'"):
        write_truth_doc({"format": "other/2"}, tmp_path / "x.json")
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(DescriptionError, match=r"bad.json: not valid JSON"):
        read_truth_doc(tmp_path / "bad.json")
    with pytest.raises(DescriptionError, match=r"gone.json: cannot read"):
        read_truth_doc(tmp_path / "gone.json")
