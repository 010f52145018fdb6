"""The Dryden gust-scale sensitivity option, the time-step rule and the study table's columns."""

import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.simulation.disturbances import DrydenTurbulence
from glideplan.studies.cross_track import (
    MAX_DT_FRACTION,
    CrossTrackConfig,
    run_cross_track_study,
)


def test_gust_scale_multiplies_the_rms_before_saturation():
    """Hand derivation: the AR(1) recursion keeps each component ~ N(0, (f sigma)^2 / 2), so
    the sample RMS of the magnitude is f sigma; the saturation bound is not scaled."""
    f, sigma = 0.4, 2.0
    model = DrydenTurbulence(sigma=sigma, gust_scale=f, saturation=sigma)
    assert model.component_sigma == pytest.approx(f * sigma / math.sqrt(2.0))
    g = model.sample(400, 500, 0.5, np.random.default_rng(3))
    rms = math.sqrt(float(np.mean(np.sum(g**2, axis=-1))))
    # 200 000 correlated draws (correlation time 13 s, dt 0.5 s): effective ~7 700 samples,
    # relative standard error of the RMS about 1 %; saturation at 2.5 RMS removes < 0.1 %
    assert rms == pytest.approx(f * sigma, rel=0.05)
    literal = DrydenTurbulence(sigma=sigma, saturation=sigma).sample(400, 500, 0.5, 3)
    mag = np.hypot(literal[..., 0], literal[..., 1])
    assert mag.max() <= sigma * (1 + 1e-12)  # saturated at the unscaled bound


@pytest.mark.parametrize("bad", [0.0, -0.3, math.nan, math.inf])
def test_gust_scale_must_be_positive_and_finite(bad):
    with pytest.raises(InvalidParameterError, match="gust_scale"):
        DrydenTurbulence(sigma=1.0, gust_scale=bad)
    with pytest.raises(InvalidParameterError, match="gust_scale"):
        CrossTrackConfig(gust_scale=bad)


def test_default_gust_scale_keeps_old_results_files_valid():
    """A default study stores no gust_scale key, so files written before the option resume."""
    assert "gust_scale" not in CrossTrackConfig().to_dict()
    assert CrossTrackConfig(gust_scale=0.4).to_dict()["gust_scale"] == 0.4


def test_weaker_gusts_give_smaller_errors(tmp_path):
    """Common random numbers: same goals and gust shapes, only the RMS differs."""
    common = {"eps": (0.95,), "r_plan": (1.0,), "samples": 12, "chunk": 12,
              "cases": ("unsteady",), "seed": 2}  # fmt: skip
    full = run_cross_track_study(tmp_path / "f1", CrossTrackConfig(**common), processes=1,
                                 progress=False)  # fmt: skip
    weak = run_cross_track_study(tmp_path / "f03", CrossTrackConfig(**common, gust_scale=0.3),
                                 processes=1, progress=False)  # fmt: skip
    assert weak.summary[0]["mean_error"] < full.summary[0]["mean_error"]


def test_time_step_rule():
    """dt <= 0.1 / u_max: with u_max = 0.3 rad/s the limit is 1/3 s."""
    assert MAX_DT_FRACTION / 0.3 == pytest.approx(1 / 3)
    CrossTrackConfig(follower={"dt": 0.3})
    with pytest.raises(InvalidParameterError, match="dt"):
        CrossTrackConfig(follower={"dt": 0.34})


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--dt", "100"], "turn one radian"),
        (["--dt", "0.5", "--u-max", "0.3"], "--dt=0.5"),
        (["--gust-scale", "0"], "--gust-scale=0.0"),
        (["--umax", "1"], "--u-max"),
    ],
)
def test_cli_refusals(cli_error, tmp_path, args, needle):
    line = cli_error("study", "cross-track", "--out", str(tmp_path / "x"), *args)
    assert needle in line


def test_cli_table_heads_with_the_radii_simulated(run_cli, tmp_path):
    code, out, err = run_cli(
        "study", "cross-track", "--out", str(tmp_path / "t"), "--eps", "0.5", "--r-plan",
        "1.5,2.2,3", "--samples", "3", "--chunk", "3", "--case", "steady", "--processes",
        "1", "--no-progress", "--gust-scale", "0.5",
    )  # fmt: skip
    assert code == 0, err
    assert "E(1.5)" in out and "E(3)" in out and "E(1)" not in out
    assert "R~R0'" in out and "sensitivity" in out


def test_help_explains_every_column_and_labels_the_sensitivity_option(run_cli):
    code, out, _ = run_cli("study", "cross-track", "--help")
    assert code == 0
    text = " ".join(out.split())
    for word in ("knee:", "failures:", "E(R):", "R~R0'", "SENSITIVITY OPTION", "--u-max"):
        assert word in text, word
