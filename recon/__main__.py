"""``python -m recon`` = the ``recon`` console script."""

import sys

from recon.cli import main

sys.exit(main())
