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
