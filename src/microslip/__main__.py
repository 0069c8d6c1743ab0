"""``python -m microslip`` runs the command line."""

import sys

try:
    from .cli.main import entry
except KeyboardInterrupt:  # Ctrl-C while the package loads: one line, as in main()
    print("error: interrupted", file=sys.stderr)
    sys.exit(130)

entry()
