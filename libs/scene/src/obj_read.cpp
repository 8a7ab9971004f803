// Wavefront OBJ import through tinyobjloader: one mesh per object or group, one instance each.
// Polygons are triangulated; normals come from the file when every corner has one, else from
// the faces; albedo is the material's diffuse colour (Kd, from the .mtl beside the file) times
// the vertex colour of the widely read `v x y z r g b` extension, which shadowkit's own export
// writes. Files without either are light grey. A material with a dissolve texture (`map_d`), or
// one that dissolves below half (`d`, glass), cuts its faces as glTF's MASK does, read in
// obj_materials.cpp: those faces are a mesh of their own with its texture coordinates. The file
// and the material libraries it names are read through scene::readTextFile: an mtllib line
// naming a pipe would otherwise wait forever, and a byte-order mark or UTF-16 would hide the
// first line from the parser.
#include "obj_materials.h"
#include "scene_formats.h"

#include "shadowkit/scene/file_read.h"

#include <tiny_obj_loader.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// DAZ Studio and others write the dissolve texture `map_D`; tinyobjloader reads `map_d` alone.
std::string dissolveSpelledAsParsed(std::string text) {
    for (size_t line = 0; line < text.size();) {
        size_t at = text.find_first_not_of(" \t", line);
        if (at != std::string::npos && text.compare(at, 5, "map_D") == 0 && at + 5 < text.size() &&
            (text[at + 5] == ' ' || text[at + 5] == '\t'))
            text[at + 4] = 'd';
        const size_t end = text.find('\n', line);
        line = end == std::string::npos ? text.size() : end + 1;
    }
    return text;
}

// Material names with spaces. An MTL's `newmtl` names the material by the rest of its line
// ("Hard Shiny Plastic White"), and tinyobjloader reads it so, but its OBJ reader takes a
// `usemtl` line's first word alone ("Hard"): the faces then wear no material, grey and uncut
// (assimp reads such files; two of its test models have them). So both sides are rewritten
// before parsing: the name of each `newmtl` and `usemtl` line, trimmed, its runs of blanks
// joined by kNameSpace, which the names read back turn into one space each.
constexpr char kNameSpace = '\x1f';

// Calls visit(begin, end, lineEnd) with the span of the name on each line of `text` that opens
// with `keyword` and a blank — the rest of the line up to a comment, trimmed — and where the line
// ends (its '\n', or the text's end).
template <typename Visit>
void forEachNamed(std::string_view text, std::string_view keyword, Visit visit) {
    for (size_t line = 0; line < text.size();) {
        const size_t end = std::min(text.find('\n', line), text.size());
        const size_t at = text.find_first_not_of(" \t", line);
        if (at < end && text.substr(at, keyword.size()) == keyword && at + keyword.size() < end &&
            (text[at + keyword.size()] == ' ' || text[at + keyword.size()] == '\t')) {
            const size_t first = text.find_first_not_of(" \t", at + keyword.size());
            size_t last = end;
            // A comment after the name ("usemtl bark # from the trunk") is not part of it.
            for (size_t hash = text.find('#', first); hash < end; hash = text.find('#', hash + 1))
                if (text[hash - 1] == ' ' || text[hash - 1] == '\t') {
                    last = hash;
                    break;
                }
            while (last > first && (text[last - 1] == ' ' || text[last - 1] == '\t' || text[last - 1] == '\r')) --last;
            if (first < last) visit(first, last, end);
        }
        line = end + 1;
    }
}

