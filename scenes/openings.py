"""The drawers and doors of a ground-truth scene: the joints an opening task can name.

A drawer is a prismatic joint whose child part is labelled ``drawer``; a door a revolute joint whose
child is a ``door`` (a prismatic shelf or a revolute lid are not). Pure: reads the :class:`Scene` only.
"""

from __future__ import annotations

from dataclasses import dataclass

from .model import JointType, Scene

__all__ = ["Opening", "openings"]


@dataclass(frozen=True)
class Opening:
    """One drawer or door of a scene: ``kind`` ("drawer" / "door"), its URDF ``joint`` name, and the
    ``object`` (name) and ``category`` it belongs to."""

    kind: str
    joint: str
    object: str
    category: str

    @property
    def task(self) -> str:
        """The opening task's text, ``open-drawer:<joint>`` or ``open-door:<joint>``."""
        return f"open-{self.kind}:{self.joint}"


_KINDS = {(JointType.PRISMATIC, "drawer"): "drawer", (JointType.REVOLUTE, "door"): "door"}


def openings(scene: Scene) -> tuple[Opening, ...]:
    """Every drawer and door of ``scene``, in object order then joint order."""
    out = []
    for obj in scene.objects:
        for j in obj.joints:
            kind = _KINDS.get((j.type, obj.part(j.child).label))
            if kind is not None:
                out.append(Opening(kind, obj.joint_name(j), obj.name, obj.category))
    return tuple(out)
