"""The only URDF reader and writer of partscene (on yourdfpy's schema dataclasses).

:func:`read_urdf` checks what every engine needs and names the file and element when something is wrong:
valid XML, one tree of links (no cycle, none cut off), known joint types, finite numbers, positive shape
sizes, a non-zero axis and ``lower <= upper`` on movable joints, existing mesh files. It keeps limits,
dynamics, inertials, visuals (with materials) and collisions; a relative mesh path is resolved against
the file's folder (the model holds absolute paths or ``package://`` URIs).

:func:`urdf_text` writes a model as pretty-printed URDF (PyBullet's tinyxml2 fails on yourdfpy's one-line
output of a large scene); :func:`write_urdf` writes it atomically.
"""

from __future__ import annotations

import hashlib
import io
import pickle
import threading
from collections import OrderedDict
from pathlib import Path

import numpy as np

from ._atomic import write_text_atomic
from ._errors import DescriptionError
from ._model import Dynamics, Inertial, Joint, JointType, Limit, Link, SceneModel
from ._shape import Material, Shape, ShapeKind

__all__ = ["MAX_NAME_LENGTH", "read_urdf", "urdf_text", "urdf_xml", "xml_text", "round_numbers", "write_urdf", "LENGTH_DECIMALS",
           "SIGNIFICANT_DIGITS"]

_TYPES = tuple(t.value for t in JointType)

#: the longest link or joint name :func:`read_urdf` accepts (characters); PyBullet crashes on names of a
#: few thousand characters, and no partscene name comes near this
MAX_NAME_LENGTH = 255


def _yourdfpy():
    """yourdfpy, imported on first use (it imports trimesh: about a second)."""
    import yourdfpy
    return yourdfpy


# ---------------------------------------------------------------------------------------------- reading
def _finite(values, where: str) -> np.ndarray:
    a = np.asarray(values, dtype=float).reshape(-1)
    if not np.all(np.isfinite(a)):
        raise DescriptionError(f"{where}: expected finite numbers, got {a.tolist()}")
    return a


def _pose(T, where: str) -> np.ndarray:
    return np.eye(4) if T is None else _finite(T, where).reshape(4, 4)


def _mesh_path(filename: str, base: Path, where: str) -> str:
    path = filename[len("file://"):] if filename.startswith("file://") else filename
    if path.startswith("package://"):
        return path
    p = Path(path) if Path(path).is_absolute() else (base / path)
    if not p.is_file():
        raise DescriptionError(f"{where} mesh {filename!r} not found (looked at {p})")
    return str(p.resolve())


def _shape(g, base: Path, at: str, what: str, material=None, name=None, origin=None) -> Shape:
    where = f"{at} {what}"
    T = _pose(origin, f"{where} origin")
    if g.box is not None:
        size = _finite(g.box.size, f"{where} box size")
        if size.shape != (3,) or size.min() <= 0:
            raise DescriptionError(f"{where} box has a non-positive size {tuple(size.tolist())}")
        return Shape(ShapeKind.BOX, size, T, name, None, material)
    if g.cylinder is not None:
        r, ln = _finite([g.cylinder.radius, g.cylinder.length], f"{where} cylinder")
        if r <= 0 or ln <= 0:
            raise DescriptionError(f"{where} cylinder has a non-positive radius/length")
        return Shape.cylinder(r, ln, T, name=name, material=material)
    if g.sphere is not None:
        r, = _finite([g.sphere.radius], f"{where} sphere")
        if r <= 0:
            raise DescriptionError(f"{where} sphere has a non-positive radius")
        return Shape.sphere(r, T, name=name, material=material)
    scale = np.ones(3) if g.mesh.scale is None else _finite(np.broadcast_to(g.mesh.scale, (3,)), f"{where} mesh scale")
    return Shape(ShapeKind.MESH, scale, T, name, _mesh_path(g.mesh.filename or "", base, at), material)


def _material(m) -> Material | None:
    if m is None:
        return None
    rgba = None if m.color is None else tuple(float(x) for x in m.color.rgba)
    return Material(m.name, rgba)


