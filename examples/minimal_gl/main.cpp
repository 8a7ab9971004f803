// minimal_gl: shadowkit in an OpenGL program of its own, in one file.
//
// The program has its own camera (glm::lookAt, glm::perspective with OpenGL's default clip
// depth [-1, 1]), its own meshes (a ground plane and a field of pillars) and its own shaders.
// shadowkit gives it two things:
//   - shadowkit::core: four cascades with per-split LiSPSM fitted to the camera each frame,
//     as matrices in OpenGL's conventions (shadowkit/core/engine_camera.h,
//     output_conventions.h), with the recommended bias (bias.h);
//   - shadowkit_shadows.glsl, installed with the package: the lookup in the fragment shader.
// With --lamps the frame is at night, lit by a spot lamp and a point lamp among the pillars:
// their maps' set-ups from shadowkit::core (local_lights.h), the maps drawn by the program
// (each texel the distance to the lamp, written per fragment), and their lookups from
// shadowkit_local_shadows.glsl, appended after the sun's file.
//
//   minimal_gl OUT.png [--no-shadows] [--pcss] [--reversed-z] [--lamps]
// draws one 640 × 360 frame off screen and writes it. --pcss: soft shadows of a 3° sun (PCSS
// reads the maps' depths through a second sampler) instead of 2 × 2 PCF. --reversed-z: the
// program as a reversed-Z engine draws, camera and shadow maps alike — clip depth [0, 1]
// (glClipControl), the near side stored as 1, GL_GREATER and GL_GEQUAL, the biases' signs turned —
// with SK_SHADOW_REVERSED_Z defined before the lookup; the picture is the same frame. With
// --lamps, --pcss gives the lamps a 35 cm radius and --reversed-z stores 1 − distance / range.
#include <shadowkit/core/bias.h>
#include <shadowkit/core/engine_camera.h>
#include <shadowkit/core/local_lights.h>
#include <shadowkit/core/output_conventions.h>
#include <shadowkit/core/shadow_filter.h>

// epoxy before GLFW, which would otherwise include the system GL header first.
#include <epoxy/gl.h>

#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace sk = shadowkit::core;

namespace {

constexpr int kWidth = 640, kHeight = 360, kMapSize = 1024, kCascades = 4, kLampMapSize = 1024;

// ---- the program's own meshes: position and normal per vertex, triangles ----
struct Vertex {
    glm::vec3 position, normal;
};

void addQuad(std::vector<Vertex>& out, glm::vec3 corner, glm::vec3 edgeA, glm::vec3 edgeB) {
    const glm::vec3 n = glm::normalize(glm::cross(edgeA, edgeB));
    const glm::vec3 p[4] = {corner, corner + edgeA, corner + edgeA + edgeB, corner + edgeB};
    for (int i : {0, 1, 2, 0, 2, 3}) out.push_back({p[i], n});
}

void addBox(std::vector<Vertex>& out, glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 d = hi - lo, x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
    addQuad(out, lo, y, x);     // -z
    addQuad(out, lo + z, x, y); // +z
    addQuad(out, lo, z, y);     // -x
    addQuad(out, lo + x, y, z); // +x
    addQuad(out, lo + y, z, x); // +y
    addQuad(out, lo, x, z);     // -y
}

std::vector<Vertex> makeScene() {
    std::vector<Vertex> v;
    addQuad(v, {-150, 0, -150}, {0, 0, 300}, {300, 0, 0}); // ground, normal +y
    for (int i = -6; i <= 6; ++i)
        for (int k = -12; k <= 1; ++k) {
            const float h = 2.0f + float((i * 7 + k * 13 + 100) % 9); // 2 .. 10 m
            const glm::vec3 c(float(i) * 9.0f, 0.0f, float(k) * 9.0f);
            addBox(v, c - glm::vec3(0.6f, 0.0f, 0.6f), c + glm::vec3(0.6f, h, 0.6f));
        }
    return v;
}

// ---- shaders ----
// Exits naming what failed, with the driver's log, unless `ok`.
void checkOrExit(GLint ok, const char* what, GLuint object, PFNGLGETSHADERINFOLOGPROC getLog) {
    if (ok) return;
    char log[4096];
    getLog(object, sizeof log, nullptr, log);
    std::fprintf(stderr, "minimal_gl: %s: %s\n", what, log);
    std::exit(1);
}

GLuint compile(GLenum stage, const std::string& source) {
    const GLuint s = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    checkOrExit(ok, "shader", s, glGetShaderInfoLog);
    return s;
}

// Not `link`: that name is POSIX link(2), which a call with two C strings would pick.
GLuint linkProgram(const std::string& vertex, const std::string& fragment) {
    const GLuint p = glCreateProgram();
    glAttachShader(p, compile(GL_VERTEX_SHADER, vertex));
    glAttachShader(p, compile(GL_FRAGMENT_SHADER, fragment));
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    checkOrExit(ok, "link", p, glGetProgramInfoLog); // same signature as the shader's
    return p;
}

const char* kDepthVert = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 clipFromWorld;
uniform float constantBias; // bias.constant * 2^-24: the constant term in clip space, not glPolygonOffset's
void main() { gl_Position = clipFromWorld * vec4(position, 1.0); gl_Position.z += constantBias * gl_Position.w; })";

