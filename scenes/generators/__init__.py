"""Object generators: each ``make_<category>(rng, ...)`` returns an object with id 0 and local part ids."""

from __future__ import annotations

from .cabinet import CABINET_LAYOUTS, MIXED_CABINET_LAYOUTS, make_cabinet
from .furniture import make_bed, make_chair, make_table
from .handles import HANDLE_STYLES
from .microwave import make_microwave
from .refrigerator import FRIDGE_LAYOUTS, make_refrigerator

__all__ = ["GENERATORS", "CATEGORIES", "make_cabinet", "make_microwave", "make_refrigerator",
           "make_table", "make_chair", "make_bed", "CABINET_LAYOUTS", "MIXED_CABINET_LAYOUTS",
           "FRIDGE_LAYOUTS", "HANDLE_STYLES"]

GENERATORS = {
    "cabinet": make_cabinet,
    "microwave": make_microwave,
    "refrigerator": make_refrigerator,
    "table": make_table,
    "chair": make_chair,
    "bed": make_bed,
}
CATEGORIES = tuple(GENERATORS)
