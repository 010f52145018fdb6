"""`glideplan study cross-track`: the resumable Monte Carlo study of Fig 3.4."""

from __future__ import annotations

import math
import pathlib
from typing import TYPE_CHECKING, Annotated

import typer

from glideplan.cli.app import study_app
from glideplan.errors import InvalidParameterError
from glideplan.studies.cross_track import MAX_DT_FRACTION

if TYPE_CHECKING:
    from glideplan.studies.cross_track import CrossTrackConfig, CrossTrackResult


def _values(name: str, items: list[str] | None) -> tuple[float, ...] | None:
    """Numbers from repeated options, each a number, a comma list or START:STOP:STEP."""
    if not items:
        return None
    out: list[float] = []
    for item in items:
        for part in str(item).split(","):
            part = part.strip()
            if not part:
                continue
            try:
                if ":" in part:
                    a, b, step = (float(x) for x in part.split(":"))
                    if not step > 0 or not math.isfinite(a + b + step):
                        raise ValueError
                    n = math.floor((b - a) / step + 1e-9) + 1
                    out.extend(round(a + i * step, 10) for i in range(max(0, n)))
                else:
                    out.append(float(part))
            except ValueError:
                raise InvalidParameterError(
                    name, item, "must be numbers, comma lists or START:STOP:STEP"
                ) from None
    for v in out:
        if not math.isfinite(v):
            raise InvalidParameterError(name, v, "must be finite")
    return tuple(out)


TABLE_COLUMNS = (
    ("case", "steady (constant wind) or unsteady (Dryden gusts)"),
    ("eps", "disturbance bound delta_max / v"),
    ("R0'/R0", "feasible turn radius over R0, (1 + eps)^2 (3.3)"),
    ("E(R)", "mean final cross-track error / R0 at the smallest and largest R_plan simulated "
             "(the header shows that R_plan)"),
    ("R~R0'", "the simulated R_plan nearest R0'/R0"),
    ("E(R~R0')", "mean final cross-track error / R0 at that R_plan"),
    ("knee", "smallest R_plan whose mean error lies within 10% of the curve's drop above its "
             "minimum (where the curve flattens)"),
    ("failures", "runs that never crossed the finish line (left out of the means)"),
)  # fmt: skip


#: The study's library parameter names -> the options the user gave (errors name the option).
_CROSS_TRACK_FLAGS = {
    "samples": "--samples",
    "chunk": "--chunk",
    "seed": "--seed",
    "case": "--case",
    "eps": "--eps",
    "r_plan": "--r-plan",
    "speed": "--speed",
    "u_max": "--u-max",
    "max_turn_rate": "--u-max",
    "gust_scale": "--gust-scale",
    "dt": "--dt",
    "out": "--out",
    "scheduler": "--scheduler",
    "processes": "--processes",
}


# cross_track_command's options (module level keeps the command itself short)
_CrossTrackOut = Annotated[
    pathlib.Path,
    typer.Option(
        "--out",
        metavar="DIR",
        help="Directory for samples.sqlite and summary.json.",
        show_default=False,
    ),
]
_CrossTrackEps = Annotated[
    list[str] | None,
    typer.Option(
        "--eps",
        metavar="LIST",
        help="Disturbance bounds eps = delta_max / v (repeat or a,b,c).",
        show_default="0.25,0.5,0.75,0.95",
    ),
]
_CrossTrackRPlan = Annotated[
    list[str] | None,
    typer.Option(
        "--r-plan",
        metavar="LIST",
        help="Planning radii / R0 (repeat, a,b,c or START:STOP:STEP).",
        show_default="1:4:0.1",
    ),
]
_CrossTrackScheduler = Annotated[
    str | None,
    typer.Option("--scheduler", help="Dask scheduler ADDRESS (default: local processes)."),
]
_CrossTrackProcesses = Annotated[
    int | None, typer.Option("--processes", help="Local worker processes (default: cores).")
]
_CrossTrackDt = Annotated[
    float,
    typer.Option(
        "--dt",
        help=f"Simulation time step (s); at most {MAX_DT_FRACTION:g} / u_max, a tenth of "
        "the time to turn one radian.",
    ),
]
_CrossTrackGustScale = Annotated[
    float,
    typer.Option(
        "--gust-scale",
        help="SENSITIVITY OPTION, not the dissertation's model: multiply the Dryden gust "
        "RMS (eps v) by F; the saturation stays eps v. 1 = the model as stated.",
        metavar="F",
    ),
]
_CrossTrackProgress = Annotated[
    bool, typer.Option("--progress/--no-progress", help="Show a progress bar.")
]