// The lamps' depth pass: the distance to the lamp, mapped as the lookup is told (storedFromDistance).
const char* kLampDepthVert = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 clipFromWorld;
out vec3 wsPosition;
void main() { wsPosition = position; gl_Position = clipFromWorld * vec4(position, 1.0); })";
const char* kLampDepthFrag = R"(#version 450 core
in vec3 wsPosition;
uniform vec3 wsLamp;
uniform vec2 storedFromDistance;
void main() { gl_FragDepth = distance(wsPosition, wsLamp) * storedFromDistance.x + storedFromDistance.y; })";

const char* kMainVert = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 clipFromWorld;
out vec3 wsPosition, wsNormal;
void main() { wsPosition = position; wsNormal = normal; gl_Position = clipFromWorld * vec4(position, 1.0); })";

// Declarations, then shadowkit_shadows.glsl, then this program's shading.
const char* kMainFragHead = R"(#version 450 core
layout(binding = 1) uniform sampler2DArray shadowDepths; // the same maps, no comparison: PCSS's search
#define SK_SHADOW_DEPTHS shadowDepths
uniform mat4 textureFromWorld[4];
uniform vec4 linearDepthFromWorld[4];
uniform vec4 splits[4];
#define SK_SHADOW_TEXTURE_FROM_WORLD(i) textureFromWorld[i]
#define SK_SHADOW_LINEAR_DEPTH_FROM_WORLD(i) linearDepthFromWorld[i]
#define SK_SHADOW_SPLIT(i) splits[i].xy
layout(binding = 2) uniform sampler2DArrayShadow spotMaps; // the lamps' maps, and their distances for PCSS
layout(binding = 3) uniform sampler2DArray spotDepths;
layout(binding = 4) uniform samplerCubeArrayShadow pointMaps;
layout(binding = 5) uniform samplerCubeArray pointDepths;
#define SK_SPOT_MAPS spotMaps
#define SK_SPOT_DEPTHS spotDepths
#define SK_POINT_MAPS pointMaps
#define SK_POINT_DEPTHS pointDepths
)";
const char* kMainFragBody = R"(
layout(binding = 0) uniform sampler2DArrayShadow shadowMaps;
uniform int mapCount, linearDepth, shadows, offsetGuard, filterKind;
uniform float mapTexels, normalOffsetTexels, normalOffsetFootprint, sunTanHalfAngle;
uniform vec3 wsEye, wsViewForward, wsTowardsSun;
uniform int lamps;
uniform vec3 wsSpot, wsSpotAxis, wsPoint;
uniform float spotCosHalf, lampRange, lampRadius, spotTexelPerMetre, pointTexelPerMetre;
uniform vec2 storedFromDistance;
uniform vec3 lampBias; // core::LocalBias: slope and normal offset in texels, constant in metres
uniform mat4 spotTextureFromWorld;
in vec3 wsPosition, wsNormal;
out vec4 color;

// A lamp's light on a receiver: facing it, inverse square, windowed to nothing at the range.
float lampLight(float intensity, vec3 toLamp, vec3 n) {
    const float d = length(toLamp), x = d / lampRange;
    return intensity * max(dot(n, toLamp) / d, 0.0) * clamp(1.0 - x * x, 0.0, 1.0) / max(d * d, 0.25);
}

