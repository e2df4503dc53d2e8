"""Entry point of ``python3 -m rbsim`` (see :mod:`rbsim.cli`)."""

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
