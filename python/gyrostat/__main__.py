"""``python -m gyrostat``: the command line (see gyrostat.cli)."""

import sys

from gyrostat.cli import main

sys.exit(main())