// `text` with each `keyword` line's name joined (above) and what follows it on the line (blanks,
// a comment) dropped; the same text where no line needs that.
std::string withNamesJoined(std::string text, std::string_view keyword) {
    struct Span {
        size_t first, last, lineEnd;
    };
    std::vector<Span> spans;
    forEachNamed(text, keyword, [&](size_t first, size_t last, size_t lineEnd) {
        if (text.find_first_of(" \t", first) < last || text.find_first_not_of('\r', last) < lineEnd)
            spans.push_back({first, last, lineEnd});
    });
    if (spans.empty()) return text;
    std::string joined;
    joined.reserve(text.size());
    size_t copied = 0;
    for (const Span& span : spans) {
        joined.append(text, copied, span.first - copied);
        for (size_t i = span.first; i < span.last; ++i) {
            if (text[i] != ' ' && text[i] != '\t')
                joined += text[i];
            else if (joined.back() != kNameSpace)
                joined += kNameSpace;
        }
        copied = span.lineEnd;
    }
    joined.append(text, copied);
    return joined;
}

// A name as the file wrote it, its joined blanks one space each.
std::string spelled(std::string name) {
    std::replace(name.begin(), name.end(), kNameSpace, ' ');
    return name;
}

// The material libraries an OBJ names (`mtllib`), beside it, as tinyobjloader's own reader finds
// them. One that cannot be read leaves the faces that wear its materials in the default grey and
// uncut: tinyobjloader says so in its warnings, which name no file and which this reader does
// not pass on (most are noise: an empty group name, a degenerate face), so the libraries not read
// are kept here, each once, for a warning of their own.
class MaterialLibraries : public tinyobj::MaterialReader {
public:
    explicit MaterialLibraries(fs::path directory) : m_directory(std::move(directory)) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* materialOf, std::string* warn, std::string* err) override {
        const fs::path path = m_directory / name;
        const auto text = readTextFile(path);
        if (!text) {
            // readTextFile's error names the path first: kept is what follows it.
            std::string why = text.error();
            if (const std::string named = path.string() + ": "; why.starts_with(named)) why.erase(0, named.size());
            if (std::none_of(m_unread.begin(), m_unread.end(), [&](const auto& u) { return u.first == name; }))
                m_unread.emplace_back(name, why);
            return false;
        }
        std::istringstream in(dissolveSpelledAsParsed(withNamesJoined(*text, "newmtl")));
        tinyobj::LoadMtl(materialOf, materials, &in, warn, err);
        ++m_read;
        return true;
    }
    // How many libraries were read.
    int read() const { return m_read; }
    // The libraries named that could not be read, in the order named: their names as written and why.
    const std::vector<std::pair<std::string, std::string>>& unread() const { return m_unread; }

private:
    fs::path m_directory;
    std::vector<std::pair<std::string, std::string>> m_unread;
    int m_read = 0;
};

// The material names the OBJ's `usemtl` lines give, joined as its text is before parsing, each
// once, in order.
std::vector<std::string> materialsUsed(std::string_view joinedText) {
    std::vector<std::string> names;
    forEachNamed(joinedText, "usemtl", [&](size_t first, size_t last, size_t) {
        std::string name(joinedText.substr(first, last - first));
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(std::move(name));
    });
    return names;
}

// A face's corner: its indices into the file's positions, normals (+ 1) and texture coordinates (+ 1).
struct Corner {
    int position = 0, normal = 0, texcoord = 0;
    bool operator==(const Corner&) const = default;
};
struct CornerHash {
    size_t operator()(const Corner& c) const {
        // Fibonacci hashing of each index, combined: corners of one position differ in the others.
        uint64_t h = uint64_t(uint32_t(c.position)) * 0x9E3779B97F4A7C15ull;
        h ^= (uint64_t(uint32_t(c.normal)) + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2)) * 0x9E3779B97F4A7C15ull;
        h ^= (uint64_t(uint32_t(c.texcoord)) + 0x85EBCA77C2B2AE63ull + (h << 6) + (h >> 2)) * 0x9E3779B97F4A7C15ull;
        return size_t(h ^ (h >> 32));
    }
};

} // namespace

