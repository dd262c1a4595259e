"""The corpus: 26 articulated objects in other people's conventions (:mod:`thirdparty.build`).

Kinds covered: base and wall cabinets, kitchen units, drawer stacks, a dresser, a file cabinet,
microwaves, refrigerators (stacked and side-by-side double doors), a dishwasher and an oven (bottom-hinged
doors), a top-hinged wall flap, a wardrobe, a safe; double doors and stacked fronts that touch at rest
(gap 0) or overlap by 1 mm; joints that open toward negative values; continuous hinges; rotated joint frames and frames at
the far end of the hinge; handles as links, unnamed mesh geometry, one mesh with their panel, knobs, an edge-pull profile, or
none (a handleless wall-cabinet door overhanging the carcass's bottom, to be pulled from below).

``FIXTURES`` names the few objects the test suite builds (a spread of those kinds); the benchmark builds
all of them.
"""

from __future__ import annotations

from thirdparty.build import FrontSpec as F
from thirdparty.build import ObjectSpec as O

__all__ = ["CATALOGUE", "FIXTURES", "spec_named"]


def _stack(x0, x1, zs, **kw):
    """Drawers stacked in column [x0, x1] with boundaries ``zs`` (bottom to top)."""
    return tuple(F("drawer", (x0, x1, a, b), **kw) for a, b in zip(zs[:-1], zs[1:]))


