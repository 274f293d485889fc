#pragma once
// Writing a file whole or not at all: the content goes to a temporary file in the same folder,
// is flushed, and then renamed over the target, so a failure (full disk, no permission) leaves
// any previous file intact and no partial file behind. The content is given whole
// (write_file_atomically) or in pieces (AtomicFile, for a file too large to hold in memory).

#include <filesystem>
#include <string>
#include <string_view>

namespace patchwork {

/// Replaces `path` with `content` atomically. \throws IoError naming the path and the reason.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// A file written atomically in pieces: the constructor creates the temporary file, write()
/// appends to it, commit() flushes it and renames it over the target. Destroyed without a
/// successful commit() (a failed write, an exception between writes), it removes the temporary
/// file: the target is untouched.
class AtomicFile {
 public:
  /// Creates the temporary file beside `path`. \throws IoError naming the path and the reason.
  explicit AtomicFile(std::filesystem::path path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Removes the temporary file unless commit() succeeded.
  ~AtomicFile();

  /// Appends `bytes` to the temporary file.
  /// \pre commit() has not been called. \throws IoError naming the path and the reason.
  void write(std::string_view bytes);
  /// Flushes the temporary file to disk and renames it over the target.
  /// \pre commit() has not been called. \throws IoError naming the path and the reason.
  void commit();

 private:
  // Closes and removes the temporary file (once), keeping errno.
  void discard() noexcept;
  // Discards the temporary file and throws IoError "what: strerror(errno)".
  [[noreturn]] void fail(const char* what);

  std::filesystem::path path_;
  std::string temporary_;
  int fd_ = -1;
};

/// The whole content of a file. \throws IoError if it cannot be opened or read, or is a directory.
std::string read_file(const std::filesystem::path& path);

}  // namespace patchwork
