// The parts of the talus Python module, each registered by its own function (module.cpp calls
// them in order): the exceptions, scenes, the simulation, the analyses of outputs.
#pragma once

#include "io/scene/scene.h"

#include <pybind11/pybind11.h>

#include <memory>

namespace talus::python {

/// A scene built and not yet run: a Simulation takes its particles (then it is spent).
struct Scene {
  std::unique_ptr<SceneSetup> setup;
  SceneSetup& get() const; ///< throws ValueError when spent
};

void registerExceptions(pybind11::module_& m);
void registerScene(pybind11::module_& m);
void registerSimulation(pybind11::module_& m);
void registerAnalysis(pybind11::module_& m);

} // namespace talus::python
