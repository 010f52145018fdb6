"""The CLI framework: exit codes and one-line errors."""

import subprocess
import sys

from glideplan.cli.app import main


def test_no_arguments_prints_help(capsys):
    assert main([]) == 0
    assert "plan" in capsys.readouterr().out


def test_unknown_command_is_one_line_exit_2(capsys):
    assert main(["fly-me-to-the-moon"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("glideplan: error:")


def test_reproduce_rejects_unknown_figure(capsys, tmp_path):
    assert main(["reproduce", "--only", "fig99.9", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "fig99.9" in err[0]


def test_console_script_runs_without_traceback():
    out = subprocess.run(
        [sys.executable, "-m", "glideplan", "plan", "no-such-planner"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 2
    assert "Traceback" not in out.stderr
    assert out.stderr.strip().startswith("glideplan: error:")
