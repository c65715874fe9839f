"""Talus from Python: scenes, simulations stepped from a script, particles and grids as NumPy
arrays, and the analyses of a run's outputs (docs/python.md).

    import talus
    scene = talus.Scene("data/scenes/default.toml", set=["simulation.end_time=1"])
    sim = talus.Simulation(scene, out="out")
    sim.run(callback=lambda s: print(s.time))
    rock = sim.particles("rock")          # {'position': (N, 3) float64, 'velocity': ...}
"""

import csv
import json
import os
import shutil
import subprocess
import sys
import time as _time

from ._talus import (InputError, NumericalError, WriteError, Scene, read_map, read_series,
                     map_stats, compare, aimec)
from ._talus import _Simulation

__all__ = ["Scene", "Simulation", "InputError", "NumericalError", "WriteError", "read_map",
           "read_series", "map_stats", "compare", "aimec", "run", "check", "terrain", "ensemble", "calibrate",
           "program"]


class Simulation(_Simulation):
    """A scene's run, stepped from Python. It writes what `talus run` writes (the scene's
    [output], summary.json, particles.h5 at the end, checkpoints) into `out` (default: the scene's
    output directory).

    Simulation(scene, out="", threads=0, resume=False): resume=True continues from out's
    checkpoint (talus.InputError when it is missing or from another scene).
    """

    def run(self, until=None, callback=None, every=1, progress=None):
        """Steps to `until` (default: the end time). `callback(sim)` is called every `every`
        steps; progress (default: when stderr is a terminal or in a notebook) shows simulated
        time and speed. Ctrl-C stops after the step with a checkpoint, then raises
        KeyboardInterrupt; Simulation(scene, out, resume=True) continues. Returns self.result."""
        end = self.end_time if until is None else min(until, self.end_time)
        show = _Progress(end, self) if (progress if progress is not None else _interactive()) else None
        if callback is None and show is None:
            self.advance_to(end)
            return self.result
        try:
            while not self.ended and self.time < end:
                self.step()
                if callback is not None and self.steps % every == 0:
                    callback(self)
                if show is not None:
                    show.update()
            if not self.ended and self.time >= self.end_time:
                self.step()  # the final outputs
        except KeyboardInterrupt:
            self.interrupt()
            raise
        finally:
            if show is not None:
                show.close()
        return self.result

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def run(scene, out="", threads=0, set=None):
    """`talus run`: a scene (a Scene, a path or a dict) to its end time; returns the result."""
    if not isinstance(scene, Scene):
        scene = Scene(scene, set=set or [])
    return Simulation(scene, out=out, threads=threads).run(progress=False)


def _interactive():
    if "ipykernel" in sys.modules:
        return True
    return sys.stderr is not None and hasattr(sys.stderr, "isatty") and sys.stderr.isatty()


class _Progress:
    """One line: simulated time of the end, steps, particle-steps per second. tqdm when there."""

    def __init__(self, end, sim):
        self.end, self.sim, self.t0, self.last = end, sim, _time.monotonic(), 0.0
        self.work0 = sim.particle_steps
        try:
            from tqdm.auto import tqdm
            self.bar = tqdm(total=end, unit="s sim", bar_format="{l_bar}{bar}| {n:.3g}/{total:.3g} s [{elapsed}<{remaining}]")
        except ImportError:
            self.bar = None

    def update(self):
        now = _time.monotonic()
        if now - self.last < 0.2:
            return
        self.last = now
        if self.bar is not None:
            self.bar.update(self.sim.time - self.bar.n)
            return
        rate = (self.sim.particle_steps - self.work0) / max(now - self.t0, 1e-9)
        sys.stderr.write("\rtalus: t = %.4g / %.4g s, step %d, %.3g particle-steps/s " % (
            self.sim.time, self.end, self.sim.steps, rate))
        sys.stderr.flush()

    def close(self):
        if self.bar is not None:
            self.bar.update(self.sim.time - self.bar.n)
            self.bar.close()
        else:
            sys.stderr.write("\n")


def check(scene, set=None):
    """`talus check`: builds the scene (a path, a dict or TOML text via Scene.from_text) and
    returns what it seeds: {'materials', 'particles', 'bodies' [{label, material, kind,
    particles, seeded_volume, geometric_volume, mean_thickness}], 'notes', 'dx', 'end_time'}."""
    s = scene if isinstance(scene, Scene) else Scene(scene, set=set or [])
    return {"materials": s.materials, "particles": s.particle_count, "bodies": s.bodies,
            "notes": s.notes, "dx": s.dx, "end_time": s.end_time}


