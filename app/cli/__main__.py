"""`python -m app.cli`: the `rolling` command."""

from app.cli import main

main()
