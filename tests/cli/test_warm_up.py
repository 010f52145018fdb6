"""`glideplan warm-up` runs README commands: each case is a registered command, and its exact
argument list appears in the README's command list (reference: the README itself), so the
warm-up cannot drift into running commands that no longer exist."""

from __future__ import annotations

import pathlib

from glideplan.cli.app import command_index
from glideplan.warmup import WARM_UP_CASES

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def test_every_case_is_a_registered_readme_command() -> None:
    commands = command_index().commands
    readme = README.read_text()
    lines = [ln.split("#")[0].replace("\\", " ").split() for ln in readme.splitlines()
             if ln.startswith("glideplan ")]
    for case in WARM_UP_CASES:
        words = case.args
        path = tuple(w for w in words[:2] if not w.startswith("-") and w != "@mission")
        assert path in commands or path[:1] in commands, case
        # the case's options appear, in order, in one of the README's command lines
        opts = [w for w in words if w != "@mission"]
        assert any(ln[1:1 + len(path)] == list(path)
                   and all(o in ln for o in opts) for ln in lines), case
