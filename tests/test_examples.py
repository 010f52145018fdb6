"""Every script in examples/ runs to completion (CI runs them through this test).

Each runs in a fresh interpreter in an empty directory (also its $GLIDEPLAN_OUT); it must
exit 0 without a traceback, print its results, and every file it writes must be readable by
its format's own reader (PNG signature and Matplotlib's reader, TOML by tomllib). A script
whose docstring promises a figure in $GLIDEPLAN_OUT must write one.
"""

import ast
import os
import pathlib
import subprocess
import sys
import tomllib

import pytest

EXAMPLES = sorted((pathlib.Path(__file__).parents[1] / "examples").glob("*.py"))


def test_there_are_examples():
    assert len(EXAMPLES) >= 5


@pytest.mark.parametrize("script", EXAMPLES, ids=lambda p: p.name)
def test_example_runs(script, tmp_path):
    env = os.environ | {"MPLBACKEND": "Agg", "GLIDEPLAN_OUT": str(tmp_path)}
    out = subprocess.run(
        [sys.executable, str(script)],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=tmp_path,
        env=env,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert "Traceback" not in out.stderr
    assert out.stdout.strip(), "an example prints its results"
    written = [p for p in tmp_path.rglob("*") if p.is_file()]
    doc = ast.get_docstring(ast.parse(script.read_text())) or ""
    source = script.read_text()
    if "GLIDEPLAN_OUT" in source and (".png" in doc or "figure" in doc):
        assert any(p.suffix == ".png" for p in written), (doc, written)
    for path in written:
        assert path.stat().st_size > 0, path
        if path.suffix == ".png":
            import matplotlib.image

            assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", path
            image = matplotlib.image.imread(path)
            assert image.shape[0] > 100 and image.shape[1] > 100, (path, image.shape)
        elif path.suffix == ".toml":
            assert tomllib.loads(path.read_text()), path
