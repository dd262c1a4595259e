"""``python -m simcheck`` = the ``simcheck`` console script."""

import sys

from simcheck.cli import main

sys.exit(main())
