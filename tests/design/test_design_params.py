"""TOML parameter sets: round trip, edge units, and errors that name the field."""

import pytest

from glideplan.design import (
    FX23DV,
    DesignParameters,
    Tank,
    dumps_parameters,
    load_parameters,
    loads_parameters,
    save_parameters,
)
from glideplan.errors import InvalidParameterError


def test_default_round_trip_through_file(tmp_path):
    p = DesignParameters(tank=Tank(name="big", max_pressure_pa=3e7, internal_volume_m3=0.01))
    path = save_parameters(p, tmp_path / "glider.toml")
    assert load_parameters(path) == p
    assert loads_parameters(dumps_parameters(DesignParameters())) == DesignParameters()


def test_edge_units_are_converted():
    # 3442 psi -> 23,731,755 Pa (as FX23DV); 4 L -> 0.004 m^3; 9 in -> 0.2286 m; 20 degC -> 293.15 K
    p = loads_parameters(
        """
        [tank]
        max_pressure_psi = 3442
        internal_volume_in3 = 183
        [bladder]
        max_volume_l = 4
        neutral_volume_l = 2
        [hull]
        diameter_in = 9
        [environment]
        temperature_degc = 20
        """
    )
    assert p.tank.max_pressure_pa == pytest.approx(FX23DV.max_pressure_pa)
    assert p.tank.internal_volume_m3 == pytest.approx(FX23DV.internal_volume_m3)
    assert p.bladder.max_volume_m3 == pytest.approx(0.004)
    assert p.hull.diameter_m == pytest.approx(0.2286)
    assert p.environment.temperature_k == pytest.approx(293.15)
    # sections not given keep their defaults
    assert p.glide == DesignParameters().glide


@pytest.mark.parametrize(
    ("text", "name"),
    [
        ("[tank]\nmax_pressure_pa = -1.0\n", "tank.max_pressure_pa"),
        ("[bladder]\nmax_volume_l = -5\n", "bladder.max_volume_m3"),
        ("[tank]\nvolume = 3\n", "tank.volume"),
        ("[tank]\nmax_pressure_pa = 1e7\nmax_pressure_psi = 3000\n", "tank.max_pressure_psi"),
        ("[engine]\nx = 1\n", "engine"),
        ("[hull]\ndiameter_m = 'wide'\n", "hull.diameter_m"),
        ("[hull]\ndiameter_in = 'wide'\n", "hull.diameter_in"),
        ("[lbl]\nbeacons_m = [[0, 0], [10, 0]]\n", "lbl.beacons_m"),
        ("[lbl]\nbeacons_m = [[0, 0], [10, 0], [20, 0]]\n", "lbl.beacons_m"),
        ("tank = 3\n", "tank"),
    ],
)
def test_bad_values_name_the_field(text, name):
    with pytest.raises(InvalidParameterError) as err:
        loads_parameters(text)
    assert err.value.name == name
    assert str(err.value).startswith(name)


def test_malformed_toml_names_the_file(tmp_path):
    bad = tmp_path / "broken.toml"
    bad.write_text("[tank\nmax_pressure_pa = 1\n")
    with pytest.raises(InvalidParameterError) as err:
        load_parameters(bad)
    assert str(bad) in str(err.value) and "not valid TOML" in str(err.value)


def test_missing_file_is_a_clear_error(tmp_path):
    with pytest.raises(InvalidParameterError) as err:
        load_parameters(tmp_path / "nope.toml")
    assert err.value.name == "params"


def test_section_type_checked():
    with pytest.raises(InvalidParameterError) as err:
        DesignParameters(tank="FX23DV")  # type: ignore[arg-type]
    assert err.value.name == "tank"