core::Result<Scene> loadObj(const fs::path& file) {
    auto text = readTextFile(file);
    if (!text) return text.errorInfo();
    // The file's text is held once more by the stream below; the names are joined in place of it,
    // not beside it (a copy only where a line needs it).
    const std::string joinedText = withNamesJoined(std::move(*text), "usemtl");
    std::istringstream in(joinedText);
    MaterialLibraries libraries(file.parent_path());
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    // Triangulated; colours only when every vertex has one (no white fallback).
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &libraries, /*triangulate=*/true,
                          /*default_vcols_fallback=*/false))
        return core::makeError(file.string() + ": not a readable OBJ file (" + oneLine(err) + ")");
    const bool colours = !attrib.colors.empty();
    const size_t vertexCount = attrib.vertices.size() / 3, normalCount = attrib.normals.size() / 3;
    // Positions are parsed in double (tinyobjloader_double) and become float only relative to
    // the file's anchor (near_origin.cpp): a file in survey metres keeps its millimetres.
    core::Aabb fileBounds;
    for (size_t v = 0; v < vertexCount; ++v) {
        const glm::dvec3 p(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) fileBounds.extend(p);
    }
    const glm::dvec3 anchor = anchorOf(fileBounds);

    Scene scene;
    for (const auto& [library, why] : libraries.unread())
        scene.warnings.push_back(file.string() + ": its material library '" + printable(library) +
                                 "': " + oneLine(why) +
                                 "; the faces wearing its materials are drawn grey, and none is cut by a map_d");
    // A name that the libraries the OBJ names, all read, do not define (often by its case):
    // tinyobjloader gives those faces no material, and said so only in the warnings dropped above. An OBJ that names no
    // library is not told about its usemtl lines (exporters write `usemtl Default` with none).
    if (libraries.read() > 0 && libraries.unread().empty()) {
        std::vector<std::string> undefined;
        for (const std::string& name : materialsUsed(joinedText))
            if (std::none_of(materials.begin(), materials.end(), [&](const auto& m) { return m.name == name; }))
                undefined.push_back(name);
        if (!undefined.empty()) {
            std::string names;
            for (size_t i = 0; i < std::min<size_t>(undefined.size(), 3); ++i)
                names += (i ? ", '" : "'") + printable(spelled(undefined[i])) + "'";
            if (undefined.size() > 3) names += " and " + std::to_string(undefined.size() - 3) + " more";
            scene.warnings.push_back(file.string() + ": usemtl names " + std::to_string(undefined.size()) +
                                     (undefined.size() == 1 ? " material" : " materials") +
                                     " that no material library defines (" + names +
                                     "): their faces are drawn grey, and none is cut by a map_d");
        }
    }
    for (tinyobj::material_t& material : materials) material.name = spelled(std::move(material.name));
    // The file's materials that cut their faces (map_d, or a dissolve below half): their index in
    // scene.materials, else −1.
    std::vector<size_t> facesWearing(materials.size(), 0);
    for (const tinyobj::shape_t& shape : shapes)
        for (const int material : shape.mesh.material_ids)
            if (material >= 0 && size_t(material) < materials.size()) ++facesWearing[size_t(material)];
    const std::vector<int32_t> cutBy = readObjMaterials(materials, facesWearing, file, scene);
    const size_t texcoordCount = attrib.texcoords.size() / 2;
    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& faces = shape.mesh;
        const std::string name = shape.name.empty() ? file.stem().string() : shape.name;
        // The shape's faces in one mesh, but those of a cutting material in one of their own
        // (Mesh::material is per mesh): part 0 is the opaque faces', part k + 1 material k's —
        // kept in a map, as a file may hold thousands of groups and of materials.
        struct Part {
            Mesh mesh;
            bool everyNormal = true;
        };
        std::map<size_t, Part> parts;
        // One vertex per distinct (position, normal, texture coordinate) corner of each material:
        // material + 1 picks the map; the key holds normal + 1 and, for a cutting material,
        // texture coordinate + 1, so that "none" is 0.
        std::vector<std::unordered_map<Corner, uint32_t, CornerHash>> vertexOf(materials.size() + 1);
        for (size_t corner = 0; corner < faces.indices.size(); ++corner) {
            const tinyobj::index_t& index = faces.indices[corner];
            const size_t face = corner / 3;
            const int material = face < faces.material_ids.size() ? faces.material_ids[face] : -1;
            if (index.vertex_index < 0 || size_t(index.vertex_index) >= vertexCount)
                return core::makeError(file.string() + ": object '" + name + "': a face names vertex " +
                                       std::to_string(index.vertex_index + 1) + " of " + std::to_string(vertexCount));
            const bool hasNormal = index.normal_index >= 0 && size_t(index.normal_index) < normalCount;
            const size_t slot = material >= 0 && size_t(material) < materials.size() ? size_t(material) + 1 : 0;
            const bool cut = slot > 0 && cutBy[slot - 1] >= 0;
            const bool hasUv = cut && index.texcoord_index >= 0 && size_t(index.texcoord_index) < texcoordCount;
            Part& part = parts[cut ? slot : 0];
            Mesh& mesh = part.mesh;
            part.everyNormal = part.everyNormal && hasNormal;
            const Corner key{index.vertex_index, hasNormal ? index.normal_index + 1 : 0,
                             hasUv ? index.texcoord_index + 1 : 0};
            auto [it, inserted] = vertexOf[slot].try_emplace(key, uint32_t(mesh.vertices.size()));
            if (inserted) {
                const size_t v = size_t(index.vertex_index);
                Vertex vertex;
                const glm::dvec3 position(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                          attrib.vertices[3 * v + 2]);
                vertex.position = glm::vec3(position - anchor);
                if (!std::isfinite(vertex.position.x) || !std::isfinite(vertex.position.y) ||
                    !std::isfinite(vertex.position.z))
                    return core::makeError(file.string() + ": object '" + name + "': vertex " + std::to_string(v + 1) +
                                           " is not finite");
                vertex.normal = glm::vec3(0, 1, 0);
                if (hasNormal) {
                    const size_t n = size_t(index.normal_index);
                    const glm::vec3 normal(attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]);
                    const float length = glm::length(normal);
                    if (length > 0.0f && std::isfinite(length)) vertex.normal = normal / length;
                }
                glm::vec3 albedo =
                    material >= 0 && size_t(material) < materials.size()
                        ? glm::vec3(materials[size_t(material)].diffuse[0], materials[size_t(material)].diffuse[1],
                                    materials[size_t(material)].diffuse[2])
                        : glm::vec3(colours ? 1.0f : 0.7f);
                if (colours)
                    albedo *= glm::vec3(attrib.colors[3 * v], attrib.colors[3 * v + 1], attrib.colors[3 * v + 2]);
                vertex.albedo = glm::clamp(albedo, 0.0f, 1.0f);
                if (hasUv) {
                    const size_t t = size_t(index.texcoord_index);
                    const glm::vec2 uv = objTextureUv(materials[slot - 1].alpha_texopt,
                                                      {attrib.texcoords[2 * t], attrib.texcoords[2 * t + 1]});
                    vertex.uv = std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : glm::vec2(0.0f);
                }
                mesh.vertices.push_back(vertex);
            }
            mesh.indices.push_back(it->second);
        }
        for (auto& [part, content] : parts) {
            Mesh& mesh = content.mesh;
            if (mesh.indices.empty()) continue; // points and lines only, or no face of this material
            mesh.name = part == 0 ? name : name + " (" + materials[part - 1].name + ")";
            mesh.material = part == 0 ? -1 : cutBy[part - 1];
            if (!content.everyNormal) computeNormals(mesh);
            mesh.computeBounds();
            scene.meshes.push_back(std::move(mesh));
            scene.batches.push_back({uint32_t(scene.meshes.size() - 1), {}, false});
        }
    }
    if (scene.meshes.empty()) return core::makeError(file.string() + ": OBJ file holds no faces");
    const std::vector<std::vector<glm::dmat4>> placements(scene.batches.size(),
                                                          {glm::translate(glm::dmat4(1.0), anchor)});
    placeNearOrigin(scene, placements);
    return scene;
}

} // namespace shadowkit::scene::formats