def program():
    """The talus program that terrain() and ensemble() start: $TALUS_EXE, else the build tree's
    (this package in build/python), else `talus` on the PATH."""
    exe = os.environ.get("TALUS_EXE")
    if exe:
        return exe
    here = os.path.dirname(os.path.abspath(__file__))
    built = os.path.join(here, "..", "..", "tools", "talus")
    if os.access(built, os.X_OK):
        return os.path.normpath(built)
    found = shutil.which("talus")
    if found:
        return found
    raise FileNotFoundError("the talus program was not found: set TALUS_EXE or put talus on the PATH")


def _command(args):
    """Runs `talus ARGS`; its one-line error becomes InputError (exit 2) or RuntimeError."""
    p = subprocess.run([program()] + [str(a) for a in args], capture_output=True, text=True)
    if p.returncode != 0:
        line = next((l for l in p.stderr.splitlines() if "error" in l), p.stderr.strip())
        line = line.replace("talus: error: ", "")
        raise (InputError if p.returncode == 2 else RuntimeError)(line)
    return p


def terrain(dem, out, dx=None, smooth=None, bounds=None, origin=None, band=None, fill_nodata=False, crs=None):
    """`talus terrain`: a DEM's narrow-band level set (.vdb) for [terrain] sdf = OUT. Returns out."""
    args = ["terrain", dem, "--out", out]
    for flag, value in [("--dx", dx), ("--smooth", smooth), ("--band", band), ("--crs", crs)]:
        if value is not None:
            args += [flag, value]
    if bounds is not None:
        args += ["--bounds"] + list(bounds)
    if origin is not None:
        args += ["--origin"] + list(origin)
    if fill_nodata:
        args.append("--fill-nodata")
    _command(args)
    return out


def ensemble(scene, vary, samples, out="ensemble", method="lhs", seed=None, threads=1, jobs=None, set=None):
    """`talus ensemble`: members of a scene file over varied keys (vary: {key: (low, high)}),
    in parallel and resumable (a second call continues). Returns {'out', 'members': rows of
    members.csv as dicts, 'files'}; the probability and quantile maps are in out/maps."""
    args = ["ensemble", scene, "--samples", samples, "--method", method, "--out", out, "--threads", threads]
    for key, (low, high) in vary.items():
        args += ["--vary", f"{key}={low}:{high}"]
    for flag, value in [("--seed", seed), ("--jobs", jobs)]:
        if value is not None:
            args += [flag, value]
    for s in set or []:
        args += ["--set", s]
    _command(args)
    with open(os.path.join(out, "members.csv"), newline="") as f:
        members = list(csv.DictReader(f))
    files = sorted(os.path.relpath(os.path.join(d, n), out) for d, _, ns in os.walk(out) for n in ns
                   if not os.path.relpath(d, out).startswith("member_"))
    return {"out": out, "members": members, "files": files}


def calibrate(scene, vary, observed, out="calibration", budget=20, weight=None, raster_result=None, screen=None,
              tolerance=None, seed=None, threads=1, jobs=None, set=None):
    """`talus calibrate`: the parameters (vary: {key: (low, high)}) whose run best matches an
    observed event (observed: ["footprint=FILE", "runout=X,Y", "raster=FILE"]), by Morris
    screening and a Gaussian-process search; resumable (a second call continues). Returns
    result.json as a dict with 'out', 'members' (rows of calibration.csv as dicts) and
    'calibrated_scene' (the scene file with the values written in, out/calibrated.toml)."""
    args = ["calibrate", scene, "--out", out, "--budget", budget, "--threads", threads]
    for key, (low, high) in vary.items():
        args += ["--vary", f"{key}={low}:{high}"]
    for o in observed:
        args += ["--observed", o]
    for kind, w in (weight or {}).items():
        args += ["--weight", f"{kind}={w}"]
    for flag, value in [("--raster-result", raster_result), ("--screen", screen), ("--tolerance", tolerance),
                        ("--seed", seed), ("--jobs", jobs)]:
        if value is not None:
            args += [flag, value]
    for s in set or []:
        args += ["--set", s]
    _command(args)
    with open(os.path.join(out, "result.json")) as f:
        result = json.load(f)
    with open(os.path.join(out, "calibration.csv"), newline="") as f:
        result["members"] = list(csv.DictReader(f))
    result["out"] = out
    result["calibrated_scene"] = os.path.join(out, "calibrated.toml")
    return result

