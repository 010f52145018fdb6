"""A GRIB file mixing the currents with messages cfgrib cannot combine (issue 26): no cfgrib
traceback on stderr, and one warning naming the file and the skipped variable.

Input built here: 10u/10v at steps 0, 1, 2 h (`write_grib`) plus 2t messages at steps 0, 1
and 0 again, which cfgrib cannot put in one hypercube ("skipping variable: paramId==167",
logged with a traceback).
"""

from __future__ import annotations

import json

import numpy as np
import pytest


def _mixed(path):
    pytest.importorskip("cfgrib")
    from glideplan.fields.synthetic import _pyproj_before_eccodes, write_grib

    lat, lon = np.linspace(44.0, 45.0, 5), np.linspace(-9.0, -8.0, 5)
    times = np.datetime64("2026-03-01T00:00") + np.arange(3) * np.timedelta64(3600, "s")
    u = np.full((3, 5, 5), 1.0)
    write_grib(path, lat, lon, times, u, 0.0 * u)
    _pyproj_before_eccodes()
    import eccodes

    with path.open("ab") as fh:
        for step in (0, 1, 0):
            h = eccodes.codes_grib_new_from_samples("regular_ll_sfc_grib2")
            eccodes.codes_set_key_vals(h, {
                "Ni": 5, "Nj": 5, "latitudeOfFirstGridPointInDegrees": 45.0,
                "latitudeOfLastGridPointInDegrees": 44.0,
                "longitudeOfFirstGridPointInDegrees": 351.0,
                "longitudeOfLastGridPointInDegrees": 352.0,
                "iDirectionIncrementInDegrees": 0.25, "jDirectionIncrementInDegrees": 0.25,
                "jScansPositively": 0, "dataDate": 20260301, "dataTime": 0, "stepUnits": 1,
                "forecastTime": step})
            eccodes.codes_set_string(h, "shortName", "2t")
            eccodes.codes_set_values(h, np.full(25, 280.0))
            eccodes.codes_write(h, fh)
            eccodes.codes_release(h)
    return path


def test_mixed_grib_warns_once_without_a_traceback(tmp_path, run_cli):
    path = _mixed(tmp_path / "mixed.grib")
    code, out, err = run_cli("route", "--field", str(path), "--from", "44.5", "-8.9", "--to",
                             "44.5", "-8.85", "--speed", "0.5", "--json")
    assert code == 0, err
    assert "Traceback" not in err and "skipping variable" not in err
    data = json.loads(out)
    notes = [w for w in data["field"]["warnings"] if "cfgrib skipped" in w]
    assert len(notes) == 1 and str(path) in notes[0] and "t2m (paramId 167)" in notes[0]
    assert data["status"] == "solved"
