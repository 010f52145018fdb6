"""`glideplan warm-up`: compile every numba kernel once (see `glideplan.warmup`)."""

from __future__ import annotations

import typer

from glideplan.cli.app import app


@app.command("warm-up")
def warm_up_command(
    jobs: int = typer.Option(1, "--jobs", min=1, max=64, help="cases run at once (processes)"),
) -> None:
    """Compile the compiled kernels once (~1 min on a fresh install), so first calls are fast.

    Runs one small case of each product (Dubins, wind, chapters 4-6, route, mission, glide
    reach, turn-back) and prints the seconds each took; the kernels stay cached on disk.
    Exits 1 when a case failed (its command is one of the README's examples).
    """
    from glideplan.warmup import warm_up

    failed = 0
    for kernels, seconds, code in warm_up(jobs=jobs):
        note = "" if code == 0 else f"  (exit {code}: not fully warmed)"
        failed += code != 0
        typer.echo(f"{kernels:28s} {seconds:6.1f} s{note}")
    if failed:
        typer.echo(f"glideplan: error: warm-up: {failed} case(s) failed (run them alone to see "
                   "why: `glideplan warm-up` lists them above)", err=True)
        raise typer.Exit(1)