CATALOGUE: tuple = (
    O("base_cabinet_door_drawer", "cabinet", 0.6, 0.55, 0.85, elevation=0.1, names="words",
      fronts=(F("drawer", (0, 0.6, 0.75, 0.95)), F("door_left", (0, 0.6, 0.1, 0.75)))),
    O("kitchen_unit_double_door", "cabinet", 0.8, 0.56, 0.78, elevation=0.1, names="indexed", place=(1.3, -0.4, 20),
      fronts=(F("door_left", (0, 0.4, 0.1, 0.88), handle="mesh"),
              F("door_right", (0.4, 0.8, 0.1, 0.88), handle="mesh", sign=-1))),
    O("sink_base_no_handles", "cabinet", 0.9, 0.58, 0.78, elevation=0.12, gap=0.003, names="camel",
      fronts=(F("door_left", (0, 0.45, 0.12, 0.9), handle="none"),
              F("door_right", (0.45, 0.9, 0.12, 0.9), handle="none"))),
    O("drawer_stack_knobs", "cabinet", 0.5, 0.5, 0.8, elevation=0.05, names="words", place=(1.2, 0.6, -30),
      fronts=_stack(0, 0.5, (0.05, 0.3, 0.55, 0.85), handle="knob")),
    O("dresser_six", "cabinet", 1.1, 0.5, 0.9, elevation=0.08, names="indexed", inertials=False,
      fronts=_stack(0, 0.55, (0.08, 0.38, 0.68, 0.98), handle="mesh")
      + _stack(0.55, 1.1, (0.08, 0.38, 0.68, 0.98), handle="mesh", sign=-1)),
    O("file_cabinet", "cabinet", 0.45, 0.62, 1.3, names="camel", place=(1.3, 0.0, 90),
      fronts=_stack(0, 0.45, (0.0, 0.32, 0.64, 0.96, 1.3), frame="centre")),
    O("nightstand", "cabinet", 0.45, 0.4, 0.55, elevation=0.1, names="words", gap=0.004,
      fronts=(F("drawer", (0, 0.45, 0.5, 0.65), handle="knob_link"),
              F("door_right", (0, 0.45, 0.1, 0.5), handle="knob_link", sign=-1))),
    O("wall_cabinet_double", "wall_cabinet", 0.8, 0.35, 0.7, elevation=1.35, names="indexed",
      fronts=(F("door_left", (0, 0.4, 1.35, 2.05), frame="rotated"),
              F("door_right", (0.4, 0.8, 1.35, 2.05), frame="rotated"))),
    O("wall_cabinet_finger_pull", "wall_cabinet", 0.6, 0.35, 0.7, elevation=1.4, names="camel",
      notes="handleless: the door overhangs the carcass's bottom by 3 cm, to be pulled from below (nothing a "
            "scan shows tells its hinge side)",
      fronts=(F("door_right", (0, 0.6, 1.37, 2.1), handle="none"),)),
    O("wall_cabinet_edge_pull", "wall_cabinet", 0.5, 0.33, 0.72, elevation=1.42, names="words",
      notes="handleless door whose finger pull is an aluminium edge profile along its free edge",
      fronts=(F("door_left", (0, 0.5, 1.42, 2.14), handle="profile"),)),
    O("wall_flap", "wall_cabinet", 0.8, 0.35, 0.4, elevation=1.45, names="words",
      fronts=(F("door_top", (0, 0.8, 1.45, 1.85), limit=1.4),)),
    O("microwave_left_hinge", "microwave", 0.5, 0.4, 0.3, elevation=0.9, names="words", place=(1.2, 0.2, 10),
      fronts=(F("door_left", (0, 0.38, 0.9, 1.2), handle="mesh", sign=-1, limit=1.75),)),
    O("microwave_knob", "microwave", 0.55, 0.42, 0.32, elevation=1.0, names="camel",
      fronts=(F("door_left", (0, 0.4, 1.0, 1.32), handle="knob", limit=1.57),)),
    O("microwave_continuous", "microwave", 0.5, 0.4, 0.3, elevation=0.95, names="indexed",
      fronts=(F("door_left", (0, 0.38, 0.95, 1.25), continuous=True),)),
    O("refrigerator_stacked", "refrigerator", 0.7, 0.65, 1.8, names="words", place=(1.5, 0.2, 0),
      fronts=(F("door_right", (0, 0.7, 1.25, 1.8), frame="rotated"),
              F("door_right", (0, 0.7, 0.0, 1.25), sign=-1))),
    O("refrigerator_side_by_side", "refrigerator", 0.9, 0.7, 1.78, names="camel", place=(1.5, 0.0, -15),
      fronts=(F("door_left", (0, 0.45, 0.0, 1.78), handle="mesh"),
              F("door_right", (0.45, 0.9, 0.0, 1.78), handle="mesh", sign=-1))),
    O("dishwasher", "dishwasher", 0.6, 0.58, 0.82, elevation=0.05, names="words",
      fronts=(F("door_bottom", (0, 0.6, 0.05, 0.87), limit=1.45),)),
    # the oven door pivots on its outer face (hinge="front"), as real oven doors clear the drawer they touch:
    # hinged on its back face its lower front edge would sweep 2 cm down into the drawer front (blocked past
    # ~9 deg; docs/decisions.md, "Third-party corpus: stays")
    O("oven", "oven", 0.6, 0.58, 0.86, elevation=0.05, names="indexed", place=(1.3, 0.5, 0),
      fronts=(F("door_bottom", (0, 0.6, 0.25, 0.91), sign=-1, hinge="front"),
              F("drawer", (0, 0.6, 0.05, 0.25)))),
    O("tall_pantry", "cabinet", 0.6, 0.6, 2.0, names="words", place=(1.4, -0.2, 0),
      fronts=(F("door_left", (0, 0.6, 0.9, 2.0), frame="rotated"),
              F("door_left", (0, 0.6, 0.0, 0.9)))),
    O("tv_stand", "cabinet", 1.2, 0.45, 0.45, elevation=0.08, names="camel", gap=0.002,
      fronts=(F("drawer", (0, 0.6, 0.08, 0.53), handle="mesh"), F("drawer", (0.6, 1.2, 0.08, 0.53), sign=-1))),
    O("vanity", "cabinet", 0.6, 0.48, 0.8, elevation=0.1, names="indexed", place=(1.3, 0.4, -45),
      fronts=(F("drawer", (0, 0.6, 0.7, 0.9), frame="centre"),
              F("door_right", (0, 0.6, 0.1, 0.7), limit=1.57))),
    O("safe_box", "cabinet", 0.5, 0.5, 0.6, elevation=0.3, front_t=0.05, names="words",
      fronts=(F("door_right", (0, 0.5, 0.3, 0.9), handle="knob", limit=1.57),)),
    O("wardrobe", "cabinet", 1.0, 0.6, 1.9, names="words", place=(1.6, 0.1, 0),
      fronts=(F("door_left", (0, 0.5, 0.5, 1.9), handle="mesh"), F("door_right", (0.5, 1.0, 0.5, 1.9)),
              F("drawer", (0, 0.5, 0.0, 0.5)), F("drawer", (0.5, 1.0, 0.0, 0.5), handle="knob"))),
    O("double_door_overlapping", "cabinet", 0.9, 0.55, 0.8, elevation=0.1, gap=-0.001, names="camel",
      notes="exported with its doors overlapping 1 mm at rest", place=(1.3, 0.2, -10),
      fronts=(F("door_left", (0, 0.45, 0.1, 0.9), handle="mesh"), F("door_right", (0.45, 0.9, 0.1, 0.9)))),
    O("one_mesh_fronts", "cabinet", 0.6, 0.5, 0.8, elevation=0.1, names="indexed", place=(1.3, -0.3, 15),
      notes="each front's panel and handle exported as one mesh", gap=0.002,
      fronts=(F("drawer", (0, 0.6, 0.7, 0.9), handle="merged"),
              F("door_left", (0, 0.6, 0.1, 0.7), handle="merged", sign=-1))),
    O("corner_unit_rotated", "cabinet", 0.7, 0.55, 0.85, elevation=0.1, names="indexed", place=(1.2, 0.8, 60),
      fronts=(F("drawer", (0, 0.7, 0.75, 0.95), frame="centre", sign=-1),
              F("door_right", (0, 0.7, 0.1, 0.75), frame="rotated", handle="mesh", sign=-1))),
)

FIXTURES: tuple = ("kitchen_unit_double_door", "dresser_six", "microwave_left_hinge", "nightstand",
                   "microwave_continuous", "wall_cabinet_finger_pull")


def spec_named(name: str):
    """The catalogue entry called ``name`` (KeyError naming the known ones otherwise)."""
    for s in CATALOGUE:
        if s.name == name:
            return s
    raise KeyError(f"no corpus object {name!r}; known: {', '.join(s.name for s in CATALOGUE)}")
