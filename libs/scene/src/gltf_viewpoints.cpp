// A glTF file's own cameras (glTF 2.0 §3.10, §5.12) and punctual lights (KHR_lights_punctual):
// the picture and the lighting its author set up. Shadows need neither — the standard views
// frame any model under their own suns — but a user who lit a scene expects to see and measure
// it as lit (`--view file`, views.h). Both are placed by their node, like a mesh: a camera looks
// along its node's −z with +y up, a directional or spot light shines along its node's −z, a point
// or spot light stands at the node's origin. A node's scale does not scale a light or a camera's
// frustum (both extensions say so): only the directions it gives, renormalised, are kept.
#include "gltf_viewpoints.h"

#include "scene_formats.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>

namespace shadowkit::scene::formats {
namespace {

// The unit image of a direction under a node's linear part, or nothing where the node squashes
// it to (almost) nothing or to a non-finite vector.
std::optional<core::Vec3> placedDirection(const glm::dmat4& fileFromNode, const core::Vec3& osDirection) {
    const core::Vec3 placed = glm::dmat3(fileFromNode) * osDirection;
    const double length = glm::length(placed);
    if (!std::isfinite(length) || !(length > 1e-12)) return std::nullopt;
    return placed / length;
}

std::string nameOf(const tinygltf::Node& node, const std::string& own) {
    return printable(node.name.empty() ? own : node.name);
}

// Where a camera's node places it and which way it looks (its −z, with its +y up), or nothing
// where the node gives it no direction.
std::optional<std::pair<core::Vec3, core::Vec3>> cameraAxes(const glm::dmat4& fileFromNode) {
    const std::optional<core::Vec3> forward = placedDirection(fileFromNode, {0.0, 0.0, -1.0});
    const std::optional<core::Vec3> up = placedDirection(fileFromNode, {0.0, 1.0, 0.0});
    if (!forward || !up || glm::length(glm::cross(*forward, *up)) < 1e-6) return std::nullopt;
    return std::pair{*forward, *up};
}

// glTF §5.13: xmag and ymag half the view's width and height (not zero; a negative one, which
// the specification advises against, mirrors the picture and is read as its magnitude), znear
// >= 0, zfar > znear, both required. The projection into `out`, or what is wrong with it.
const char* readOrthographic(const tinygltf::OrthographicCamera& o, FileCamera& out) {
    const double xmag = std::abs(o.xmag), ymag = std::abs(o.ymag);
    if (!(std::isfinite(xmag) && xmag > 0.0 && std::isfinite(ymag) && ymag > 0.0))
        return "xmag and ymag are not sizes above 0";
    if (!(std::isfinite(o.znear) && o.znear >= 0.0)) return "znear is not a distance of 0 or more";
    if (!(std::isfinite(o.zfar) && o.zfar > o.znear)) return "zfar is not beyond znear";
    out.orthographicHalfHeight = ymag;
    out.aspect = xmag / ymag;
    out.zNear = o.znear;
    out.zFar = o.zfar;
    return nullptr;
}

// glTF §5.12 (tinygltf writes 0 for an absent aspectRatio or zfar). The projection into `out`,
// or what is wrong with it.
const char* readPerspective(const tinygltf::PerspectiveCamera& p, FileCamera& out) {
    if (!(std::isfinite(p.yfov) && p.yfov > 0.0 && p.yfov < std::numbers::pi)) return "yfov is not an angle in (0, π)";
    if (!(std::isfinite(p.znear) && p.znear > 0.0)) return "znear is not a distance above 0";
    if (!(p.zfar == 0.0 || (std::isfinite(p.zfar) && p.zfar > p.znear))) return "zfar is not beyond znear";
    if (!(p.aspectRatio == 0.0 || (std::isfinite(p.aspectRatio) && p.aspectRatio > 0.0)))
        return "aspectRatio is not above 0";
    out.fovYDegrees = glm::degrees(p.yfov);
    if (p.aspectRatio > 0.0) out.aspect = p.aspectRatio;
    out.zNear = p.znear;
    if (p.zfar > 0.0) out.zFar = p.zfar;
    return nullptr;
}

void readCamera(const tinygltf::Model& model, const tinygltf::Node& node, const glm::dmat4& fileFromNode,
                const std::string& where, Scene& scene) {
    const tinygltf::Camera& camera = model.cameras[size_t(node.camera)];
    const bool orthographic = camera.type == "orthographic";
    if (!orthographic && camera.type != "perspective") {
        scene.warnings.push_back(where + ": its camera is of type '" + printable(camera.type) +
                                 "', neither perspective nor orthographic: left out");
        return;
    }
    FileCamera out;
    const char* fault =
        orthographic ? readOrthographic(camera.orthographic, out) : readPerspective(camera.perspective, out);
    const auto axes = cameraAxes(fileFromNode);
    if (!fault && !axes) fault = "its node gives it no direction to look along";
    if (fault) {
        scene.warnings.push_back(where + ": its camera is left out: " + fault);
        return;
    }
    out.name = nameOf(node, camera.name);
    out.localEye = core::Vec3(fileFromNode[3]);
    std::tie(out.localForward, out.localUp) = *axes;
    if (orthographic)
        scene.warnings.push_back(where + ": its camera is orthographic: drawn as a telephoto (from far behind it, a "
                                         "picture within 1 % of the orthographic one across the scene's depth)");
    scene.cameras.push_back(std::move(out));
}

// A node at `localAt` whose −z is `forward` and whose +y is `up` made square to it.
tinygltf::Node nodeLookingAlong(const std::string& name, const core::Vec3& localAt, const core::Vec3& forward,
                                const core::Vec3& up) {
    const core::Vec3 z = -glm::normalize(forward);
    const core::Vec3 x = glm::normalize(glm::cross(up, z)), y = glm::cross(z, x);
    tinygltf::Node node;
    node.name = name;
    for (const core::Vec3& column : {x, y, z})
        node.matrix.insert(node.matrix.end(), {column.x, column.y, column.z, 0.0});
    node.matrix.insert(node.matrix.end(), {localAt.x, localAt.y, localAt.z, 1.0});
    return node;
}

void readLight(const tinygltf::Model& model, const tinygltf::Node& node, const glm::dmat4& fileFromNode,
               const std::string& where, Scene& scene) {
    const auto extension = node.extensions.find("KHR_lights_punctual");
    if (extension == node.extensions.end()) return;
    const tinygltf::Value& index = extension->second.Get("light");
    if (!index.IsInt() && !index.IsNumber()) {
        scene.warnings.push_back(where + ": its KHR_lights_punctual names no light: left out");
        return;
    }
    const double number = index.GetNumberAsDouble();
    if (!(number >= 0.0 && number < double(model.lights.size())) || number != std::floor(number)) {
        scene.warnings.push_back(where + ": it names light " + std::to_string(number) + " of " +
                                 std::to_string(model.lights.size()) + ": left out");
        return;
    }
    const tinygltf::Light& light = model.lights[size_t(number)];
    FileLight out;
    out.name = nameOf(node, light.name);
    if (light.type == "directional")
        out.kind = FileLight::Kind::Sun;
    else if (light.type == "point")
        out.kind = FileLight::Kind::Point;
    else if (light.type == "spot")
        out.kind = FileLight::Kind::Spot;
    else {
        scene.warnings.push_back(where + ": its light is of type '" + printable(light.type) + "': left out");
        return;
    }
    if (!(light.intensity > 0.0)) return; // off: it lights nothing, so it shadows nothing
    const std::optional<core::Vec3> direction = placedDirection(fileFromNode, {0.0, 0.0, -1.0});
    if (out.kind != FileLight::Kind::Point && !direction) {
        scene.warnings.push_back(where + ": its light is left out: its node gives it no direction");
        return;
    }
    if (direction) out.localDirection = *direction;
    out.localPosition = core::Vec3(fileFromNode[3]);
    if (out.kind == FileLight::Kind::Spot) {
        // glTF's outer cone angle is the half-angle, in (0, π/2]; shadowkit's spot maps take a
        // full opening up to 170° (a perspective frustum's limit, local_lights.h).
        const double outer = light.spot.outerConeAngle;
        if (!(outer > 0.0 && outer <= 0.5 * std::numbers::pi)) {
            scene.warnings.push_back(where + ": its spot light is left out: outerConeAngle is not in (0, π/2]");
            return;
        }
        out.coneDegrees = std::min(2.0 * glm::degrees(outer), 170.0);
        if (2.0 * glm::degrees(outer) > 170.0)
            scene.warnings.push_back(where + ": its spot light opens wider than 170°: its shadows are drawn to 170°");
    }
    if (std::isfinite(light.range) && light.range > 0.0) out.range = light.range; // tinygltf: 0 unlimited
    scene.lights.push_back(std::move(out));
}

} // namespace

void readNodeViewpoints(const tinygltf::Model& model, int nodeIndex, const glm::dmat4& fileFromNode,
                        const std::string& file, bool visible, Scene& scene) {
    const tinygltf::Node& node = model.nodes[size_t(nodeIndex)];
    const std::string where =
        file + ": node " + std::to_string(nodeIndex) + (node.name.empty() ? "" : " '" + printable(node.name) + "'");
    if (node.camera >= 0 && size_t(node.camera) < model.cameras.size())
        readCamera(model, node, fileFromNode, where, scene);
    else if (node.camera >= 0)
        scene.warnings.push_back(where + ": it names camera " + std::to_string(node.camera) + " of " +
                                 std::to_string(model.cameras.size()) + ": left out");
    if (visible) readLight(model, node, fileFromNode, where, scene);
}

std::vector<int> writeViewpoints(const Scene& scene, tinygltf::Model& model) {
    std::vector<int> nodes;
    const auto add = [&](tinygltf::Node node) {
        model.nodes.push_back(std::move(node));
        nodes.push_back(int(model.nodes.size() - 1));
    };
    for (const FileCamera& c : scene.cameras) {
        tinygltf::Camera camera;
        if (c.orthographicHalfHeight) { // as it was read: zFar and aspect are set
            camera.type = "orthographic";
            camera.orthographic.ymag = *c.orthographicHalfHeight;
            camera.orthographic.xmag = *c.orthographicHalfHeight * c.aspect.value_or(1.0);
            camera.orthographic.znear = c.zNear;
            camera.orthographic.zfar = c.zFar.value_or(1e9);
        } else {
            camera.type = "perspective";
            camera.perspective.yfov = glm::radians(c.fovYDegrees);
            camera.perspective.znear = c.zNear;
            // tinygltf writes zfar always, and 0 is no glTF far plane: a far plane past any world
            // (1e9 m, the reader's tightening takes it to the scene) stands for the infinite one.
            camera.perspective.zfar = c.zFar.value_or(1e9);
            camera.perspective.aspectRatio = c.aspect.value_or(0.0); // 0: not written
        }
        model.cameras.push_back(std::move(camera));
        tinygltf::Node node = nodeLookingAlong(c.name, c.localEye, c.localForward, c.localUp);
        node.camera = int(model.cameras.size() - 1);
        add(std::move(node));
    }
    for (const FileLight& l : scene.lights) {
        tinygltf::Light light;
        light.name = l.name;
        light.type = l.kind == FileLight::Kind::Sun     ? "directional"
                     : l.kind == FileLight::Kind::Point ? "point"
                                                        : "spot";
        light.range = l.range.value_or(0.0); // 0: not written, unlimited
        light.spot.innerConeAngle = 0.0;
        light.spot.outerConeAngle = glm::radians(0.5 * l.coneDegrees);
        model.lights.push_back(std::move(light));
        // Any up square to the light's direction: only the direction is the light's.
        const core::Vec3 up = std::abs(l.localDirection.y) < 0.9 ? core::Vec3(0, 1, 0) : core::Vec3(1, 0, 0);
        tinygltf::Node node = nodeLookingAlong(l.name, l.localPosition, l.localDirection, up);
        tinygltf::Value::Object extension{{"light", tinygltf::Value(int(model.lights.size() - 1))}};
        node.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(extension));
        add(std::move(node));
    }
    return nodes;
}

void placeViewpoints(Scene& scene) {
    for (FileCamera& camera : scene.cameras) camera.localEye -= scene.wsOrigin;
    for (FileLight& light : scene.lights) light.localPosition -= scene.wsOrigin;
}

} // namespace shadowkit::scene::formats
