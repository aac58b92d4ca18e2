"""`python -m stratum.cli`: the `stratum` command without the installed console script."""

import sys

from . import main

sys.exit(main())
