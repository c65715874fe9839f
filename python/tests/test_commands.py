"""check, terrain and ensemble as functions returning Python objects."""
import os
import subprocess

import pytest

import talus

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_check_reports_what_each_body_seeds():
    c = talus.check(talus.Scene.default())
    assert c["materials"] == ["rock", "snow"]
    assert sum(b["particles"] for b in c["bodies"]) == c["particles"] > 0
    # Each particle stands for dx^3 / particles_per_cell of its body's volume.
    for b in c["bodies"]:
        assert b["seeded_volume"] == pytest.approx(b["particles"] * c["dx"] ** 3 / 8, rel=1e-9)


def test_terrain_builds_a_level_set_a_scene_reads(tmp_path, talus_exe):
    dem = tmp_path / "valley.tif"
    subprocess.run([talus_exe, "synth-dem", "slope_valley", "--out", str(dem), "--cell", "20"], check=True,
                   capture_output=True)
    out = talus.terrain(str(dem), str(tmp_path / "valley.vdb"), dx=20.0)
    assert os.path.getsize(out) > 1000
    with pytest.raises(talus.InputError, match="nowhere.tif"):
        talus.terrain(str(tmp_path / "nowhere.tif"), str(tmp_path / "x.vdb"))


def test_an_ensemble_returns_its_members(tmp_path, talus_exe):
    scene = os.path.join(ROOT, "data", "scenes", "default.toml")
    e = talus.ensemble(scene, {"terrain.friction": (0.3, 0.5)}, samples=2, out=str(tmp_path / "ens"),
                       set=["simulation.end_time=1"], jobs=2)
    assert len(e["members"]) == 2
    assert "members.csv" in e["files"]
    assert any(f.startswith("maps/") for f in e["files"])


def test_a_calibration_recovers_the_friction_of_a_synthetic_event(tmp_path, talus_exe):
    # A 3 m slab on the synthetic slope at friction 0.3 (dx 10 m, a fraction of a second a run) is
    # the event: its run-out point; the calibration over 0.15-0.5 must find it within 0.03.
    scene = tmp_path / "slab.toml"
    scene.write_text("""[simulation]
dx = 10.0
end_time = 20.0
[terrain]
synthetic = { kind = "slope_valley", cell_size = 20.0 }
friction = 0.3
[domain]
walls = "open"
[[materials]]
name = "snow"
preset = "snow"
[[bodies]]
name = "slab"
kind = "release"
material = "snow"
bounds = [2600250.0, 1200350.0, 2600400.0, 1200450.0]
thickness = 3.0
[output]
maps = true
plots = false
[ensemble]
runout_result = "pft"
runout_threshold = 0.1
path = [[2600100.0, 1200400.0], [2601300.0, 1200400.0]]
""")
    truth = talus.run(str(scene), out=str(tmp_path / "truth"), set=["output.peak_files=true"])
    pft = [f for f in os.listdir(tmp_path / "truth" / "peakFiles") if f.endswith("_pft.tif") or f.endswith("_pft.asc")]
    assert pft
    r = talus.calibrate(str(scene), {"terrain.friction": (0.15, 0.5)},
                        [f"raster={tmp_path / 'truth' / 'peakFiles' / pft[0]}"], raster_result="pft",
                        out=str(tmp_path / "cal"), budget=10, jobs=2)
    (p,) = r["parameters"]
    assert p["key"] == "terrain.friction"
    assert p["value"] == pytest.approx(0.3, abs=0.03)
    assert p["plausible_low"] <= 0.3 <= p["plausible_high"]
    assert len(r["members"]) == 10
    assert os.path.exists(r["calibrated_scene"])

