"""Run the benchmark scripts in this folder one after the other, in separate processes.

`python benchmarks/run_all.py` runs the speed benchmarks (a few minutes);
`python benchmarks/run_all.py --validate` runs the validation scripts, `*_vs_direct.py`
(synthesis against the direct method on hundreds of random goals; tens of minutes) and
`validate_*.py` (long cross-checks moved out of the test suite).
"""

import pathlib
import subprocess
import sys

HERE = pathlib.Path(__file__).parent

if __name__ == "__main__":
    validate = "--validate" in sys.argv[1:]
    scripts = [
        p
        for p in sorted(HERE.glob("*.py"))
        if p.name != "run_all.py"
        and not p.name.startswith("_")
        and (p.name.endswith("_vs_direct.py") or p.name.startswith("validate_")) == validate
    ]
    failed = []
    for script in scripts:
        print(f"\n=== {script.name} ===", flush=True)
        if subprocess.run([sys.executable, str(script)], check=False).returncode:
            failed.append(script.name)
    if failed:
        print("failed:", ", ".join(failed))
        sys.exit(1)
