// Files written whole or not at all. Every file the library and its programs write (PNG, glb,
// OBJ, JSON, CSV, HTML, NumPy arrays, viewer states) goes through writeFile: the bytes go to a
// temporary file beside the target, are flushed to the disk and renamed over the final name, so
// a full disk, a missing directory or a killed process never leaves a partial file under that
// name, and never reports "wrote" for a file that is not there.
#pragma once

#include "shadowkit/core/result.h"

#include <filesystem>
#include <functional>
#include <string_view>

namespace shadowkit::scene {

// Writes `bytes` to `file`, creating its missing parent directories. Errors are one line that
// starts with the file's name: "out/x.png: cannot write (No space left on device)". A target
// that exists and is not a regular file (a device such as /dev/stdout, a pipe) is written in
// place, since renaming over it would replace it.
core::Status writeFile(const std::filesystem::path& file, std::string_view bytes);

// What writeFileInPieces hands its producer: writes one piece, and returns false once a piece
// has failed (the rest may be skipped: the file will not be written).
using ByteSink = std::function<bool(std::string_view)>;

// writeFile for a file too large to hold in memory whole (a large scene's OBJ): `produce` hands
// its pieces, in order, to the sink it is given; the same guarantees and errors.
core::Status writeFileInPieces(const std::filesystem::path& file, const std::function<void(const ByteSink&)>& produce);

// Creates the parent directories `file` will need, so a long computation can fail before it
// starts rather than at its end; the same one-line error as writeFile when it cannot.
core::Status prepareOutputDirectory(const std::filesystem::path& file);

} // namespace shadowkit::scene
