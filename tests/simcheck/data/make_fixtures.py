"""One-off generator of the hand-made fixture URDFs (output committed under tests/simcheck/data)."""
def box(size, xyz, rgba="0.7 0.7 0.7 1", rpy="0 0 0"):
    s = " ".join(f"{v:g}" for v in size); o = " ".join(f"{v:g}" for v in xyz)
    return (f'    <visual><origin xyz="{o}" rpy="{rpy}"/><geometry><box size="{s}"/></geometry>'
            f'<material name="m{abs(hash(rgba))%1000}"><color rgba="{rgba}"/></material></visual>\n'
            f'    <collision><origin xyz="{o}" rpy="{rpy}"/><geometry><box size="{s}"/></geometry></collision>\n')
def inertial(m, i=0.01, xyz=(0,0,0)):
    o = " ".join(f"{v:g}" for v in xyz)
    return f'    <inertial><origin xyz="{o}"/><mass value="{m}"/><inertia ixx="{i}" iyy="{i}" izz="{i}" ixy="0" ixz="0" iyz="0"/></inertial>\n'
def link(name, body):
    return f'  <link name="{name}">\n{body}  </link>\n'
def joint(name, typ, parent, child, xyz, axis=None, lim=None, rpy="0 0 0", damping=1.0, friction=0.2):
    o = " ".join(f"{v:g}" for v in xyz)
    s = f'  <joint name="{name}" type="{typ}"><parent link="{parent}"/><child link="{child}"/><origin xyz="{o}" rpy="{rpy}"/>'
    if axis is not None:
        s += f'<axis xyz="{" ".join(f"{v:g}" for v in axis)}"/>'
    if lim is not None:
        s += f'<limit lower="{lim[0]:g}" upper="{lim[1]:g}" effort="{lim[2]:g}" velocity="{lim[3]:g}"/>'
        s += f'<dynamics damping="{damping:g}" friction="{friction:g}"/>'
    return s + '</joint>\n'

def cabinet(extra=""):
    out = '<?xml version="1.0"?>\n<robot name="fixture_cabinet">\n'
    out += link("world", "")
    B = "0.55 0.45 0.35 1"
    body = inertial(20.0, 1.0, (0, 0, 0.4))
    body += box((0.02, 0.6, 0.8), (-0.24, 0, 0.4), B)          # back
    body += box((0.5, 0.02, 0.8), (0, -0.29, 0.4), B)          # sides
    body += box((0.5, 0.02, 0.8), (0, 0.29, 0.4), B)
    body += box((0.5, 0.56, 0.02), (0, 0, 0.79), B)            # top
    body += box((0.5, 0.56, 0.02), (0, 0, 0.01), B)            # bottom
    body += box((0.5, 0.56, 0.02), (0, 0, 0.40), B)            # shelf
    out += link("cabinet1_body1", body)
    out += joint("cabinet1_body1_joint", "fixed", "world", "cabinet1_body1", (0, 0, 0))
    D = "0.8 0.75 0.6 1"
    dr = inertial(2.0, 0.05, (-0.2, 0, -0.05))
    dr += box((0.02, 0.54, 0.34), (-0.01, 0, 0), D)
    dr += box((0.40, 0.50, 0.01), (-0.22, 0, -0.15), D)
    dr += box((0.40, 0.01, 0.18), (-0.22, -0.245, -0.06), D)
    dr += box((0.40, 0.01, 0.18), (-0.22, 0.245, -0.06), D)
    dr += box((0.01, 0.50, 0.18), (-0.415, 0, -0.06), D)
    out += link("cabinet1_drawer2", dr)
    out += joint("cabinet1_drawer2_joint", "prismatic", "cabinet1_body1", "cabinet1_drawer2", (0.25, 0, 0.6), (1, 0, 0), (0, 0.35, 100, 1.0), damping=2.0, friction=0.5)
    H = "0.2 0.2 0.2 1"
    hd = inertial(0.1, 0.001) + box((0.02, 0.14, 0.02), (0, 0, 0), H) + box((0.03, 0.015, 0.015), (-0.025, -0.06, 0), H) + box((0.03, 0.015, 0.015), (-0.025, 0.06, 0), H)
    out += link("cabinet1_handle3", hd)
    out += joint("cabinet1_handle3_joint", "fixed", "cabinet1_drawer2", "cabinet1_handle3", (0.04, 0, 0.08))
    dd = inertial(3.0, 0.1, (0.01, 0.28, 0)) + box((0.02, 0.56, 0.36), (0.01, 0.28, 0), D)
    out += link("cabinet1_door4", dd)
    out += joint("cabinet1_door4_joint", "revolute", "cabinet1_body1", "cabinet1_door4", (0.25, -0.28, 0.2), (0, 0, -1), (0, 1.7, 100, 1.0), damping=1.0, friction=0.3)
    out += link("cabinet1_handle5", hd)
    out += joint("cabinet1_handle5_joint", "fixed", "cabinet1_door4", "cabinet1_handle5", (0.06, 0.48, 0.05))
    out += extra
    return out + "</robot>\n"

def gantry():
    out = '<?xml version="1.0"?>\n<robot name="gantry_gripper">\n'
    out += link("base", inertial(1.0))
    for name, parent, axis, lim in [("x_joint", "base", (1, 0, 0), (-2, 3)), ("y_joint", "x_link", (0, 1, 0), (-2, 2)),
                                    ("z_joint", "y_link", (0, 0, 1), (0, 1.6))]:
        child = name.replace("joint", "link")
        out += link(child, inertial(1.0))
        out += joint(name, "prismatic", parent, child, (0, 0, 0), axis, (*lim, 2000, 1.0), damping=0, friction=0)
    G = "0.3 0.3 0.8 1"
    out += link("hand", inertial(0.5, 0.002) + box((0.06, 0.08, 0.08), (0, 0, 0), G))
    out += joint("yaw_joint", "revolute", "z_link", "hand", (0, 0, 0), (0, 0, 1), (-3.2, 3.2, 500, 1.5), damping=0, friction=0)
    F = "0.1 0.1 0.1 1"
    out += link("finger_top", inertial(0.05, 0.0001) + box((0.05, 0.02, 0.01), (-0.065, 0, 0), F))
    out += joint("finger_top_joint", "prismatic", "hand", "finger_top", (0, 0, 0.035), (0, 0, -1), (0, 0.04, 100, 0.2), damping=0, friction=0)
    out += link("finger_bottom", inertial(0.05, 0.0001) + box((0.05, 0.02, 0.01), (-0.065, 0, 0), F))
    out += joint("finger_bottom_joint", "prismatic", "hand", "finger_bottom", (0, 0, -0.035), (0, 0, 1), (0, 0.04, 100, 0.2), damping=0, friction=0)
    out += link("tool", inertial(0.01, 1e-5))
    out += joint("tool_joint", "fixed", "hand", "tool", (-0.07, 0, 0))
    return out + "</robot>\n"

import sys
d = sys.argv[1]
open(f"{d}/cabinet.urdf", "w").write(cabinet())
# the same cabinet with a neighbouring box in the swing of the door (a "blocked" reference)
blocker = ('  <link name="box9_body9">\n' + inertial(5.0, 0.1) + box((0.2, 0.2, 0.15), (0, 0, 0), "0.4 0.6 0.4 1") + '  </link>\n'
           + joint("box9_body9_joint", "fixed", "world", "box9_body9", (0.6, 0.05, 0.075)))
open(f"{d}/cabinet_blocked.urdf", "w").write(cabinet(blocker))
open(f"{d}/gantry_gripper.urdf", "w").write(gantry())