def _link(el, base: Path, where: str) -> Link:
    yourdfpy = _yourdfpy()
    name = el.get("name")
    for tag in ("visual", "collision"):
        for k, sub in enumerate(el.findall(tag)):
            g = sub.find("geometry")
            if g is None or len(g) == 0:
                raise DescriptionError(f"{where}: link {name!r} {tag} #{k} has no <geometry>")
            if g[0].tag not in ("box", "cylinder", "sphere", "mesh"):
                raise DescriptionError(f"{where}: link {name!r} has an unknown geometry <{g[0].tag}>")
    try:
        y = yourdfpy.URDF._parse_link(el)
    except (KeyError, ValueError, TypeError, AttributeError, IndexError) as e:
        raise DescriptionError(f"{where}: link {name!r} cannot be read ({type(e).__name__}: {e})") from e
    at = f"{where}: link {name!r}"
    inertial = None
    if y.inertial is not None:
        mass = 0.0 if y.inertial.mass is None else float(_finite([y.inertial.mass], f"{at} mass")[0])
        inertia = np.zeros((3, 3)) if y.inertial.inertia is None else \
            _finite(y.inertial.inertia, f"{at} inertia").reshape(3, 3)
        inertial = Inertial(mass, _pose(y.inertial.origin, f"{at} inertial origin"), inertia)
    visuals = tuple(_shape(v.geometry, base, at, f"visual #{k}", _material(v.material), v.name, v.origin)
                    for k, v in enumerate(y.visuals))
    collisions = tuple(_shape(c.geometry, base, at, f"collision #{k}", None, c.name, c.origin)
                       for k, c in enumerate(y.collisions))
    friction = el.find("contact/lateral_friction")
    lateral = None if friction is None else float(_finite([friction.get("value", "nan")], f"{at} lateral_friction")[0])
    return Link(name, inertial, visuals, collisions, lateral)


def _joint(el, where: str) -> Joint:
    yourdfpy = _yourdfpy()
    name, typ = el.get("name"), el.get("type")
    at = f"{where}: joint {name!r}"
    if typ not in _TYPES:
        raise DescriptionError(f"{at} has unknown type {typ!r} (expected one of {', '.join(_TYPES)})")
    for role in ("parent", "child"):
        if el.find(role) is None or not el.find(role).get("link"):
            raise DescriptionError(f"{at} has no <{role} link=...>")
    try:
        y = yourdfpy.URDF._parse_joint(el)
    except (KeyError, ValueError, TypeError, AttributeError, IndexError) as e:
        raise DescriptionError(f"{at} cannot be read ({type(e).__name__}: {e})") from e
    T = _pose(y.origin, f"{at} origin")
    axis = _finite(y.axis, f"{at} axis")
    limit = dynamics = None
    if y.limit is not None:
        vals = [0.0 if v is None else v for v in (y.limit.lower, y.limit.upper, y.limit.effort, y.limit.velocity)]
        limit = Limit(*(float(v) for v in _finite(vals, f"{at} limit")))
        if min(limit.effort, limit.velocity) < 0:
            raise DescriptionError(f"{at} has limit effort {limit.effort:g} and velocity {limit.velocity:g}: both "
                                   "are magnitudes (N or N m; m/s or rad/s) and must be >= 0")
    if y.dynamics is not None:
        vals = [0.0 if v is None else float(v) for v in (y.dynamics.damping, y.dynamics.friction)]
        dynamics = Dynamics(*(float(v) for v in _finite(vals, f"{at} dynamics")))
    if typ != "fixed":
        n = float(np.linalg.norm(axis))
        if n < 1e-9:
            raise DescriptionError(f"{at} has a zero axis")
        axis = axis / n
    if typ in ("prismatic", "revolute"):
        if limit is None:
            raise DescriptionError(f"{where}: {typ} joint {name!r} has no <limit>")
        if limit.upper < limit.lower:
            raise DescriptionError(f"{at} has upper limit {limit.upper:g} < lower {limit.lower:g}")
    return Joint(name, JointType(typ), y.parent, y.child, T, axis, limit, dynamics)


#: how many parsed files :func:`read_urdf` keeps (see there)
PARSED_KEPT = 8
_parsed: OrderedDict[tuple, bytes] = OrderedDict()
_parsed_lock = threading.Lock()


def read_urdf(path: str | Path) -> SceneModel:
    """The :class:`SceneModel` of the URDF file at ``path``.

    The last :data:`PARSED_KEPT` models read are kept (pickled) under the file's path and a SHA-256 of its
    bytes: reading an unchanged file again returns a fresh copy of the same model without parsing it (a
    certification reads its scene in the planner, the simulator and the judge); a changed file is parsed
    anew. Every call returns its own model, so changing one never changes another.

    Raises:
        DescriptionError: the file is missing, not XML, or malformed (names the file and the link/joint).
    """
    path = Path(path)
    if not path.is_file():
        raise DescriptionError(f"{path}: URDF file not found")
    data = path.read_bytes()
    key = (str(path), str(path.absolute()), hashlib.sha256(data).digest())
    with _parsed_lock:
        kept = _parsed.get(key)
        if kept is not None:
            _parsed.move_to_end(key)
    if kept is not None:
        return pickle.loads(kept)
    model = _parse_urdf(path, data)
    with _parsed_lock:
        _parsed[key] = pickle.dumps(model, protocol=pickle.HIGHEST_PROTOCOL)
        while len(_parsed) > PARSED_KEPT:
            _parsed.popitem(last=False)
    return model


