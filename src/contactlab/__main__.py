"""Allow ``python -m contactlab``."""

import sys

from contactlab.cli import main

sys.exit(main())
