"""talus.Simulation against `talus run`, and what its arrays are."""
import filecmp
import os
import signal
import subprocess
import threading

import numpy as np
import pytest

import talus

# Four steps of the default scene: enough for the particles to move, binning to reorder them and
# a checkpoint (every end_time / 10) to be written.
SHORT = ["simulation.end_time=0.05"]


def test_a_run_from_python_writes_the_files_talus_run_writes_byte_for_byte(tmp_path, talus_exe):
    subprocess.run([talus_exe, "run", "--out", str(tmp_path / "cli"), "--threads", "2"] +
                   sum((["--set", s] for s in SHORT), []), check=True, capture_output=True)
    sim = talus.Simulation(talus.Scene.default(set=SHORT), out=str(tmp_path / "py"), threads=2)
    result = sim.run(progress=False)
    assert result["status"] == "completed" and result["ok"]
    for f in ["particles.h5", "series.csv", "maps/max_speed.tif", "maps/max_flow_height_vertical.tif"]:
        assert filecmp.cmp(tmp_path / "cli" / f, tmp_path / "py" / f, shallow=False), f


def test_the_particle_arrays_are_the_particles_talus_run_writes(tmp_path, talus_exe):
    h5py = pytest.importorskip("h5py")
    sim = talus.Simulation(talus.Scene.default(set=SHORT), out=str(tmp_path))
    sim.run(progress=False)
    with h5py.File(tmp_path / "particles.h5", "r") as f:
        names = [n.decode() if isinstance(n, bytes) else n for n in f.attrs["material_names"]]
        material = f["particles/material"][:]
        for i, name in enumerate(names):
            p = sim.particles(name)
            rows = material == i
            # Bit for bit: the file is written from the same arrays in the same order.
            np.testing.assert_array_equal(p["position"], f["particles/position"][rows])
            np.testing.assert_array_equal(p["velocity"], f["particles/velocity"][rows])
            np.testing.assert_array_equal(p["mass"], f["particles/mass"][rows])


def test_arrays_have_the_documented_shapes_units_and_dtypes(tmp_path):
    scene = talus.Scene.default(set=SHORT)
    origin = scene.origin
    sim = talus.Simulation(scene, out=str(tmp_path))
    assert scene.spent
    sim.step()
    total = 0.0
    for name in sim.materials:
        p = sim.particles(name)
        n = len(p["mass"])
        assert p["position"].shape == (n, 3) and p["position"].dtype == np.float64
        for key, shape in [("position_local", (n, 3)), ("velocity", (n, 3)), ("affine", (n, 3, 3)),
                           ("kirchhoff_stress", (n, 6))]:
            assert p[key].shape == shape and p[key].dtype == np.float32, key
            assert not p[key].flags.writeable, key
        # World = local + origin, in double (national grids: x ~ 2.6e6 m).
        np.testing.assert_allclose(p["position"], p["position_local"].astype(np.float64) + origin, rtol=0, atol=1e-9)
        # Views, not copies: a second call reads the same memory.
        assert np.shares_memory(p["velocity"], sim.particles(name)["velocity"])
        for k, v in p["state"].items():
            assert v.shape == (n,), k
        total += float(p["mass"].astype(np.float64).sum())
    assert total == pytest.approx(sim.total_mass(), rel=1e-6)
    g = sim.grid()
    nb = len(g["block_origin"])
    assert g["mass"].shape == (nb, 8, 8, 8) and g["velocity"].shape == (nb, 8, 8, 8, 3)
    # The grid holds the step's mass: the particles' to float rounding.
    assert float(g["mass"].astype(np.float64).sum()) == pytest.approx(total, rel=1e-5)
    loads = sim.loads()
    assert loads[0]["name"] == "terrain" and len(loads[0]["force"]) == 3


def test_a_run_interrupted_from_python_resumes_to_the_same_end(tmp_path):
    straight = talus.Simulation(talus.Scene.default(set=["simulation.end_time=0.1"]), out=str(tmp_path / "straight"))
    straight.run(progress=False)

    def stop_at_five(sim):
        if sim.steps == 5:
            raise KeyboardInterrupt  # as Ctrl-C in a notebook

    sim = talus.Simulation(talus.Scene.default(set=["simulation.end_time=0.1"]), out=str(tmp_path / "cut"))
    with pytest.raises(KeyboardInterrupt):
        sim.run(callback=stop_at_five, progress=False)
    assert sim.ended and sim.result["status"] == "interrupted"
    assert sim.result["checkpoint_time"] == sim.time > 0
    assert not (tmp_path / "cut" / "particles.h5").exists()
    again = talus.Simulation(talus.Scene.default(set=["simulation.end_time=0.1"]), out=str(tmp_path / "cut"), resume=True)
    assert again.time == sim.time
    assert again.run(progress=False)["ok"]
    for f in ["particles.h5", "series.csv", "maps/max_speed.tif"]:
        assert filecmp.cmp(tmp_path / "straight" / f, tmp_path / "cut" / f, shallow=False), f


def test_run_until_stops_there_and_continues(tmp_path):
    sim = talus.Simulation(talus.Scene.default(set=SHORT), out=str(tmp_path))
    seen = []
    sim.run(until=0.02, callback=lambda s: seen.append(s.time), progress=False)
    assert not sim.ended and sim.time >= 0.02 and seen == sorted(seen) and len(seen) == sim.steps
    sim.run(progress=False)
    assert sim.ended and sim.time == pytest.approx(0.05, abs=1e-12)
    assert not sim.step()  # after the end: nothing more


def test_a_real_sigint_while_stepping_in_cpp_stops_after_the_step_with_a_checkpoint(tmp_path):
    scene = ["simulation.end_time=40"]
    sim = talus.Simulation(talus.Scene.default(set=scene), out=str(tmp_path))
    # Ctrl-C arrives while advance_to steps with the GIL released: Python only flags it, and the
    # module looks at the flag after each step.
    threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    with pytest.raises(KeyboardInterrupt):
        sim.run(progress=False)
    assert sim.result["status"] == "interrupted" and 0 < sim.time < 40
    assert (tmp_path / "checkpoint.h5").exists() and sim.result["checkpoint_time"] == sim.time
    again = talus.Simulation(talus.Scene.default(set=scene), out=str(tmp_path), resume=True)
    assert again.time == sim.time and again.steps == sim.steps
