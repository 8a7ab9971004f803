// --camera FILE: a camera (and optionally the sun) as JSON, for a mask another renderer drew
// from a camera of its own (`shadowkit score`). Read: what `shadowkit setup` prints (its
// "inputs": "camera" and "light"), an object with "camera" (and "light"), or the camera object
// itself — "eye", "direction", "up", "fov_y_degrees", "near", "far", and optionally "aspect",
// "width" and "height" — in world metres and degrees.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/light.h"
#include "shadowkit/core/result.h"

#include <optional>
#include <string>

namespace shadowkit::app {

struct CameraFile {
    core::PerspectiveCamera camera; // aspect 0 where the file gives none
    std::optional<core::DirectionalLight> light;
    std::optional<int> width, height; // the image's, where the file gives them
};

// Errors of one line name --camera, the file and the field.
core::Result<CameraFile> loadCameraFile(const std::string& file);

} // namespace shadowkit::app
