"""``python -m planarkin``: the same command as the ``planarkin`` console script."""

import sys

from .face.cli import main

sys.exit(main())
