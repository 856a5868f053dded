#pragma once
// A file written whole or not at all: into a temporary file beside it, then renamed over
// it, so a reader (or a second gbxc writing the same folder) sees the old file or the new
// one, never a part. Ctrl-C (or a kill) while it is written removes the temporary file. A
// symbolic link is written through; an existing file keeps its permissions.
#include <filesystem>
#include <string>

namespace gbx::rt {

// Returns what went wrong, or nothing.
std::string writeWhole(const std::filesystem::path& path, const std::string& text);

} // namespace gbx::rt
