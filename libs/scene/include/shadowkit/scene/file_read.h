// Files read whole. Every file shadowkit reads from its user — scenes and the buffers, images
// and material libraries they name, shadow masks, and the JSON of views, paths, cameras,
// configurations and states — comes through readFile, the other half of file_write.h. A file
// from outside names what it likes: a glTF image URI of "" or "textures/" names a directory
// (whose size a seek reports as 2^63 on ext4, so a reader that trusts it asks for that much
// memory), and one naming a pipe makes a plain open() wait for a writer that never comes. So only
// regular files are read, the pipe opened without waiting, and the size is checked before the
// bytes are held.
#pragma once

#include "shadowkit/core/result.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace shadowkit::scene {

/// The largest file read by default: glTF's lengths are 32-bit (a glb's header, tinygltf's
/// buffers), and no other input comes near it.
inline constexpr uintmax_t kMaxReadFileBytes = (uintmax_t(1) << 32) - 1;

/// The whole of `file`, or a one-line error that starts with its name: "x.json: a directory,
/// not a file", "x.png: a device, pipe or socket, not a file", "x.bin: cannot be read (No such
/// file or directory)", "x.bin: 5,120 MiB, over the 4,096 MiB limit".
/// Symbolic links are followed.
core::Result<std::string> readFile(const std::filesystem::path& file, uintmax_t maxBytes = kMaxReadFileBytes);

/// The whole of a text `file` as UTF-8, for the parsers of line formats (OBJ, MTL) that read
/// ASCII: a UTF-8 byte-order mark is dropped (one before `v 0 0 0` made the first vertex a line
/// of nothing, and a face naming it was refused as naming no vertex) and UTF-16 behind its mark,
/// little- or big-endian as Windows editors write it, is converted. UTF-16 of an odd length or
/// with a surrogate out of its pair is refused in one line ("x.obj: UTF-16 text with a lone
/// surrogate at byte 10"); the rest as readFile.
core::Result<std::string> readTextFile(const std::filesystem::path& file, uintmax_t maxBytes = kMaxReadFileBytes);

} // namespace shadowkit::scene
