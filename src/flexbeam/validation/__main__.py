"""``python -m flexbeam.validation [--reduced] [--out docs] [--only SECTION ...]``."""

import sys

from .runner import main

sys.exit(main())