@study_app.command(
    "cross-track",
    epilog="Table columns: " + "; ".join(f"{name}: {text}" for name, text in TABLE_COLUMNS) + ".",
)
def cross_track_command(
    out: _CrossTrackOut,
    eps: _CrossTrackEps = None,
    r_plan: _CrossTrackRPlan = None,
    samples: Annotated[int, typer.Option("--samples", help="Goals per (case, eps, r_plan).")] = 900,
    case: Annotated[str, typer.Option("--case", help="steady, unsteady or both.")] = "both",
    seed: Annotated[int, typer.Option("--seed", help="Master random seed.")] = 0,
    scheduler: _CrossTrackScheduler = None,
    processes: _CrossTrackProcesses = None,
    chunk: Annotated[int, typer.Option("--chunk", help="Samples per work unit.")] = 100,
    speed: Annotated[float, typer.Option("--speed", help="Airspeed v (m/s).")] = 20.0,
    u_max: Annotated[float, typer.Option("--u-max", help="Turn-rate bound u_max (rad/s).")] = 0.3,
    dt: _CrossTrackDt = 0.05,
    gust_scale: _CrossTrackGustScale = 1.0,
    json_out: Annotated[bool, typer.Option("--json", help="Print the summary as JSON.")] = False,
    progress: _CrossTrackProgress = True,
) -> None:
    """Mean final cross-track error vs planning radius, steady and Dryden disturbances (3.4).

    Results are written as work units finish; rerunning the command resumes a stopped study.
    A results file written with another configuration is refused, never mixed.
    """
    from glideplan.cli.common import check_output_dir, flag_names, print_json
    from glideplan.studies.cross_track import (
        DEFAULT_EPS,
        DEFAULT_R_PLAN,
        CrossTrackConfig,
        run_cross_track_study,
    )

    cases = {"both": ("steady", "unsteady"), "steady": ("steady",), "unsteady": ("unsteady",)}
    if case not in cases:
        raise InvalidParameterError("--case", case, "must be steady, unsteady or both")
    if scheduler is not None and not scheduler.strip():
        raise InvalidParameterError("--scheduler", scheduler, "must be a scheduler address")
    check_output_dir(out, "--out")
    follower = {} if dt == 0.05 else {"dt": dt}
    with flag_names(**_CROSS_TRACK_FLAGS):
        config = CrossTrackConfig(
            eps=_values("--eps", eps) or DEFAULT_EPS,
            r_plan=_values("--r-plan", r_plan) or DEFAULT_R_PLAN,
            samples=samples,
            cases=cases[case],
            seed=seed,
            speed=speed,
            max_turn_rate=u_max,
            chunk=chunk,
            gust_scale=gust_scale,
            follower=follower,
        )
        result = run_cross_track_study(
            out, config, scheduler=scheduler, processes=processes, progress=progress
        )
    if json_out:
        print_json({"summary": result.summary, "knees": result.knees, "directory": str(out)})
        return
    _print_cross_track(result, config, out, gust_scale)


def _print_cross_track(result: CrossTrackResult, config: CrossTrackConfig, out: pathlib.Path,
                       gust_scale: float) -> None:
    """The study's table: per case and eps, E at the first radius, near R0', at the last; the
    knee; failures; then the work units run and resumed."""
    from rich.console import Console
    from rich.table import Table

    title = f"final cross-track error / R0 ({out / 'summary.json'})"
    if gust_scale != 1.0:
        title += f", gust scale {gust_scale:g} (sensitivity)"
    table = Table(title=title)
    r_first, r_last = min(config.r_plan), max(config.r_plan)
    headers = ("case", "eps", "R0'/R0", f"E({r_first:g})", "R~R0'", "E(R~R0')",
               f"E({r_last:g})", "knee", "failures")  # fmt: skip
    for col in headers:
        table.add_column(col, justify="right")

    def fmt(v: float | None) -> str:
        return "n/a" if v is None else f"{v:.3f}"

    for c in config.cases:
        for e in config.eps:
            pts = sorted(
                (s for s in result.summary if s["case"] == c and s["eps"] == e),
                key=lambda s: s["r_plan"],
            )
            if not pts:
                continue
            rf = (1 + e) ** 2
            near = min(pts, key=lambda s: abs(s["r_plan"] - rf))
            table.add_row(
                c,
                f"{e:g}",
                f"{rf:.2f}",
                fmt(pts[0]["mean_error"]),
                f"{near['r_plan']:g}",
                fmt(near["mean_error"]),
                fmt(pts[-1]["mean_error"]),
                f"{result.knees[c][e]:.2f}",
                str(sum(p["failures"] for p in pts)),
            )
    Console().print(table)
    r = result.report
    typer.echo(
        f"{r.ran} work unit(s) run, {r.skipped} resumed from the results file, {r.seconds:.1f} s"
    )
