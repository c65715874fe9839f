"""Bad input raises talus.InputError with the line the talus program prints, and its place."""
import tomllib

import pytest

import talus


def test_a_dict_scene_is_the_toml_scene_and_a_misspelt_key_is_named_with_its_path():
    scene = tomllib.loads(talus.Scene.default_text())
    assert talus.Scene.from_dict(scene).hash == talus.Scene.default().hash
    scene["simulation"]["end_tme"] = 2.0
    with pytest.raises(talus.InputError) as e:
        talus.Scene.from_dict(scene)
    assert isinstance(e.value, ValueError)
    assert e.value.file == "<dict>" and e.value.key == "simulation.end_tme"
    assert "end_time" in str(e.value)  # the closest valid name


def test_a_value_python_cannot_give_a_scene_is_refused_by_key():
    with pytest.raises(talus.InputError, match=r"simulation\.dx.*not a scene value"):
        talus.Scene.from_dict({"simulation": {"dx": object()}})


def test_toml_text_errors_name_the_line_and_key():
    text = "[simulation]\ndx = 0.1\nend_time = -1\n"
    with pytest.raises(talus.InputError) as e:
        talus.Scene.from_text(text, name="study.toml")
    assert e.value.file == "study.toml" and e.value.line == 3 and e.value.key == "simulation.end_time"
    assert str(e.value).startswith("study.toml:3: simulation.end_time: ")


def test_a_missing_file_and_a_bad_override_are_input_errors(tmp_path):
    with pytest.raises(talus.InputError, match="scene file not found"):
        talus.Scene(tmp_path / "nowhere.toml")
    with pytest.raises(talus.InputError, match="simulation.end_time"):
        talus.Scene.default(set=["simulation.end_time=-3"])


def test_a_scene_runs_once_and_materials_are_looked_up_by_name(tmp_path):
    scene = talus.Scene.default(set=["simulation.end_time=0.01"])
    sim = talus.Simulation(scene, out=str(tmp_path))
    with pytest.raises(ValueError, match="given to a Simulation already"):
        talus.Simulation(scene, out=str(tmp_path / "again"))
    with pytest.raises(KeyError, match="no material 'granite'"):
        sim.particles("granite")


def test_resuming_without_a_checkpoint_is_an_input_error(tmp_path):
    with pytest.raises(talus.InputError, match="checkpoint"):
        talus.Simulation(talus.Scene.default(set=["simulation.end_time=0.01"]), out=str(tmp_path), resume=True)


def test_an_unwritable_output_folder_raises_write_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(talus.WriteError, match="file/out"):
        talus.Simulation(talus.Scene.default(set=["simulation.end_time=0.01"]), out=str(blocker / "out"))
