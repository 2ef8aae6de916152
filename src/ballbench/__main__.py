"""``python -m ballbench``: the ``ballbench`` command."""
from ballbench.validation.cli import main

raise SystemExit(main())
