"""Single-front URDFs at any height, written at test time: a box cabinet (back, sides, top, bottom panels) whose
front faces world -x at ``x = FRONT_X``, closed by one door with a handle bar.

``hinge``: ``"side"`` (a vertical hinge on the cabinet's -y edge, a vertical bar near the free edge: a
microwave or wall-cabinet door), ``"bottom"`` (a horizontal hinge along the bottom front edge, the door
swinging down and out, a horizontal bar near its top: a dishwasher or oven door) or ``"top"`` (a horizontal
hinge along the top front edge, the door swinging up and out, a bar near its bottom: a wall-cabinet flap).
Every joint opens toward positive values; the door stands 2 mm in front of the body (no contact at rest).
A door on a horizontal hinge gets a joint friction that holds it against gravity at any angle, as the
counterbalance springs of a dishwasher door and the friction hinges or gas struts of a flap do.
The handle bar is a 2 cm square box (``bar="box"``) or a round bar of 2 cm diameter (``bar="round"``).
"""

from __future__ import annotations

from pathlib import Path

FRONT_X = 1.2
_GAP = 0.002


def _box(size, xyz) -> str:
    s = " ".join(f"{v:.4f}" for v in size)
    o = " ".join(f"{v:.4f}" for v in xyz)
    g = f'<origin xyz="{o}"/><geometry><box size="{s}"/></geometry>'
    return f"    <visual>{g}</visual>\n    <collision>{g}</collision>\n"


def _cylinder(radius: float, length: float, xyz, long_axis: int) -> str:
    """A cylinder along link axis ``long_axis`` (0, 1, 2) centred at ``xyz``."""
    rpy = ("0 1.5708 0", "1.5708 0 0", "0 0 0")[long_axis]
    o = " ".join(f"{v:.4f}" for v in xyz)
    g = f'<origin xyz="{o}" rpy="{rpy}"/><geometry><cylinder radius="{radius:.4f}" length="{length:.4f}"/></geometry>'
    return f"    <visual>{g}</visual>\n    <collision>{g}</collision>\n"


def _inertial(mass: float, size=(0.1, 0.1, 0.1), xyz=(0.0, 0.0, 0.0)) -> str:
    """A solid box's inertia (kg m^2) about its centre ``xyz`` (link frame)."""
    x, y, z = size
    ixx, iyy, izz = (mass / 12 * (y * y + z * z), mass / 12 * (x * x + z * z), mass / 12 * (x * x + y * y))
    o = " ".join(f"{v:.4f}" for v in xyz)
    return (f'    <inertial><origin xyz="{o}"/><mass value="{mass}"/>'
            f'<inertia ixx="{ixx:.5f}" ixy="0" ixz="0" iyy="{iyy:.5f}" iyz="0" izz="{izz:.5f}"/></inertial>\n')


def single_front_urdf(path: Path, *, hinge: str, bottom: float, width: float = 0.5, height: float = 0.35,
                      depth: float = 0.4, name: str = "unit1", upper: float = 1.5, bar: str = "box",
                      friction: float | None = None) -> Path:
    """Write the cabinet with its body's bottom ``bottom`` m above the floor (0 stands on it; above, it hangs
    from an invisible wall). The door is ``width x height`` m; the joint is ``{name}_door2_joint``, limits
    ``[0, upper]`` rad, joint friction ``friction`` N*m (default: 0.2 on a vertical hinge, 12 on a horizontal
    one). ``bar``: "box" or "round". Returns ``path``."""
    t, w, h, d, kind = 0.02, width, height, depth, bar
    x0 = FRONT_X                                   # the body's front plane
    zc = bottom + h / 2
    body = _inertial(20.0, (d, w, h), (x0 + d / 2, 0, zc))
    body += _box((t, w, h), (x0 + d - t / 2, 0, zc))                       # back
    body += _box((d, t, h), (x0 + d / 2, -w / 2 + t / 2, zc))              # sides
    body += _box((d, t, h), (x0 + d / 2, w / 2 - t / 2, zc))
    body += _box((d, w, t), (x0 + d / 2, 0, bottom + h - t / 2))           # top
    body += _box((d, w, t), (x0 + d / 2, 0, bottom + t / 2))               # bottom
    xd = x0 - _GAP - t / 2                          # the door panel's centre plane
    if hinge == "side":
        origin, axis = (xd, -w / 2, zc), (0, 0, 1)
        centre = (0, w / 2, 0)
        bar, bar_at = (0.02, 0.02, min(0.2, 0.6 * h)), (-0.045, w - 0.06, 0)
    elif hinge == "bottom":
        origin, axis = (xd, 0, bottom), (0, -1, 0)
        centre = (0, 0, h / 2)
        bar, bar_at = (0.02, min(0.3, 0.6 * w), 0.02), (-0.045, 0, h - 0.05)
    elif hinge == "top":
        origin, axis = (xd, 0, bottom + h), (0, 1, 0)
        centre = (0, 0, -h / 2)
        bar, bar_at = (0.02, min(0.3, 0.6 * w), 0.02), (-0.045, 0, -h + 0.05)
    else:
        raise ValueError(f"hinge must be side, bottom or top, got {hinge!r}")
    panel = _inertial(3.0, (t, w, h), centre) + _box((t, w - 0.004, h - 0.004), centre)
    long_axis = 2 if hinge == "side" else 1
    if kind not in ("box", "round"):
        raise ValueError(f"bar must be box or round, got {kind!r}")
    shape = _box(bar, bar_at) if kind == "box" else _cylinder(bar[0] / 2, bar[long_axis], bar_at, long_axis)
    handle = _inertial(0.2, bar, bar_at) + shape
    # two standoffs from the bar's back to the panel's front face, near the bar's ends
    back, face = bar_at[0] + bar[0] / 2, -t / 2
    for sign in (-1, 1):
        at = list(bar_at)
        at[0] = (back + face) / 2
        at[long_axis] += sign * (bar[long_axis] / 2 - 0.015)
        handle += _box((face - back, 0.015, 0.015), at)
    if friction is None:
        friction = 0.2 if hinge == "side" else 12.0     # N*m; gravity on the door: 3 kg * 9.81 * h / 2 <= 11 N*m
    o = " ".join(f"{v:.4f}" for v in origin)
    a = " ".join(f"{v:g}" for v in axis)
    text = (f'<?xml version="1.0"?>\n<robot name="{name}">\n  <link name="world"/>\n'
            f'  <link name="{name}_body1">\n{body}  </link>\n'
            f'  <joint name="{name}_body1_joint" type="fixed"><parent link="world"/><child link="{name}_body1"/>'
            f'<origin xyz="0 0 0"/></joint>\n'
            f'  <link name="{name}_door2">\n{panel}  </link>\n'
            f'  <joint name="{name}_door2_joint" type="revolute"><parent link="{name}_body1"/>'
            f'<child link="{name}_door2"/><origin xyz="{o}"/><axis xyz="{a}"/>'
            f'<limit lower="0" upper="{upper}" effort="100" velocity="1.0"/>'
            f'<dynamics damping="1.0" friction="{friction}"/></joint>\n'
            f'  <link name="{name}_handle3">\n{handle}  </link>\n'
            f'  <joint name="{name}_handle3_joint" type="fixed"><parent link="{name}_door2"/>'
            f'<child link="{name}_handle3"/><origin xyz="0 0 0"/></joint>\n'
            f"</robot>\n")
    path = Path(path)
    path.write_text(text)
    return path
