"""``python -m symtmm`` is the ``symtmm`` command."""

import sys

from .cli import main

if __name__ == "__main__":      # (not in a child process, which imports this module anew)
    sys.exit(main())
