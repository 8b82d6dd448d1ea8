"""``python -m planarkin``: the same command as the ``planarkin`` console script."""

import sys

from .cli import main

sys.exit(main())
