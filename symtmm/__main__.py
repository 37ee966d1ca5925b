"""``python -m symtmm`` is the ``symtmm`` command."""

import sys

from .cli import main

sys.exit(main())
