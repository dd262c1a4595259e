"""The shared naming convention: truth and reconstruction name the same joint the same way."""

import pytest

from scenes.description import joint_name, link_name, object_name, parse_link_name


def test_names_follow_the_documented_pattern():
    assert object_name("cabinet", 3) == "cabinet3"
    assert link_name("cabinet", 3, "drawer", 12) == "cabinet3_drawer12"
    assert joint_name("cabinet", 3, "drawer", 12) == "cabinet3_drawer12_joint"


def test_unsafe_characters_are_removed():
    assert link_name("Kitchen Cabinet", 1, "door-left", 7) == "kitchencabinet1_doorleft7"


@pytest.mark.parametrize("category,oid,label,pid", [("cabinet", 3, "drawer", 12), ("bed", 0, "headboard", 101)])
def test_parse_inverts_link_name(category, oid, label, pid):
    assert parse_link_name(link_name(category, oid, label, pid)) == {
        "category": category, "object_id": oid, "label": label, "part_id": pid}


def test_parse_rejects_foreign_names():
    assert parse_link_name("panda_link7") is None
    assert parse_link_name("world") is None
