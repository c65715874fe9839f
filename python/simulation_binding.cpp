// talus.Simulation: a run (io/run/run.h) stepped from Python, with its outputs and checkpoints
// as `talus run` writes them, and the particles, grid and loads as NumPy arrays.
#include "python/bindings.h"

#include "engine/simulation.h"
#include "io/common/write_error.h"
#include "io/run/run.h"

#include <pybind11/numpy.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <csignal>

namespace py = pybind11;

namespace talus::python {

namespace {

const char* statusName(RunStatus s) {
  switch (s) {
  case RunStatus::Completed: return "completed";
  case RunStatus::NumericalFailure: return "numerical failure";
  case RunStatus::WriteFailure: return "write failure";
  case RunStatus::Interrupted: return "interrupted";
  }
  return "?";
}

/// A Simulation from Python: the Run and the names Python looks materials up by.
class PySimulation {
public:
  PySimulation(Scene& scene, const std::string& out, int threads, bool resume) {
    scene.get(); // a spent scene raises ValueError here
    RunOptions o;
    o.outDir = out;
    o.threads = threads;
    o.resume = resume;
    o.progress = false; // Python shows its own (talus.Simulation.run)
    std::unique_ptr<SceneSetup> taken = std::move(scene.setup);
    origin_ = taken->settings.origin;
    {
      py::gil_scoped_release nogil;
      run_ = std::make_unique<Run>(std::move(*taken), o);
    }
    raiseFailure(); // an output folder that cannot be written
  }

  /// One step (the GIL released); raises the run's failure once, when it ends with one.
  bool step() {
    bool more;
    {
      py::gil_scoped_release nogil;
      more = run_->step();
    }
    if (!more) raiseFailure();
    return more;
  }

  /// Steps to time t without returning to Python in between (Run::advanceTo, the GIL released);
  /// Ctrl-C is looked at after each step and ends the run with a checkpoint (then
  /// KeyboardInterrupt).
  bool advanceTo(double t) {
    bool interrupted = false;
    {
      py::gil_scoped_release nogil;
      run_->advanceTo(t, [&] {
        {
          py::gil_scoped_acquire gil; // Python only flagged the signal; it raises here
          interrupted = PyErr_CheckSignals() != 0;
        }
        if (interrupted) run_->interrupt(SIGINT);
      });
    }
    if (interrupted) throw py::error_already_set();
    raiseFailure();
    return !run_->ended();
  }

  void raiseFailure() {
    const RunResult& r = run_->result();
    if (reported_ || r.status == RunStatus::Completed || r.status == RunStatus::Interrupted) return;
    reported_ = true;
    if (r.status == RunStatus::NumericalFailure) throw NumericalError(r.error);
    PyErr_SetString(py::module_::import("talus._talus").attr("WriteError").ptr(), r.error.c_str());
    throw py::error_already_set();
  }

  py::dict result() const {
    const RunResult& r = run_->result();
    py::dict d;
    d["out_dir"] = r.outDir, d["status"] = statusName(r.status), d["ok"] = r.ok, d["error"] = r.error;
    d["steps"] = r.steps, d["time"] = r.time, d["wall_seconds"] = r.wallSeconds;
    d["checkpoint_time"] = r.checkpointTime, d["files"] = r.files;
    return d;
  }

  const MaterialGroup& group(const std::string& name) const {
    for (const MaterialGroup* g : run_->simulation().groups())
      if (g->name() == name) return *g;
    throw py::key_error("no material '" + name + "' in this scene");
  }

