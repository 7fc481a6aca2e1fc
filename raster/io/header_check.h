// Checks of a model file's header before Assimp reads it, for the formats whose header
// declares what follows (recognised by content: PLY's "ply" line, OFF's "OFF"):
// - the declared counts against what the file's size can hold. Assimp reserves memory for the
//   declared counts up front, so a 300-byte file claiming 10^11 vertices would ask for
//   terabytes (Debian's assimp-testmodels/invalid/OutOfMemory.off). Only a lower bound on the
//   bytes per element is used (ASCII: one character and a separator per value; binary: the
//   property sizes), so no valid file is rejected;
// - a PLY header's end: an "end_header" line. Assimp 5.2's PLY reader loops forever on headers
//   without one (found by fuzzing).
// - an OBJ file's first 64 KiB are text: binary data (a sparse file of gigabytes, a wrong file)
//   would be read to its end and yield an empty mesh.
// The reader runs isolated anyway (isolated_call.h); these checks turn the common cases into a
// precise message instead of a time-out.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

namespace tessera::io {

// What is wrong with the file's header, or nothing (also for formats without such a header).
std::optional<std::string> header_problem(const std::filesystem::path& path);

}  // namespace tessera::io
