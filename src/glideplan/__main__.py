"""`python -m glideplan` runs the CLI."""

from glideplan.cli.app import run

run()
