#pragma once
// Writing a file whole or not at all: the content goes to a temporary file in the same folder,
// is flushed, and then renamed over the target, so a failure (full disk, no permission) leaves
// any previous file intact and no partial file behind.

#include <filesystem>
#include <string_view>

namespace patchwork {

/// Replaces `path` with `content` atomically. \throws IoError naming the path and the reason.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// The whole content of a file. \throws IoError if it cannot be opened or read, or is a directory.
std::string read_file(const std::filesystem::path& path);

}  // namespace patchwork