def _parse_urdf(path: Path, data: bytes) -> SceneModel:
    """Parse and check ``data``, the bytes of the URDF file at ``path``."""
    yourdfpy = _yourdfpy()
    from lxml import etree
    where = str(path)
    try:
        root = etree.parse(io.BytesIO(data), etree.XMLParser(remove_blank_text=True, remove_comments=True),
                           base_url=str(path)).getroot()
    except etree.XMLSyntaxError as e:
        raise DescriptionError(f"{where}: not valid XML ({e})") from e
    if root.tag != "robot":
        raise DescriptionError(f"{where}: root element is <{root.tag}>, expected <robot>")
    for tag in ("link", "joint"):
        for el in root.findall(tag):
            if not el.get("name"):
                raise DescriptionError(f"{where}: a <{tag}> has no name")
            if len(el.get("name")) > MAX_NAME_LENGTH:
                raise DescriptionError(f"{where}: {tag} {el.get('name')[:40]!r}... has a name of "
                                       f"{len(el.get('name'))} characters (at most {MAX_NAME_LENGTH}): shorten it")
    links = [_link(el, path.parent, where) for el in root.findall("link")]
    joints = [_joint(el, where) for el in root.findall("joint")]
    by_name = {l.name: l for l in links}
    for j in joints:
        child = by_name.get(j.child)
        if j.type.value != "fixed" and child is not None and child.inertial is not None and \
                not child.inertial.mass > 0:
            raise DescriptionError(f"{where}: link {j.child!r} (child of {j.type.value} joint {j.name!r}) has mass "
                                   f"{child.inertial.mass:g}; a moving link needs a positive mass")
        if j.type.value != "fixed" and child is not None and child.inertial is not None:
            problem = _inertia_problem(child.inertial.inertia)
            if problem:
                raise DescriptionError(f"{where}: link {j.child!r} (child of {j.type.value} joint {j.name!r}) has an "
                                       f"inertia that {problem}; a moving link needs a physical inertia tensor")
    materials = tuple(_material(yourdfpy.URDF._parse_material(m)) for m in root.findall("material"))
    return SceneModel(root.get("name", ""), links, joints, materials, path)


def _inertia_problem(inertia: np.ndarray) -> str:
    """What is unphysical about ``inertia`` ((3, 3), kg m^2, about the centre of mass), or "" if nothing: the
    tensor must be symmetric (up to a relative 1e-6) with positive principal moments. (The triangle
    inequality is not required: PyBullet and MuJoCo simulate hand-written tensors that break it.)"""
    inertia = np.asarray(inertia, float)
    scale = max(float(np.abs(inertia).max()), 1e-300)
    if not np.allclose(inertia, inertia.T, rtol=0.0, atol=1e-6 * scale):
        return "is not symmetric"
    smallest = float(np.linalg.eigvalsh(0.5 * (inertia + inertia.T))[0])
    if not smallest > 0:
        return f"has principal moment {smallest:.3g} kg m^2 (must be > 0)"
    return ""


# ---------------------------------------------------------------------------------------------- writing
def _geometry(s: Shape):
    yourdfpy = _yourdfpy()
    if s.kind is ShapeKind.BOX:
        return yourdfpy.Geometry(box=yourdfpy.Box(size=np.asarray(s.size, float)))
    if s.kind is ShapeKind.CYLINDER:
        return yourdfpy.Geometry(cylinder=yourdfpy.Cylinder(radius=s.radius, length=s.length))
    if s.kind is ShapeKind.SPHERE:
        return yourdfpy.Geometry(sphere=yourdfpy.Sphere(radius=s.size[0] / 2.0))
    return yourdfpy.Geometry(mesh=yourdfpy.Mesh(filename=s.mesh, scale=np.asarray(s.size, float)))


def _y_material(m: Material | None):
    yourdfpy = _yourdfpy()
    if m is None:
        return None
    return yourdfpy.Material(name=m.name, color=None if m.rgba is None else yourdfpy.Color(rgba=np.asarray(m.rgba)))


def _y_link(link: Link):
    yourdfpy = _yourdfpy()
    inertial = None
    if link.inertial is not None:
        inertial = yourdfpy.Inertial(origin=link.inertial.T_link_com, mass=float(link.inertial.mass),
                                     inertia=np.asarray(link.inertial.inertia, float))
    return yourdfpy.Link(
        name=link.name, inertial=inertial,
        visuals=[yourdfpy.Visual(name=s.name, origin=s.T_link_shape, geometry=_geometry(s),
                                 material=_y_material(s.material)) for s in link.visuals],
        collisions=[yourdfpy.Collision(name=s.name, origin=s.T_link_shape, geometry=_geometry(s))
                    for s in link.collisions])