// The night frame: the program's own lamps, shadowed by shadowkit's lookups.
vec3 lampLighting(vec3 n) {
    const SkLocalShadowOptions o = SkLocalShadowOptions(lampBias.x, lampBias.y, lampBias.z, filterKind, 16, 16.0);
    const vec3 toSpot = wsSpot - wsPosition, toPoint = wsPoint - wsPosition;
    float spot = dot(-normalize(toSpot), wsSpotAxis) >= spotCosHalf ? lampLight(1500.0, toSpot, n) : 0.0;
    float point = lampLight(60.0, toPoint, n);
    if (shadows != 0 && spot > 0.0)
        spot *= skSpotShadow(SkLocalLight(wsSpot, lampRadius, storedFromDistance, spotTexelPerMetre, 0),
                             spotTextureFromWorld, o, wsPosition, n);
    if (shadows != 0 && point > 0.0)
        point *= skPointShadow(SkLocalLight(wsPoint, lampRadius, storedFromDistance, pointTexelPerMetre, 0), o,
                               wsPosition, n);
    return spot * vec3(1.0, 0.85, 0.6) + point * vec3(0.6, 0.8, 1.0);
}

void main() {
    const vec3 n = normalize(wsNormal);
    const vec3 dx = dFdx(wsPosition), dy = dFdy(wsPosition); // uniform control flow
    const vec3 albedo = n.y > 0.9 && wsPosition.y < 0.01 ? vec3(0.55, 0.6, 0.45) : vec3(0.7, 0.55, 0.45);
    if (lamps != 0) {
        color = vec4(pow(albedo * (0.03 + lampLighting(n)), vec3(1.0 / 2.2)), 1.0);
        return;
    }
    const SkShadowOptions o = SkShadowOptions(mapTexels, linearDepth != 0, normalOffsetTexels, false, filterKind, 16, 16.0,
                                              sunTanHalfAngle, normalOffsetFootprint, offsetGuard != 0);
    const float viewDepth = dot(wsPosition - wsEye, wsViewForward);
    const float nDotL = max(dot(n, wsTowardsSun), 0.0);
    const float lit = shadows != 0 && nDotL > 0.0 ? skCascadedShadow(shadowMaps, mapCount, o, viewDepth, wsPosition, n, dx, dy) : 1.0;
    color = vec4(pow(albedo * (0.25 + 0.9 * nDotL * lit), vec3(1.0 / 2.2)), 1.0);
})";