  Run& run() { return *run_; }
  const Simulation& sim() const { return run_->simulation(); }
  const Vec3d& origin() const { return origin_; }

private:
  std::unique_ptr<Run> run_;
  Vec3d origin_;
  bool reported_ = false;
};

/// A read-only NumPy view of `data` kept alive by `owner` (the Python Simulation).
template <class T>
py::array view(const T* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, py::handle owner) {
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// The particles of one material: views of the engine's arrays, positions in world coordinates.
py::dict particlesOf(const PySimulation& s, const std::string& name, py::handle owner) {
  const MaterialGroup& g = s.group(name);
  const ParticleSet& P = g.particles;
  const py::ssize_t n = py::ssize_t(P.size()), r = sizeof(Real);
  py::dict d;
  // World positions need the origin added in double (x ~ 2.6e6 m in national grids): a copy.
  py::array_t<double> x({n, py::ssize_t(3)});
  auto xm = x.mutable_unchecked<2>();
  for (py::ssize_t p = 0; p < n; ++p)
    for (int a = 0; a < 3; ++a) xm(p, a) = double(P.x[p][a]) + s.origin()[a];
  d["position"] = x;
  d["position_local"] = view(P.x.empty() ? nullptr : P.x[0].data(), {n, 3}, {3 * r, r}, owner);
  d["velocity"] = view(P.v.empty() ? nullptr : P.v[0].data(), {n, 3}, {3 * r, r}, owner);
  d["mass"] = view(P.mass.data(), {n}, {r}, owner);
  // Eigen's 3x3 is column-major: C[p, i, j] is at 9p + 3j + i.
  d["affine"] = view(P.C.empty() ? nullptr : P.C[0].data(), {n, 3, 3}, {9 * r, r, 3 * r}, owner);
  d["kirchhoff_stress"] = view(P.tau.empty() ? nullptr : &P.tau[0].xx, {n, 6}, {6 * r, r}, owner);
  py::dict scalars;
  std::vector<float> values;
  for (const auto& k : g.scalarNames()) {
    g.scalar(k, values);
    scalars[py::str(k)] = py::array_t<float>(py::ssize_t(values.size()), values.data());
  }
  d["state"] = scalars;
  d["density"] = g.density(); // reference density: a particle's volume at rest is mass / density
  return d;
}

/// The grid's active blocks as left by the last step: node mass and velocity (after the grid
/// update) per block of 8x8x8 nodes, and each block's first node in world coordinates.
py::dict gridOf(const PySimulation& s, py::handle owner) {
  const SparseGrid& g = s.sim().grid();
  const py::ssize_t nb = py::ssize_t(g.blockCount()), v = sizeof(Vec4), r = sizeof(Real);
  py::array_t<double> corner({nb, py::ssize_t(3)});
  auto cm = corner.mutable_unchecked<2>();
  for (py::ssize_t b = 0; b < nb; ++b) {
    const BlockCoord& c = g.topology.coord(uint32_t(b));
    const int k[3] = {c.x, c.y, c.z};
    for (int a = 0; a < 3; ++a) cm(b, a) = double(k[a] * kBlockDim) * double(g.dx) + s.origin()[a];
  }
  const Real* base = g.nodes.empty() ? nullptr : g.nodes[0].data();
  const std::vector<py::ssize_t> strides{kBlockNodes * v, 64 * v, 8 * v, v};
  py::dict d;
  d["dx"] = double(g.dx);
  d["block_origin"] = corner;
  d["mass"] = view(base, {nb, 8, 8, 8}, strides, owner);
  auto vs = strides;
  vs.push_back(r);
  d["velocity"] = view(base ? base + 1 : nullptr, {nb, 8, 8, 8, 3}, vs, owner);
  return d;
}

py::list loadsOf(const PySimulation& s) {
  py::list out;
  const auto& cols = s.sim().colliders();
  const auto& loads = s.sim().colliderLoads();
  for (size_t i = 0; i < cols.size() && i < loads.size(); ++i) {
    py::dict d;
    d["name"] = cols[i]->name();
    d["force"] = std::vector<double>(loads[i].force.data(), loads[i].force.data() + 3);
    d["moment"] = std::vector<double>(loads[i].moment.data(), loads[i].moment.data() + 3);
    out.append(d);
  }
  return out;
}

} // namespace

void registerSimulation(py::module_& m) {
  py::class_<PySimulation>(m, "_Simulation")
      .def(py::init<Scene&, const std::string&, int, bool>(), py::arg("scene"), py::arg("out") = "",
           py::arg("threads") = 0, py::arg("resume") = false)
      .def("step", &PySimulation::step)
      .def("advance_to", &PySimulation::advanceTo, py::arg("time"))
      .def("interrupt", [](PySimulation& s) { s.run().interrupt(0); })
      .def("checkpoint", [](PySimulation& s) {
        s.run().checkpoint();
        s.raiseFailure();
      })
      .def_property_readonly("time", [](const PySimulation& s) { return s.sim().time(); })
      .def_property_readonly("steps", [](const PySimulation& s) { return s.sim().steps(); })
      .def_property_readonly("end_time", [](PySimulation& s) { return s.run().endTime(); })
      .def_property_readonly("ended", [](PySimulation& s) { return s.run().ended(); })
      .def_property_readonly("result", &PySimulation::result)
      .def_property_readonly("materials",
                             [](const PySimulation& s) {
                               std::vector<std::string> n;
                               for (const auto* g : s.sim().groups()) n.push_back(g->name());
                               return n;
                             })
      .def_property_readonly("origin", [](const PySimulation& s) { return s.origin(); })
      .def_property_readonly("particle_count", [](const PySimulation& s) { return s.sim().particleCount(); })
      .def_property_readonly("particle_steps", [](const PySimulation& s) { return s.sim().particleSteps(); })
      .def("particles", [](py::object self, const std::string& name) { return particlesOf(self.cast<const PySimulation&>(), name, self); })
      .def("grid", [](py::object self) { return gridOf(self.cast<const PySimulation&>(), self); })
      .def("loads", &loadsOf)
      .def("kinetic_energy", [](const PySimulation& s) { return s.sim().kineticEnergy(); })
      .def("total_mass", [](const PySimulation& s) { return s.sim().totalMass(); });
}

} // namespace talus::python
