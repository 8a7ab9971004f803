// glTF buffer views compressed with meshoptimizer's codecs, decoded.
//
// Based on: the EXT_meshopt_compression specification (Kapoulkine & St. Pierre, ratified by
// Khronos; KhronosGroup/glTF, extensions/2.0/Vendor/EXT_meshopt_compression), whose bitstreams
// (Appendix A: attributes, triangles, indices) and filters (Appendix B: octahedral, quaternion,
// exponential) Debian's libmeshoptimizer 0.18 decodes (meshopt_decodeVertexBuffer,
// meshopt_decodeIndexBuffer, meshopt_decodeIndexSequence, meshopt_decodeFilter*). gltfpack -c
// writes such files, and they are common in the wild. KHR_meshopt_compression, its successor,
// has the same JSON; its version-1 attribute streams (header byte 0xa1) and its colour filter are
// newer than that library, so those are named and refused, and its other streams decode.
//
// tinygltf knows nothing of the extension, so the decoding brackets it:
//   - before it parses, the JSON is rewritten where a buffer only stands in for decoded views: a
//     "placeholder" (marked `fallback`, or with no data: no uri, and not the glb's binary chunk)
//     has a length and no bytes, which tinygltf refuses ("'uri' is missing") or, in a glb, fills
//     with the binary chunk's first bytes. It gets one byte of data instead; its declared length
//     is kept. A file that does not name the extension is parsed byte for byte as before.
//   - after, each compressed view is checked against the rules of the specification (the view
//     holds count × byteStride bytes; strides and counts per mode and filter) and against its
//     buffers, then decoded into its own range of its buffer, which for a placeholder grows as far
//     as its views reach (never past its declared length).
// Hostile files: every number is checked before memory is given to it. A stream of n encoded
// bytes cannot decode to more than 64 n bytes (an attribute block of 16-element groups spends at
// least 2 header bits per byte of the element: 64 bytes out per byte in; a triangle at least one
// code byte for 12 bytes of 32-bit indices; an index at least one byte for 4), so a view that
// claims more is refused before its output is allocated, and so is a file whose views together
// would decode to more than the reader's 4 GiB limit. The decoders themselves are written for
// untrusted input (a malformed stream returns an error, never reads past its bytes).
#include "gltf_meshopt.h"

#include "gltf_materials.h"
#include "scene_formats.h"

#include "shadowkit/scene/file_read.h"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

namespace shadowkit::scene::formats {

namespace {

constexpr std::array<const char*, 2> kExtensions = {"EXT_meshopt_compression", "KHR_meshopt_compression"};
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA=="; // one zero byte
constexpr uint64_t kMaxExpansion = 64; // decoded bytes per encoded byte, at most (above)

// The glb container (glTF 2.0 §4.4): a 12-byte header, then the JSON chunk's length and type.
constexpr size_t kGlbJsonStart = 20;
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A; // "JSON"

uint32_t read32(std::string_view bytes, size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
}

void append32(std::string& out, uint32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);
    out.append(b, 4);
}

// The JSON a file holds: the whole text, or a glb's JSON chunk (nullopt if its header is not one,
// which tinygltf then reports).
std::optional<std::string_view> jsonOf(std::string_view bytes, bool binary) {
    if (!binary) return bytes;
    if (bytes.size() < kGlbJsonStart || bytes.substr(0, 4) != "glTF" || read32(bytes, 16) != kGlbJsonChunk)
        return std::nullopt;
    const uint32_t length = read32(bytes, 12);
    if (length > bytes.size() - kGlbJsonStart) return std::nullopt;
    return bytes.substr(kGlbJsonStart, length);
}

// The glb with its JSON chunk replaced: header and chunk lengths follow, the chunk is padded with
// spaces to four bytes (§4.4.3.1), and everything after it (the binary chunk) is kept as it was.
std::string withJson(std::string_view bytes, std::string_view oldJson, std::string json) {
    while (json.size() % 4 != 0) json.push_back(' ');
    const int64_t total = int64_t(read32(bytes, 8)) + int64_t(json.size()) - int64_t(oldJson.size());
    std::string out(bytes.substr(0, 8));
    append32(out, uint32_t(std::max<int64_t>(total, 0)));
    append32(out, uint32_t(json.size()));
    append32(out, kGlbJsonChunk);
    out += json;
    out += bytes.substr(kGlbJsonStart + oldJson.size());
    return out;
}

// The meshopt extension object on a glTF object (a buffer or a buffer view) in the raw JSON, and its name.
const nlohmann::json* extensionOf(const nlohmann::json& object, const char** name = nullptr) {
    if (!object.is_object()) return nullptr;
    const auto extensions = object.find("extensions");
    if (extensions == object.end() || !extensions->is_object()) return nullptr;
    for (const char* extension : kExtensions)
        if (const auto it = extensions->find(extension); it != extensions->end() && it->is_object()) {
            if (name) *name = extension;
            return &*it;
        }
    return nullptr;
}

// A whole number of at most 2^53 (every such double is exact), or nullopt.
std::optional<uint64_t> wholeNumber(const tinygltf::Value& v) {
    if (!v.IsNumber()) return std::nullopt;
    const double d = v.GetNumberAsDouble();
    if (!(d >= 0.0 && d <= 9007199254740992.0) || std::floor(d) != d) return std::nullopt;
    return uint64_t(d);
}

} // namespace

