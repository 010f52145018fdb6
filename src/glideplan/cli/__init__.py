"""The command-line interface (`glideplan ...`); see `glideplan.cli.app`."""
