"""Rigid furniture generators: table, chair and bed (every joint fixed)."""

from __future__ import annotations

import numpy as np

from ..config import DEFAULT_GENERATOR, GeneratorConfig
from ..model import ArticulatedObject
from .builder import ObjectBuilder

__all__ = ["make_table", "make_chair", "make_bed"]


def make_table(rng: np.random.Generator, pedestal: bool | None = None,
               cfg: GeneratorConfig = DEFAULT_GENERATOR) -> ArticulatedObject:
    """A table 0.9-1.6 x 0.7-1.0 m, 0.72-0.78 m high: top on four legs or on a pedestal (column + foot)."""
    L = float(rng.uniform(0.9, 1.6))
    W = float(rng.uniform(0.7, 1.0))
    H = float(rng.uniform(0.72, 0.78))
    tt = float(rng.uniform(0.025, 0.04))
    if pedestal is None:
        pedestal = bool(rng.random() < 0.25)
    b = ObjectBuilder("table", cfg)
    top = b.add_part("top", [b.box([0, 0, H - tt / 2], [L, W, tt])], T_object_part=np.eye(4))
    b.fix(None, top)
    if pedestal:
        foot_h = 0.03
        foot = b.add_part("leg", [b.cylinder([0, 0, foot_h / 2], 0.25, foot_h)])
        col = b.add_part("leg", [b.cylinder([0, 0, foot_h + (H - tt - foot_h) / 2], 0.05, H - tt - foot_h)])
        b.fix(top, col)
        b.fix(col, foot)
        return b.build()
    s = float(rng.uniform(0.04, 0.07))
    round_legs = bool(rng.random() < 0.4)
    inset = 0.05 + s / 2
    for sx in (-1, 1):
        for sy in (-1, 1):
            c = [sx * (L / 2 - inset), sy * (W / 2 - inset), (H - tt) / 2]
            shape = b.cylinder(c, s / 2, H - tt) if round_legs else b.box(c, [s, s, H - tt])
            leg = b.add_part("leg", [shape])
            b.fix(top, leg)
    return b.build()


def make_chair(rng: np.random.Generator, arms: bool | None = None,
               cfg: GeneratorConfig = DEFAULT_GENERATOR) -> ArticulatedObject:
    """A chair: seat 0.40-0.50 m square at 0.42-0.48 m, four legs, a back, optional arms. +x = facing."""
    S = float(rng.uniform(0.40, 0.50))
    Hs = float(rng.uniform(0.42, 0.48))
    ts = 0.04
    Hb = float(rng.uniform(0.38, 0.50))
    tb = 0.03
    ls = 0.035
    if arms is None:
        arms = bool(rng.random() < 0.3)
    b = ObjectBuilder("chair", cfg)
    seat = b.add_part("seat", [b.box([0, 0, Hs - ts / 2], [S, S, ts])], T_object_part=np.eye(4))
    b.fix(None, seat)
    for sx in (-1, 1):
        for sy in (-1, 1):
            leg = b.add_part("leg", [b.box([sx * (S / 2 - ls / 2), sy * (S / 2 - ls / 2), (Hs - ts) / 2],
                                           [ls, ls, Hs - ts])])
            b.fix(seat, leg)
    back = b.add_part("back", [b.box([-S / 2 + tb / 2, 0, Hs + Hb / 2], [tb, S, Hb])])
    b.fix(seat, back)
    if arms:
        ah = 0.22
        for sy in (-1, 1):
            y = sy * (S / 2 - 0.02)
            x0, x1 = -S / 2 + tb, S / 2 - 0.02
            arm = b.add_part("arm", [b.box([x1 - 0.0125, y, Hs + ah / 2], [0.025, 0.03, ah]),
                                     b.box([(x0 + x1) / 2, y, Hs + ah + 0.0125], [x1 - x0, 0.05, 0.025])])
            b.fix(seat, arm)
            b.contact(arm, back)
    return b.build()


def make_bed(rng: np.random.Generator, cfg: GeneratorConfig = DEFAULT_GENERATOR) -> ArticulatedObject:
    """A bed 1.9-2.1 x 0.9-1.6 m: frame on four legs, a headboard at -x (the wall side), a mattress."""
    L = float(rng.uniform(1.9, 2.1))
    W = float(rng.uniform(0.9, 1.6))
    zl = float(rng.uniform(0.12, 0.22))    # leg height
    hf = 0.15                              # frame height
    hm = float(rng.uniform(0.15, 0.25))    # mattress thickness
    th = 0.05                              # headboard thickness
    Hh = float(rng.uniform(0.8, 1.1))
    b = ObjectBuilder("bed", cfg)
    x0 = -L / 2 + th                       # frame starts in front of the headboard
    frame = b.add_part("frame", [b.box([(x0 + L / 2) / 2, 0, zl + hf / 2], [L / 2 - x0, W, hf])],
                       T_object_part=np.eye(4))
    b.fix(None, frame)
    for sx in (x0 + 0.04, L / 2 - 0.04):
        for sy in (-1, 1):
            leg = b.add_part("leg", [b.box([sx, sy * (W / 2 - 0.04), zl / 2], [0.06, 0.06, zl])])
            b.fix(frame, leg)
    head = b.add_part("headboard", [b.box([-L / 2 + th / 2, 0, Hh / 2], [th, W + 0.04, Hh])])
    b.fix(frame, head)
    mat = b.add_part("mattress", [b.box([(x0 + L / 2 - 0.02) / 2, 0, zl + hf + hm / 2],
                                        [L / 2 - 0.02 - x0, W - 0.04, hm])])
    b.fix(frame, mat)
    b.contact(head, mat)
    return b.build()