def _y_joint(j: Joint):
    yourdfpy = _yourdfpy()
    limit = None if j.limit is None else yourdfpy.Limit(effort=j.limit.effort, velocity=j.limit.velocity,
                                                         lower=j.limit.lower, upper=j.limit.upper)
    dynamics = None if j.dynamics is None else yourdfpy.Dynamics(damping=j.dynamics.damping,
                                                                  friction=j.dynamics.friction)
    return yourdfpy.Joint(name=j.name, type=j.type.value, parent=j.parent, child=j.child, origin=j.T_parent_joint,
                          axis=np.asarray(j.axis, float) if j.movable else None, limit=limit, dynamics=dynamics)


def urdf_xml(model: SceneModel):
    """The ``<robot>`` element (lxml) of ``model``: links, joints, then materials, in the model's order."""
    yourdfpy = _yourdfpy()
    robot = yourdfpy.Robot(name=model.name, links=[_y_link(l) for l in model.links.values()],
                           joints=[_y_joint(j) for j in model.joints.values()],
                           materials=[_y_material(m) for m in model.materials])
    urdf = yourdfpy.URDF(robot=robot, build_scene_graph=False, load_meshes=False, filename_handler=lambda f: f)
    root = urdf.write_xml().getroot()
    from lxml import etree
    for el in root.findall("link"):                   # PyBullet's <contact> extension (yourdfpy has none)
        friction = model.links[el.get("name")].lateral_friction
        if friction is not None:
            etree.SubElement(etree.SubElement(el, "contact"), "lateral_friction", value=repr(float(friction)))
    return root


def urdf_text(model: SceneModel, rounded: bool = False) -> str:
    """The URDF text of ``model``, pretty-printed; ``rounded``: numbers as :func:`round_numbers` writes them."""
    root = urdf_xml(model)
    if rounded:
        round_numbers(root)
    return xml_text(root)


def xml_text(element) -> str:
    """Pretty-printed text (with the XML declaration) of an lxml ``element``, e.g. one of :func:`urdf_xml`."""
    from lxml import etree
    return etree.tostring(element, xml_declaration=True, encoding="UTF-8", pretty_print=True).decode()


LENGTH_DECIMALS = 6
"""Rounded URDFs write lengths (m) and angles (rad) to 1e-6."""
SIGNIFICANT_DIGITS = 9
"""Rounded URDFs keep this many significant digits of masses and inertias."""
_LENGTH_ATTRIBUTES = {("origin", "xyz"), ("origin", "rpy"), ("box", "size"), ("cylinder", "radius"),
                      ("cylinder", "length"), ("sphere", "radius"), ("axis", "xyz"), ("limit", "lower"),
                      ("limit", "upper")}
_INERTIA_KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _length(x: float) -> str:
    text = f"{round(float(x), LENGTH_DECIMALS) + 0.0:.{LENGTH_DECIMALS}f}".rstrip("0").rstrip(".")
    return "0" if text in ("", "-0") else text


def _significant(x: float, scale: float | None = None) -> str:
    """``x`` to SIGNIFICANT_DIGITS digits (of ``scale`` when given: terms far below it become 0)."""
    x = float(x)
    if scale is not None and scale > 0:
        step = 10.0 ** (np.floor(np.log10(scale)) - (SIGNIFICANT_DIGITS - 1))
        x = round(x / step) * step
    return f"{x + 0.0:.{SIGNIFICANT_DIGITS}g}"


def round_numbers(root) -> None:
    """Rewrite the numbers of a URDF element tree in place so that the same model gives the same bytes:
    lengths and angles (origins, sizes, axes, limits) to ``LENGTH_DECIMALS`` decimals, masses, joint
    friction and damping and inertias to ``SIGNIFICANT_DIGITS`` significant digits (an inertia term relative
    to the largest term of its tensor, so round-off terms near zero are written as 0)."""
    for el in root.iter():
        for key in list(el.attrib):
            if (el.tag, key) in _LENGTH_ATTRIBUTES:
                el.set(key, " ".join(_length(float(v)) for v in el.get(key).split()))
            elif (el.tag, key) in (("mass", "value"), ("dynamics", "friction"), ("dynamics", "damping")):
                el.set(key, _significant(float(el.get(key))))
        if el.tag == "inertia":
            vals = [float(el.get(k, 0.0)) for k in _INERTIA_KEYS]
            scale = max(abs(v) for v in vals)
            for k, v in zip(_INERTIA_KEYS, vals):
                el.set(k, _significant(v, scale))


def write_urdf(model: SceneModel, path: str | Path, rounded: bool = False) -> Path:
    """Write :func:`urdf_text` of ``model`` to ``path`` atomically; returns the path."""
    return write_text_atomic(path, urdf_text(model, rounded))
