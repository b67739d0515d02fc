"""``python -m factask`` runs the command line."""

from factask.cli import main

main()
