"""Maps, series and statistics of a run's outputs as Python objects."""
import numpy as np
import pytest

import talus


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("run")
    talus.run(talus.Scene.default(set=["simulation.end_time=0.05"]), out=str(out))
    return out


def test_a_map_comes_with_its_georeference(run_dir):
    m = talus.read_map(run_dir / "maps" / "max_speed.tif")
    ny, nx = m["values"].shape
    x0, cell, _, y0, _, minus_cell = m["geotransform"]
    assert cell == -minus_cell == m["cell_size"] > 0
    # The default scene lies in national-grid coordinates around (2.6e6, 1.2e6).
    assert 2.5e6 < x0 < 2.7e6 and 1.1e6 < y0 < 1.3e6 and nx > 10 and ny > 10
    assert np.nanmax(m["values"]) > 0


def test_map_stats_of_a_map_agree_with_its_values(run_dir):
    m = talus.read_map(run_dir / "maps" / "max_flow_height_vertical.tif")
    s = talus.map_stats(run_dir / "maps" / "max_flow_height_vertical.tif", threshold=0.5)
    v = m["values"].astype(np.float64)
    counted = v[np.isfinite(v) & (v >= 0.5)]
    assert s["cells"] == counted.size
    assert s["area"] == pytest.approx(counted.size * m["cell_size"] ** 2)
    assert s["max"] == pytest.approx(np.nanmax(v))
    # A map against itself: the same areas, no bias.
    c = talus.compare(run_dir / "maps" / "max_flow_height_vertical.tif",
                      run_dir / "maps" / "max_flow_height_vertical.tif", threshold=0.5)
    assert c["overlap"] == pytest.approx(1.0) and c["bias"] == pytest.approx(0.0, abs=1e-9)


def test_series_columns_are_arrays_over_time(run_dir):
    s = talus.read_series(run_dir / "series.csv")
    t = s["time_s"]
    assert t[0] == 0 and np.all(np.diff(t) > 0) and t[-1] == pytest.approx(0.05)
    assert all(len(v) == len(t) for v in s.values())
