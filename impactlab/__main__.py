import sys

from impactlab.cli import main

sys.exit(main())