std::string readFile(const char* path) {
    std::ifstream in(path);
    if (!in) {
        std::fprintf(stderr, "minimal_gl: cannot read %s\n", path);
        std::exit(1);
    }
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

int main(int argc, char** argv) {
    bool shadows = true, pcss = false, reversedZ = false, lamps = false;
    for (int i = 2; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "--no-shadows")
            shadows = false;
        else if (flag == "--pcss")
            pcss = true;
        else if (flag == "--reversed-z")
            reversedZ = true;
        else if (flag == "--lamps")
            lamps = true;
        else
            return std::fprintf(stderr, "minimal_gl: unknown option %s\n", argv[i]), 1;
    }
    if (argc < 2 || argv[1][0] == '-') {
        std::fprintf(stderr, "usage: minimal_gl OUT.png [--no-shadows] [--pcss] [--reversed-z] [--lamps]\n");
        return 1;
    }
    if (!glfwInit()) return std::fprintf(stderr, "minimal_gl: no display for GLFW\n"), 1;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(kWidth, kHeight, "minimal_gl", nullptr, nullptr);
    if (!window) return std::fprintf(stderr, "minimal_gl: no OpenGL 4.5 context\n"), 1;
    glfwMakeContextCurrent(window);

    // ---- the program's camera and sun: OpenGL conventions, clip depth [-1, 1]; or reversed-Z ----
    const glm::dvec3 eye(3.0, 6.0, 14.0), target(0.0, 0.0, -30.0);
    const glm::dmat4 viewFromWorld = glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
    const double fovY = glm::radians(60.0), aspect = double(kWidth) / kHeight;
    glm::dmat4 clipFromView = glm::perspective(fovY, aspect, 0.3, 1000.0);
    if (reversedZ) { // clip depth [0, 1] with z' = w − z: the near plane at 1 (column-major: row 2 is [c][2])
        clipFromView = glm::perspectiveRH_ZO(fovY, aspect, 0.3, 1000.0);
        for (int c = 0; c < 4; ++c) clipFromView[c][2] = clipFromView[c][3] - clipFromView[c][2];
    }
    const sk::ClipDepthRange clipDepth = reversedZ ? sk::ClipDepthRange::ZeroToOne : sk::ClipDepthRange::MinusOneToOne;
    const glm::dvec3 sunTravel = glm::normalize(glm::dvec3(0.8, -0.55, -0.35)); // sun -> scene

    // ---- shadowkit: camera from the matrices, cascades with per-split LiSPSM ----
    sk::ShadowSetupInputs in;
    sk::EngineCamera camera{viewFromWorld, clipFromView, clipDepth};
    camera.shadowDistance = 150.0; // shadows end here; the camera sees 1 km
    const sk::Result<sk::PerspectiveCamera> fitted = sk::cameraFromMatrices(camera);
    if (!fitted) return std::fprintf(stderr, "minimal_gl: %s\n", fitted.error().c_str()), 1;
    in.camera = *fitted;
    in.light = sk::DirectionalLight{sunTravel};
    in.wsSceneBounds = sk::Aabb::fromMinMax({-150, 0, -150}, {150, 12, 150});
    in.technique = sk::Technique::Csm;
    in.cascades.count = kCascades;
    in.cascades.warp = sk::CascadeWarp::Lispsm;
    in.cascades.blendBand = 0.1;
    in.mapSize = kMapSize;
    const sk::Result<sk::ShadowSetup> setup = sk::computeShadowSetup(in);
    if (!setup) return std::fprintf(stderr, "minimal_gl: %s\n", setup.error().c_str()), 1;
    const sk::BiasSettings bias = sk::recommendedBias(setup->technique, setup->depthLayout);
    const sk::OutputConventions conventions =
        reversedZ ? sk::OutputConventions{sk::ClipDepthRange::ZeroToOne, true} : sk::OutputConventions::openGL();
    std::vector<sk::EngineShadowView> views;
    for (const sk::ShadowView& v : setup->views) views.push_back(sk::toEngineView(v, *setup, conventions));

    // ---- the lamps (--lamps): each map fitted to what the camera sees of the lamp's reach ----
    sk::SpotLight spot;
    spot.wsPosition = {-22.0, 10.0, -12.0}; // to the left, its shadows across the view
    spot.wsDirection = {1.0, -0.5, -0.3};
    spot.coneDegrees = 60.0;
    sk::PointLight point;
    point.wsPosition = {-4.5, 2.5, -4.5}; // low among the nearest pillars
    spot.range = point.range = 40.0;
    spot.radius = point.radius = pcss ? 0.35 : 0.0; // PCSS's penumbrae: lamps 70 cm across
    const sk::LocalShadowInputs lampInputs{in.camera, in.wsSceneBounds, kLampMapSize};
    const sk::Result<sk::ShadowSetup> spotSetup = sk::computeSpotShadowSetup(lampInputs, spot);
    if (!spotSetup) return std::fprintf(stderr, "minimal_gl: %s\n", spotSetup.error().c_str()), 1;
    const sk::Result<sk::ShadowSetup> pointSetup = sk::computePointShadowSetup(lampInputs, point);
    if (!pointSetup) return std::fprintf(stderr, "minimal_gl: %s\n", pointSetup.error().c_str()), 1;
    // What a lamp's map stores: distance / range, or 1 − that where the near side is stored as 1.
    const float lampRange = float(spot.range);
    const glm::vec2 storedFromDistance(sk::storedFromDistance(spot.range, reversedZ));
    const sk::LocalBias lampBias; // the lookup's biases, in texels at the receiver's distance and metres

    // ---- GPU objects ----
    const std::vector<Vertex> scene = makeScene();
    GLuint vbo, vao;
    glCreateBuffers(1, &vbo);
    glNamedBufferStorage(vbo, GLsizeiptr(scene.size() * sizeof(Vertex)), scene.data(), 0);
    glCreateVertexArrays(1, &vao);
    glVertexArrayVertexBuffer(vao, 0, vbo, 0, sizeof(Vertex));
    for (GLuint a : {0u, 1u}) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE,
                                  a == 0 ? offsetof(Vertex, position) : offsetof(Vertex, normal));
        glVertexArrayAttribBinding(vao, a, 0);
    }
    // Depth maps compared in the sampler, with 2 × 2 PCF in hardware: the sun's cascades, the spot
    // lamp's map and the point lamp's cube (one cube of a cube-map array).
    auto makeMaps = [&](GLenum target, int size, int layers) {
        GLuint t;
        glCreateTextures(target, 1, &t);
        glTextureStorage3D(t, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
        glTextureParameteri(t, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(t, GL_TEXTURE_COMPARE_FUNC, reversedZ ? GL_GEQUAL : GL_LEQUAL);
        for (GLenum filter : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTextureParameteri(t, filter, GL_LINEAR);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T}) glTextureParameteri(t, wrap, GL_CLAMP_TO_EDGE);
        return t;
    };
    const GLuint maps = makeMaps(GL_TEXTURE_2D_ARRAY, kMapSize, kCascades);
    const GLuint spotMaps = makeMaps(GL_TEXTURE_2D_ARRAY, kLampMapSize, 1);
    const GLuint pointMaps = makeMaps(GL_TEXTURE_CUBE_MAP_ARRAY, kLampMapSize, 6);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS); // filters and PCSS's taps cross the cube's faces
    GLuint mapTarget;
    GLuint depthsSampler; // PCSS reads the stored depths: the same maps without the comparison
    glCreateSamplers(1, &depthsSampler);
    glSamplerParameteri(depthsSampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    for (GLenum filter : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER})
        glSamplerParameteri(depthsSampler, filter, GL_NEAREST);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T})
        glSamplerParameteri(depthsSampler, wrap, GL_CLAMP_TO_EDGE);
    glCreateFramebuffers(1, &mapTarget);
    GLuint colorTarget, colorTexture, depthTexture;
    glCreateTextures(GL_TEXTURE_2D, 1, &colorTexture);
    glTextureStorage2D(colorTexture, 1, GL_RGBA8, kWidth, kHeight);
    glCreateTextures(GL_TEXTURE_2D, 1, &depthTexture);
    glTextureStorage2D(depthTexture, 1, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
    glCreateFramebuffers(1, &colorTarget);
    glNamedFramebufferTexture(colorTarget, GL_COLOR_ATTACHMENT0, colorTexture, 0);
    glNamedFramebufferTexture(colorTarget, GL_DEPTH_ATTACHMENT, depthTexture, 0);

    const GLuint depthProgram = linkProgram(kDepthVert, "#version 450 core\nvoid main() {}\n");
    const GLuint lampDepthProgram = linkProgram(kLampDepthVert, kLampDepthFrag);
    const std::string reversedDefine = reversedZ ? "#define SK_SHADOW_REVERSED_Z\n" : "";
    const GLuint mainProgram = linkProgram(kMainVert, kMainFragHead + reversedDefine + readFile(SHADOWKIT_GLSL_FILE) +
                                                          readFile(SHADOWKIT_LOCAL_GLSL_FILE) + kMainFragBody);
    glBindVertexArray(vao);
    glEnable(GL_DEPTH_TEST);
    if (reversedZ) { // both passes: the near side at 1, nearer wins
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glClearDepth(0.0);
        glDepthFunc(GL_GREATER);
    }

    // ---- shadow pass: one layer per cascade, depth clamped, slope-scaled bias ----
    glUseProgram(depthProgram);
    glViewport(0, 0, kMapSize, kMapSize);
    if (setup->depthClamp) glEnable(GL_DEPTH_CLAMP); // casters before a map's near plane still cast
    glEnable(GL_POLYGON_OFFSET_FILL);
    // Away from the light: towards 0 in a reversed-Z map. A float map scales polygon offset's units
    // by a primitive's largest depth, so the constant term goes into the vertex shader instead.
    const float away = reversedZ ? -1.0f : 1.0f;
    glPolygonOffset(away * float(bias.slope), 0.0f);
    glUniform1f(glGetUniformLocation(depthProgram, "constantBias"), away * float(bias.constant) * 0x1p-24f);
    const size_t sunMaps = lamps ? 0 : views.size(); // the night frame reads no sun map
    for (size_t i = 0; i < sunMaps; ++i) {
        glNamedFramebufferTextureLayer(mapTarget, GL_DEPTH_ATTACHMENT, maps, 0, GLint(i));
        glBindFramebuffer(GL_FRAMEBUFFER, mapTarget);
        glClear(GL_DEPTH_BUFFER_BIT);
        glUniformMatrix4fv(glGetUniformLocation(depthProgram, "clipFromWorld"), 1, GL_FALSE,
                           glm::value_ptr(glm::mat4(views[i].clipFromWorld)));
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(scene.size()));
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_CLAMP);

    // ---- the lamps' pass: each view of a set-up into its layer (a point lamp's cube face) ----
    auto drawLampMaps = [&](GLuint texture, int layers, const sk::ShadowSetup& lampSetup) {
        glUniform3fv(glGetUniformLocation(lampDepthProgram, "wsLamp"), 1,
                     glm::value_ptr(glm::vec3(lampSetup.wsLightPosition)));
        glUniform2fv(glGetUniformLocation(lampDepthProgram, "storedFromDistance"), 1,
                     glm::value_ptr(storedFromDistance));
        glBindFramebuffer(GL_FRAMEBUFFER, mapTarget);
        for (int layer = 0; layer < layers; ++layer) { // faces that see nothing of the view stay far: lit
            glNamedFramebufferTextureLayer(mapTarget, GL_DEPTH_ATTACHMENT, texture, 0, layer);
            glClear(GL_DEPTH_BUFFER_BIT);
        }
        if (lampSetup.depthClamp) glEnable(GL_DEPTH_CLAMP);
        for (const sk::ShadowView& v : lampSetup.views) {
            glNamedFramebufferTextureLayer(mapTarget, GL_DEPTH_ATTACHMENT, texture, 0, v.face.value_or(0));
            glUniformMatrix4fv(glGetUniformLocation(lampDepthProgram, "clipFromWorld"), 1, GL_FALSE,
                               glm::value_ptr(glm::mat4(sk::toEngineView(v, lampSetup, conventions).clipFromWorld)));
            glDrawArrays(GL_TRIANGLES, 0, GLsizei(scene.size()));
        }
        glDisable(GL_DEPTH_CLAMP);
    };
    if (lamps) {
        glUseProgram(lampDepthProgram);
        glViewport(0, 0, kLampMapSize, kLampMapSize);
        drawLampMaps(spotMaps, 1, *spotSetup);
        drawLampMaps(pointMaps, 6, *pointSetup);
    }

    // ---- camera pass ----
    glBindFramebuffer(GL_FRAMEBUFFER, colorTarget);
    glViewport(0, 0, kWidth, kHeight);
    glClearColor(lamps ? 0.02f : 0.6f, lamps ? 0.03f : 0.75f, lamps ? 0.06f : 0.9f, 1.0f); // night sky with the lamps
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(mainProgram);
    auto uniform = [&](const char* name) { return glGetUniformLocation(mainProgram, name); };
    glUniformMatrix4fv(uniform("clipFromWorld"), 1, GL_FALSE, glm::value_ptr(glm::mat4(clipFromView * viewFromWorld)));
    for (size_t i = 0; i < views.size(); ++i) {
        const std::string at = "[" + std::to_string(i) + "]";
        glUniformMatrix4fv(uniform(("textureFromWorld" + at).c_str()), 1, GL_FALSE,
                           glm::value_ptr(glm::mat4(views[i].textureFromWorld)));
        glUniform4fv(uniform(("linearDepthFromWorld" + at).c_str()), 1,
                     glm::value_ptr(glm::vec4(views[i].linearDepthFromWorld)));
        glUniform4f(uniform(("splits" + at).c_str()), float(views[i].split->x), float(views[i].split->y), 0.0f, 0.0f);
    }
    glUniform1i(uniform("mapCount"), GLint(views.size()));
    glUniform1i(uniform("linearDepth"), setup->depthLayout == sk::DepthLayout::Linear);
    glUniform1i(uniform("shadows"), shadows);
    glUniform1f(uniform("mapTexels"), float(kMapSize));
    glUniform1f(uniform("normalOffsetTexels"), float(bias.normalOffset));
    glUniform1f(uniform("normalOffsetFootprint"), float(bias.normalOffsetFootprint));
    glUniform1i(uniform("offsetGuard"), bias.offsetGuard);
    glUniform1i(uniform("filterKind"), pcss ? int(sk::ShadowFilter::Pcss) : int(sk::ShadowFilter::Pcf2));
    glUniform1f(uniform("sunTanHalfAngle"), pcss ? float(std::tan(glm::radians(1.5))) : 0.0f); // a 3° sun
    glUniform3fv(uniform("wsEye"), 1, glm::value_ptr(glm::vec3(eye)));
    glUniform3fv(uniform("wsViewForward"), 1, glm::value_ptr(glm::vec3(glm::normalize(target - eye))));
    glUniform3fv(uniform("wsTowardsSun"), 1, glm::value_ptr(glm::vec3(-sunTravel)));
    const auto texelPerMetre = [](const sk::ShadowSetup& lampSetup) {
        return lampSetup.views.empty() ? 0.0f : float(sk::texelSizePerMetre(lampSetup.views[0], kLampMapSize));
    };
    const glm::mat4 spotTextureFromWorld =
        spotSetup->views.empty()
            ? glm::mat4(1.0f)
            : glm::mat4(sk::toEngineView(spotSetup->views[0], *spotSetup, conventions).textureFromWorld);
    glUniform1i(uniform("lamps"), lamps);
    glUniform3fv(uniform("wsSpot"), 1, glm::value_ptr(glm::vec3(spot.wsPosition)));
    glUniform3fv(uniform("wsSpotAxis"), 1, glm::value_ptr(glm::vec3(glm::normalize(spot.wsDirection))));
    glUniform3fv(uniform("wsPoint"), 1, glm::value_ptr(glm::vec3(point.wsPosition)));
    glUniform1f(uniform("spotCosHalf"), float(std::cos(glm::radians(0.5 * spot.coneDegrees))));
    glUniform1f(uniform("lampRange"), lampRange);
    glUniform1f(uniform("lampRadius"), float(spot.radius));
    glUniform1f(uniform("spotTexelPerMetre"), texelPerMetre(*spotSetup));
    glUniform1f(uniform("pointTexelPerMetre"), texelPerMetre(*pointSetup));
    glUniform2fv(uniform("storedFromDistance"), 1, glm::value_ptr(storedFromDistance));
    glUniform3f(uniform("lampBias"), float(lampBias.slopeTexels), float(lampBias.normalOffsetTexels),
                float(lampBias.constantMetres));
    glUniformMatrix4fv(uniform("spotTextureFromWorld"), 1, GL_FALSE, glm::value_ptr(spotTextureFromWorld));
    // Each kind of map twice: compared (units 0, 2, 4) and read as depths by PCSS (1, 3, 5).
    const GLuint unitMaps[6] = {maps, maps, spotMaps, spotMaps, pointMaps, pointMaps};
    for (GLuint unit = 0; unit < 6; ++unit) {
        glBindTextureUnit(unit, unitMaps[unit]);
        if (unit % 2) glBindSampler(unit, depthsSampler);
    }
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(scene.size()));

    // ---- read back and write the picture (rows bottom-up in GL) ----
    std::vector<unsigned char> pixels(size_t(kWidth) * kHeight * 4);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    stbi_flip_vertically_on_write(1);
    if (!stbi_write_png(argv[1], kWidth, kHeight, 4, pixels.data(), kWidth * 4))
        return std::fprintf(stderr, "minimal_gl: cannot write %s\n", argv[1]), 1;
    if (lamps)
        std::printf("minimal_gl: at night, a spot lamp (%zu map) and a point lamp (%zu of 6 cube faces), %s, %s depth, "
                    "%zu triangles, wrote %s\n",
                    spotSetup->views.size(), pointSetup->views.size(), pcss ? "PCSS" : "2 x 2 PCF",
                    reversedZ ? "reversed-Z" : "OpenGL", scene.size() / 3, argv[1]);
    else
        std::printf("minimal_gl: %zu cascades (%s, per-split LiSPSM), %s, %s depth, %zu triangles, wrote %s\n",
                    views.size(), std::string(sk::techniqueName(setup->technique)).c_str(), pcss ? "PCSS" : "2 x 2 PCF",
                    reversedZ ? "reversed-Z" : "OpenGL", scene.size() / 3, argv[1]);
    glfwTerminate();
    return 0;
}
