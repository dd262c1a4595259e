"""Every threshold and physical constant of the generators and composer, named once.

Units: metres, radians, kilograms, seconds. Densities are kg/m^3 of the solid primitives (thin panels
are solid boxes, so a cabinet body's mass is panel volume x density).
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Densities", "JointDynamics", "GeneratorConfig", "ComposerConfig", "DEFAULT_GENERATOR",
           "DEFAULT_COMPOSER"]


@dataclass(frozen=True)
class Densities:
    """kg/m^3 by part label; ``default`` for labels not listed.

    Furniture panels are particle board/MDF (~650); handles are aluminium (2700); a mattress is foam
    (~120); a microwave/refrigerator shell is thin steel over air, modelled as a solid of
    ``appliance`` effective density.
    """

    wood: float = 650.0
    handle: float = 2700.0
    mattress: float = 120.0
    appliance: float = 900.0
    default: float = 650.0

    def for_part(self, category: str, label: str) -> float:
        if label == "handle":
            return self.handle
        if label == "mattress":
            return self.mattress
        if category in ("microwave", "refrigerator"):
            return self.appliance
        return self.wood


@dataclass(frozen=True)
class JointDynamics:
    """URDF ``<limit>``/``<dynamics>`` values by joint type.

    Prismatic: effort N, velocity m/s, damping N s/m, friction N. Revolute: N m, rad/s, N m s/rad, N m.
    Fixed joints carry zero damping/friction.
    """

    prismatic_effort: float = 100.0
    prismatic_velocity: float = 0.5
    prismatic_damping: float = 5.0
    prismatic_friction: float = 1.0
    revolute_effort: float = 50.0
    revolute_velocity: float = 1.5
    revolute_damping: float = 0.5
    revolute_friction: float = 0.2


@dataclass(frozen=True)
class GeneratorConfig:
    """Construction constants shared by the object generators.

    ``panel``: body panel thickness. ``front``: drawer/door front thickness. ``front_gap``: gap
    between a body's front plane and the back face of its drawer/door fronts, and between adjacent
    fronts. ``drawer_clearance``: free space between a drawer box and its bay, per side (the drawer
    never touches its body along [0, upper]). ``drawer_wall``: drawer box wall thickness.
    ``drawer_travel``: upper limit of a drawer as a fraction of its box depth. ``door_upper``:
    (min, max) door opening range, radians. ``handle_standoff``: free space behind a bar handle for
    fingers.
    """

    panel: float = 0.018
    front: float = 0.018
    front_gap: float = 0.003
    drawer_clearance: float = 0.004
    drawer_wall: float = 0.012
    drawer_travel: float = 0.8
    door_upper: tuple[float, float] = (1.6, 1.9)
    handle_standoff: float = 0.035
    densities: Densities = field(default_factory=Densities)
    dynamics: JointDynamics = field(default_factory=JointDynamics)


@dataclass(frozen=True)
class ComposerConfig:
    """Room composition constants.

    ``front_clearance``: free floor depth in front of an articulated object's closed front (besides
    its opening parts' sweep) kept for a mobile robot: a robot with a ~0.7 m base standing 0.5-0.9 m
    in front of a handle reaches ~1.25 m out. ``robot_reach``: no other object within this distance of
    a handle's path over its joint range (in front of the object), so a robot that follows a swinging
    door's handle does not run into a neighbour. ``wall_gap``: gap between an object's back and its wall.
    ``object_gap``: minimum gap between the footprints of two objects. ``wall_thickness``/
    ``wall_height``: wall boxes. ``max_tries``: random placements tried per object.
    """

    front_clearance: float = 1.3
    robot_reach: float = 0.9
    wall_gap: float = 0.02
    object_gap: float = 0.05
    wall_thickness: float = 0.1
    wall_height: float = 2.5
    max_tries: int = 400


DEFAULT_GENERATOR = GeneratorConfig()
DEFAULT_COMPOSER = ComposerConfig()
