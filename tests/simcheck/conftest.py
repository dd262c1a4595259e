"""simcheck tests: make the helper modules beside the tests importable (pytest runs with
``--import-mode=importlib``, which does not put test folders on ``sys.path``). Helper modules are
prefixed ``simcheck_`` so they cannot shadow another package's test helpers."""

import sys
from pathlib import Path

_HERE = str(Path(__file__).parent)
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)
