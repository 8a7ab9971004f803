// The Python module's pieces (module.cpp binds them): set-ups without GL, evaluation with it.
#pragma once

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shadowkit::python {

namespace py = pybind11;

// A core error as Python's ValueError, with the core's one-line message.
template <class T>
T check(core::Result<T> result) {
    if (!result) throw py::value_error(result.error());
    return std::move(result).value();
}

py::array_t<double> toNumpy(const core::Mat4& m);
core::Mat4 toMat4(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const char* name);
core::Vec3 toVec3(const std::vector<double>& v, const char* name);

// shadowkit.setup's keyword arguments (module.cpp documents each).
struct SetupArguments {
    std::vector<double> eye{0.0, 1.8, 0.0}, direction{0.0, 0.0, -1.0}, up{0.0, 1.0, 0.0};
    double fovYDegrees = 60.0, aspect = 16.0 / 9.0, zNear = 0.5, zFar = 500.0;
    std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> viewFromWorld, clipFromView;
    std::string clipDepth = "zero_to_one";
    bool leftHanded = false;
    std::optional<double> shadowDistance;
    std::optional<std::vector<double>> light;
    std::pair<double, double> sun{45.0, 90.0};
    std::vector<double> sceneMin{-512.0, 0.0, -512.0}, sceneMax{512.0, 30.0, 512.0};
    // The libraries' defaults, as the command line's.
    std::string technique = std::string(core::techniqueName(core::defaultTechnique()));
    int mapSize = core::ShadowSetupInputs{}.mapSize;
    int cascades = core::CascadeOptions{}.count;
    double lambda = core::CascadeOptions{}.lambda;
    std::string cascadeWarp = "none";
    std::string conventions = "default";
    bool reversedZ = false;
    double sunAngle = 0.0; // degrees across: light_tan_half_angle for PCSS
};

py::dict setup(const SetupArguments& arguments);

// shadowkit.local_setup's: the camera, box, map size and conventions as setup's (its sun,
// technique and cascades unused), and the spot or point light.
struct LocalSetupArguments {
    SetupArguments view;
    std::string kind = "spot";
    std::vector<double> position{0.0, 3.0, 0.0}, direction{0.0, -1.0, 0.0};
    double coneDegrees = 40.0, range = 30.0, radius = 0.0;
};

py::dict localSetup(const LocalSetupArguments& arguments);

// Registers shadowkit.Evaluator and shadowkit.evaluate.
void bindEvaluation(py::module_& m);

} // namespace shadowkit::python
