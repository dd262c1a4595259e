"""The report's pure parts: primitives read from URDF and truth.json agree, number formatting, the
key-frame camera avoids walls."""

from __future__ import annotations

import io
import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
from PIL import Image
import pytest

from simcheck.report import ArtifactError
from simcheck.report._html import format_number
from simcheck.report._key_frames import _segment_hits_box, camera_for
from simcheck.report._primitives import Solid, solids_from_truth, solids_from_urdf

TRUTH = Path(__file__).with_name("test_simcheck_report_data") / "truth"


def test_truth_urdf_and_truth_json_give_the_same_primitives():
    """Forward kinematics over the URDF's joint origins lands every shape where truth.json says it is."""
    from_json = solids_from_truth(json.loads((TRUTH / "truth.json").read_text()))
    from_urdf = [s for s in solids_from_urdf(TRUTH / "truth.urdf") if s.label]  # walls are not parts
    assert len(from_json) == len(from_urdf) > 50

    def key(s: Solid):
        return (s.link, s.kind, tuple(np.round(s.T_world_shape[:3, 3], 4)))

    a, b = sorted(from_json, key=key), sorted(from_urdf, key=key)
    for sa, sb in zip(a, b):
        assert sa.link == sb.link and sa.kind == sb.kind
        np.testing.assert_allclose(sa.size, sb.size, atol=1e-6)
        np.testing.assert_allclose(sa.T_world_shape, sb.T_world_shape, atol=1e-6)


def test_malformed_urdf_is_rejected_naming_file_and_link(tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="r"><link name="a"><visual><geometry><box size="0.1 -1 0.1"/></geometry>'
                   "</visual></link></robot>")
    with pytest.raises(ArtifactError, match=r"bad\.urdf: link 'a' visual #0 box has a non-positive size"):
        solids_from_urdf(bad)
    (tmp_path / "x.urdf").write_text("<robot><link")
    with pytest.raises(ArtifactError, match=r"x\.urdf: not valid XML"):
        solids_from_urdf(tmp_path / "x.urdf")
    loop = tmp_path / "loop.urdf"
    box = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    loop.write_text(f'<robot name="r"><link name="a">{box}</link><link name="b">{box}</link>'
                    '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
                    '<joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint></robot>')
    with pytest.raises(ArtifactError, match=r"loop\.urdf: expected one root link"):
        solids_from_urdf(loop)
    cycle = tmp_path / "cycle.urdf"   # a root, and two links hanging from each other
    cycle.write_text(f'<robot name="r"><link name="root"/><link name="a">{box}</link><link name="b">{box}</link>'
                     '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
                     '<joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint></robot>')
    with pytest.raises(ArtifactError, match=r"cycle\.urdf: links \['a', 'b'\] are not below the root link 'root'"):
        solids_from_urdf(cycle)


@pytest.mark.parametrize("value, shown", [(0.123456, "0.1235"), (12345.678, "12350"), (3.553e-15, "0"), (6.604e-05, "0.00006604"), (2.5e7, "2.5e+07"), (3, "3"), (True, "yes"),
                                          (None, "–"), (float("inf"), "inf"), (-0.5, "-0.5")])
def test_numbers_are_shown_with_four_significant_digits(value, shown):
    assert format_number(value) == shown


def _box(centre, size):
    T = np.eye(4)
    T[:3, 3] = centre
    return Solid("box", np.asarray(size, float), T, "wall", "")


def test_segment_box_test():
    box = _box([0, 0, 0], [1, 1, 1])
    assert _segment_hits_box(np.array([-2.0, 0, 0]), np.array([2.0, 0, 0]), box)
    assert not _segment_hits_box(np.array([-2.0, 2, 0]), np.array([2.0, 2, 0]), box)
    assert not _segment_hits_box(np.array([-2.0, 0, 0]), np.array([-1.0, 0, 0]), box)  # stops short


def test_key_frame_camera_turns_away_from_a_wall_that_blocks_the_preferred_view():
    # a handle at the origin pulled along +x; the preferred eye is +50 deg to the side (towards +y)
    handle = np.repeat(np.eye(4)[None], 2, axis=0)
    handle[1, 0, 3] = 0.3
    rollout = SimpleNamespace(T_world_handle=handle, tool_pos=np.array([[0.5, 0.0, 0.0]]))
    target, eye_free = camera_for(rollout)
    assert eye_free[1] > 0.7  # preferred side (a small part: looked at from 1 m)
    wall = _box([0.8, 0.6, 1.0], [4.0, 0.1, 3.0])  # a wall between the handle and that side
    target, eye = camera_for(rollout, [wall])
    assert not _segment_hits_box(eye, target + 0.3 * (eye - target) / np.linalg.norm(eye - target), wall)
    assert eye[1] < 0.6 and not np.allclose(eye, eye_free)


def test_views_cropped_alike_keep_their_framing():
    from simcheck.report._figure import crop_alike, png_bytes

    a, b = np.full((100, 200, 3), 255, np.uint8), np.full((100, 200, 3), 255, np.uint8)
    a[40:50, 20:30] = 0                      # something left in one view, right in the other
    b[60:70, 150:160] = 0
    out = [np.asarray(Image.open(io.BytesIO(p)).convert("RGB")) for p in crop_alike([png_bytes(Image.fromarray(a), 12.0),
                                                                                     png_bytes(Image.fromarray(b), None)])]
    assert out[0].shape == out[1].shape
    ya, xa = np.argwhere(out[0][:, :, 0] == 0).min(axis=0)
    yb, xb = np.argwhere(out[1][:, :, 0] == 0).min(axis=0)
    assert (yb - ya, xb - xa) == (20, 130)   # the same offsets as in the full views


def test_a_smaller_part_is_looked_at_from_closer():
    from simcheck.key_frame_view import CAMERA_DISTANCE, MIN_CAMERA_DISTANCE, camera_distance

    assert MIN_CAMERA_DISTANCE <= camera_distance(0.5) < camera_distance(1.2) <= CAMERA_DISTANCE
    assert camera_distance(0.01) == MIN_CAMERA_DISTANCE and camera_distance(10.0) == CAMERA_DISTANCE


def test_every_criteria_threshold_has_a_unit():
    import dataclasses

    from simcheck.config import CRITERIA_UNITS, CriteriaConfig

    numeric = {f.name for f in dataclasses.fields(CriteriaConfig) if f.type in ("float", float)}
    assert numeric == set(CRITERIA_UNITS)
