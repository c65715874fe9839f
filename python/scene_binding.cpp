// talus.Scene: a scene from a TOML file, TOML text or a Python dict, read by the same reader as
// `talus run` (same keys, same one-line errors, raised as talus.InputError).
#include "python/bindings.h"

#include "io/config/toml_reader.h"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

namespace py = pybind11;

namespace talus::python {

SceneSetup& Scene::get() const {
  if (!setup) throw py::value_error("this scene was given to a Simulation already: build it again to run it again");
  return *setup;
}

namespace {

std::shared_ptr<ConfigTable> tableFromDict(const py::dict& d, const std::string& file, const std::string& path);

/// One Python value as a scene value: bool, int, float, str, list/tuple, dict (a table), or a
/// list of dicts (an array of tables, as [[materials]]). Anything else is refused by its key.
ConfigValue valueFromPython(const py::handle& o, const std::string& file, const std::string& path) {
  ConfigValue v;
  if (py::isinstance<py::bool_>(o)) {
    v.data = o.cast<bool>();
  } else if (py::isinstance<py::int_>(o)) {
    v.data = double(o.cast<long long>());
    v.isInteger = true;
  } else if (py::isinstance<py::float_>(o)) {
    v.data = o.cast<double>();
  } else if (py::isinstance<py::str>(o)) {
    v.data = o.cast<std::string>();
  } else if (py::hasattr(o, "__fspath__")) {
    v.data = py::str(o.attr("__fspath__")()).cast<std::string>();
  } else if (py::isinstance<py::dict>(o)) {
    v.data = tableFromDict(o.cast<py::dict>(), file, path);
  } else if (py::isinstance<py::list>(o) || py::isinstance<py::tuple>(o)) {
    ConfigValue::Array a;
    size_t i = 0;
    for (const auto& e : o) a.push_back(valueFromPython(e, file, path + "[" + std::to_string(i++) + "]"));
    v.data = std::move(a);
  } else if (py::hasattr(o, "tolist")) { // NumPy scalars and arrays
    return valueFromPython(o.attr("tolist")(), file, path);
  } else {
    throw InputError(file, 0, path, "a " + py::str(py::type::of(o).attr("__name__")).cast<std::string>() +
                                        " is not a scene value (bool, int, float, str, list or dict)");
  }
  return v;
}

std::shared_ptr<ConfigTable> tableFromDict(const py::dict& d, const std::string& file, const std::string& path) {
  auto t = std::make_shared<ConfigTable>(file, path, 0);
  for (const auto& [k, value] : d) {
    if (!py::isinstance<py::str>(k)) throw InputError(file, 0, path, "keys must be strings");
    const std::string key = k.cast<std::string>();
    t->set(key, valueFromPython(value, file, path.empty() ? key : path + "." + key));
  }
  return t;
}

/// Seeding and reading rasters take a while: the GIL is released meanwhile.
Scene build(const std::function<SceneSetup()>& f) {
  Scene s;
  py::gil_scoped_release nogil;
  s.setup = std::make_unique<SceneSetup>(f());
  return s;
}

using Overrides = std::vector<std::string>;

Scene fromFile(const std::filesystem::path& path, const Overrides& set) {
  return build([&] { return loadSceneFile(path.string(), set); });
}
Scene fromText(const std::string& text, const std::string& name, const Overrides& set) {
  return build([&] { return loadSceneString(text, name, set); });
}
Scene fromDict(const py::dict& d, const std::string& name, const Overrides& set) {
  auto root = tableFromDict(d, name, ""); // with the GIL: it reads Python objects
  return build([&] { return loadSceneTable(*root, set); });
}

py::list bodiesOf(const SceneSetup& s) {
  py::list out;
  for (const auto& b : s.bodies) {
    py::dict d;
    d["label"] = b.label, d["material"] = b.material, d["kind"] = b.kind, d["particles"] = b.particles;
    d["seeded_volume"] = b.seededVolume, d["geometric_volume"] = b.geometricVolume;
    d["mean_thickness"] = b.meanThickness;
    d["field_mass"] = b.fieldMass; // kg: a cover made an erodible field (no particles), else 0
    out.append(d);
  }
  return out;
}

} // namespace

void registerScene(py::module_& m) {
  const char* setDoc = "set: `--set`-style overrides, e.g. ['simulation.end_time=0.5', 'materials.snow.density=250']";
  py::class_<Scene>(m, "Scene",
                    "A scene built from a TOML file, TOML text or a dict (docs/scenes.md), ready to run.\n"
                    "Scene(source, set=None): source is a path or a dict. Bad input raises talus.InputError.\n"
                    "A Simulation takes the scene's particles: build the scene again to run it again.")
      .def(py::init([](const py::object& source, const Overrides& set) {
             if (py::isinstance<py::dict>(source)) return fromDict(source, "<dict>", set);
             return fromFile(source.cast<std::filesystem::path>(), set);
           }),
           py::arg("source"), py::arg("set") = Overrides{})
      .def_static("from_file", &fromFile, py::arg("path"), py::arg("set") = Overrides{}, setDoc)
      .def_static("from_text", &fromText, py::arg("text"), py::arg("name") = "<text>", py::arg("set") = Overrides{},
                  "A scene from TOML text; errors name `name` and the line.")
      .def_static("from_dict", &fromDict, py::arg("scene"), py::arg("name") = "<dict>", py::arg("set") = Overrides{},
                  "A scene from nested dicts and lists as the TOML file would hold them; errors name the key.")
      .def_static("default", [](const Overrides& set) { return fromText(defaultSceneText(), "<default scene>", set); },
                  py::arg("set") = Overrides{}, "The scene `talus run` runs without a file (data/scenes/default.toml).")
      .def_static("default_text", &defaultSceneText, "The default scene's TOML text (`talus run --print-default`).")
      .def_property_readonly("file", [](const Scene& s) { return s.get().file; })
      .def_property_readonly("end_time", [](const Scene& s) { return s.get().endTime; }, "s")
      .def_property_readonly("dx", [](const Scene& s) { return s.get().settings.dx; }, "grid spacing (m)")
      .def_property_readonly("origin", [](const Scene& s) { return s.get().settings.origin; },
                             "world coordinates of the local frame's origin (m)")
      .def_property_readonly("materials", [](const Scene& s) { return s.get().materialNames; })
      .def_property_readonly("particle_count", [](const Scene& s) { return s.get().seededParticles(); })
      .def_property_readonly("bodies", [](const Scene& s) { return bodiesOf(s.get()); },
                             "what each body seeded (as `talus check` prints it)")
      .def_property_readonly("notes", [](const Scene& s) { return s.get().notes; }, "the reader's notes and warnings")
      .def_property_readonly("output_directory", [](const Scene& s) { return s.get().output.directory; })
      .def_property_readonly("hash", [](const Scene& s) { return s.get().hash; },
                             "identifies the state a checkpoint of this scene holds")
      .def_property_readonly("spent", [](const Scene& s) { return !s.setup; });
}

} // namespace talus::python