std::optional<MeshoptFile> prepareMeshopt(std::string_view bytes, bool binary) {
    const std::optional<std::string_view> text = jsonOf(bytes, binary);
    if (!text || text->find("meshopt_compression") == std::string_view::npos) return std::nullopt;
    nlohmann::json json = nlohmann::json::parse(text->begin(), text->end(), nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.is_object()) return std::nullopt;
    const auto views = json.find("bufferViews");
    const auto buffers = json.find("buffers");
    if (views == json.end() || !views->is_array() || buffers == json.end() || !buffers->is_array()) return std::nullopt;
    std::set<uint64_t> decodedInto; // buffers that compressed views decode into
    bool compressed = false;
    for (const nlohmann::json& view : *views) {
        if (!extensionOf(view)) continue;
        compressed = true;
        if (const auto b = view.find("buffer"); b != view.end() && b->is_number_unsigned())
            decodedInto.insert(b->get<uint64_t>());
    }
    if (!compressed) return std::nullopt;
    MeshoptFile file;
    for (size_t i = 0; i < buffers->size(); ++i) {
        nlohmann::json& buffer = (*buffers)[i];
        const nlohmann::json* extension = extensionOf(buffer);
        const auto marked = extension ? extension->find("fallback") : nlohmann::json::const_iterator{};
        const bool fallback = extension && marked != extension->end() && marked->is_boolean() && marked->get<bool>();
        const bool noData = buffer.is_object() && !buffer.contains("uri") && !(binary && i == 0);
        const auto length = buffer.is_object() ? buffer.find("byteLength") : buffer.end();
        if (!(fallback || (noData && decodedInto.count(i))) || length == buffer.end() || !length->is_number_unsigned())
            continue; // a buffer with data, or one tinygltf will refuse by itself
        file.placeholders.emplace_back(i, length->get<uint64_t>());
        buffer["uri"] = kPlaceholderUri;
        buffer["byteLength"] = 1;
    }
    // The parser took only well-formed UTF-8, so nothing is replaced; the handler keeps dump() from throwing.
    std::string rewritten = json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    file.bytes = binary ? withJson(bytes, *text, std::move(rewritten)) : std::move(rewritten);
    return file;
}

