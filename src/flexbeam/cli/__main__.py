"""``python -m flexbeam.cli``: the ``flexbeam`` command."""

from . import main

main()
