"""The CLI framework: exit codes and one-line errors."""

import subprocess
import sys

from glideplan.cli.app import main


def test_no_arguments_prints_help(capsys):
    assert main([]) == 0
    assert "plan" in capsys.readouterr().out


def test_unknown_command_is_one_line_exit_2(cli_error):
    cli_error("fly-me-to-the-moon")


def test_reproduce_rejects_unknown_figure(cli_error, tmp_path):
    assert "fig99.9" in cli_error("reproduce", "--only", "fig99.9", "--out", str(tmp_path))


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


def test_reproduce_index_links_are_relative_to_the_output(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["reproduce", "--only", "fig2.2", "--out", "rel"]) == 0
    index = (tmp_path / "rel" / "index.md").read_text()
    links = [line.split("](")[1].split(")")[0] for line in index.splitlines() if "![" in line]
    assert links and all((tmp_path / "rel" / link).is_file() for link in links)