core::Status decodeMeshoptViews(tinygltf::Model& model, const std::vector<std::pair<size_t, uint64_t>>& placeholders,
                                const std::string& file) {
    const std::map<size_t, uint64_t> declared(placeholders.begin(), placeholders.end());
    for (const auto& [index, length] : declared) // made as long as their views need, below
        if (index < model.buffers.size()) model.buffers[index].data.clear();
    uint64_t decodedTotal = 0;
    for (size_t v = 0; v < model.bufferViews.size(); ++v) {
        tinygltf::BufferView& view = model.bufferViews[v];
        const char* name = nullptr;
        const tinygltf::Value* ext = nullptr;
        for (const char* extension : kExtensions)
            if (const auto it = view.extensions.find(extension); it != view.extensions.end()) {
                name = extension;
                ext = &it->second;
                break;
            }
        const std::string what = file + ": buffer view " + std::to_string(v);
        if (!ext) {
            if (view.buffer >= 0 && declared.count(size_t(view.buffer)))
                return core::makeError(what + " reads buffer " + std::to_string(view.buffer) +
                                       ", a placeholder for compressed views, which holds no data of its own");
            continue;
        }
        const std::string where = what + " (" + name + ")";
        const auto error = [&](const std::string& why) { return core::makeError(where + ": " + why); };
        if (!ext->IsObject()) return error("the extension is not an object");
        const auto number = [&](const char* key, std::optional<uint64_t> fallback) -> std::optional<uint64_t> {
            const tinygltf::Value& value = ext->Get(key);
            return value.Type() == tinygltf::NULL_TYPE ? fallback : wholeNumber(value);
        };
        const auto source = number("buffer", std::nullopt), offset = number("byteOffset", 0);
        const auto length = number("byteLength", std::nullopt), stride = number("byteStride", std::nullopt);
        const auto count = number("count", std::nullopt);
        if (!source || !offset || !length || !stride || !count)
            return error("buffer, byteLength, byteStride and count must be whole numbers (byteOffset too, if given)");
        const std::string mode = ext->Get("mode").IsString() ? ext->Get("mode").Get<std::string>() : "";
        const std::string filter = ext->Get("filter").IsString() ? ext->Get("filter").Get<std::string>() : "NONE";

        // The specification's rules for the extension object.
        if (*stride == 0 || *stride > 256) return error("byteStride " + std::to_string(*stride) + " is not 1 to 256");
        if (view.byteStride != 0 && uint64_t(view.byteStride) != *stride)
            return error("the view's byteStride " + std::to_string(view.byteStride) + " differs from the extension's " +
                         std::to_string(*stride));
        if (*count > (uint64_t(1) << 53) / *stride || uint64_t(view.byteLength) != *count * *stride)
            return error("the view holds " + std::to_string(view.byteLength) + " bytes, not count × byteStride");
        const uint64_t size = *count * *stride;
        if (mode == "ATTRIBUTES") {
            if (*stride % 4 != 0) return error("ATTRIBUTES need a byteStride divisible by 4");
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (*stride != 2 && *stride != 4) return error(mode + " need a byteStride of 2 or 4");
            if (mode == "TRIANGLES" && *count % 3 != 0) return error("TRIANGLES need a count divisible by 3");
            if (filter != "NONE") return error(mode + " take no filter");
        } else {
            return error("mode '" + printable(mode) + "' is none of ATTRIBUTES, TRIANGLES, INDICES");
        }
        if (filter == "OCTAHEDRAL" ? *stride != 4 && *stride != 8 : filter == "QUATERNION" ? *stride != 8 : false)
            return error("the " + filter + " filter does not take a byteStride of " + std::to_string(*stride));
        if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL")
            return error("filter '" + printable(filter) + "', which shadowkit cannot apply");

        // The bytes it reads and writes.
        if (*source >= model.buffers.size()) return error("its compressed data names no buffer");
        if (declared.count(*source))
            return error("its compressed data lies in buffer " + std::to_string(*source) + ", a placeholder");
        const std::vector<unsigned char>& encoded = model.buffers[*source].data;
        if (*offset > encoded.size() || *length > encoded.size() - *offset)
            return error("its compressed bytes reach past buffer " + std::to_string(*source));
        if (size > kMaxExpansion * *length)
            return error(std::to_string(size) + " bytes cannot be decoded from " + std::to_string(*length) +
                         " (meshopt's codecs expand 64 times at most)");
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) return error("it names no buffer");
        std::vector<unsigned char>& target = model.buffers[size_t(view.buffer)].data;
        const uint64_t end = uint64_t(view.byteOffset) + size;
        if (end < size) return error("its byteOffset is out of range");
        if (const auto placeholder = declared.find(size_t(view.buffer)); placeholder != declared.end()) {
            if (end > placeholder->second)
                return error("it reaches past the " + std::to_string(placeholder->second) +
                             " bytes its buffer declares");
        } else if (end > target.size()) {
            return error("it reaches past its buffer");
        }
        decodedTotal += size;
        if (decodedTotal > kMaxReadFileBytes)
            return error("the file's views decode to more than the 4 GiB shadowkit reads from one file");

        std::vector<unsigned char> decoded(size);
        const unsigned char* in = encoded.data() + *offset;
        const int status =
            mode == "ATTRIBUTES"  ? meshopt_decodeVertexBuffer(decoded.data(), *count, *stride, in, *length)
            : mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(decoded.data(), *count, *stride, in, *length)
                                  : meshopt_decodeIndexSequence(decoded.data(), *count, *stride, in, *length);
        if (status != 0) {
            if (mode == "ATTRIBUTES" && *length > 0 && in[0] == 0xa1)
                return error(
                    "its attributes are in meshopt's vertex codec version 1, newer than the meshoptimizer 0.18 "
                    "shadowkit decodes with: export them with EXT_meshopt_compression (gltfpack -ce ext)");
            return error("its compressed bytes are not a valid " + mode + " stream (meshoptimizer says " +
                         std::to_string(status) + ")");
        }
        if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data(), *count, *stride);
        if (filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data(), *count, *stride);
        if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data(), *count, *stride);
        if (target.size() < end) target.resize(end);
        std::copy(decoded.begin(), decoded.end(), target.begin() + std::ptrdiff_t(view.byteOffset));
    }
    return core::Ok{};
}

} // namespace shadowkit::scene::formats
