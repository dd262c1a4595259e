"""scenes.openings: the drawers and doors of a ground-truth scene, by their child part's label."""

from __future__ import annotations

from scenes.builtin import build_scene
from scenes.model import JointType
from scenes.openings import openings


def test_openings_are_the_prismatic_drawers_and_revolute_doors_of_the_kitchen():
    scene = build_scene("kitchen", 0)
    found = openings(scene)
    assert found and len({o.joint for o in found}) == len(found)
    for o in found:
        obj = next(ob for ob in scene.objects if ob.name == o.object)
        joint = next(j for j in obj.joints if obj.joint_name(j) == o.joint)
        assert (joint.type, obj.part(joint.child).label) == {"drawer": (JointType.PRISMATIC, "drawer"),
                                                              "door": (JointType.REVOLUTE, "door")}[o.kind]
        assert o.category == obj.category and o.task == f"open-{o.kind}:{o.joint}"
    every = sum(1 for ob in scene.objects for j in ob.joints
                if (j.type, ob.part(j.child).label) in ((JointType.PRISMATIC, "drawer"), (JointType.REVOLUTE, "door")))
    assert len(found) == every
    assert {o.kind for o in found} == {"drawer", "door"}
