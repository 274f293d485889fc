#include "io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"

namespace patchwork {

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  // Built with append: GCC 12 warns falsely (-Wrestrict) on a chain of string operator+.
  std::string hidden_name(".");
  hidden_name.append(path.filename().string()).append(".XXXXXX");
  const std::string pattern = (folder / hidden_name).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw IoError(path.string(), detail::message("cannot create a temporary file: ", std::strerror(errno)));
  const std::string temporary(name.data());
  const auto fail = [&](const char* what) {
    const int code = errno;
    ::close(fd);
    ::unlink(temporary.c_str());
    throw IoError(path.string(), detail::message(what, ": ", std::strerror(code)));
  };
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t step = ::write(fd, content.data() + written, content.size() - written);
    if (step < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    written += static_cast<std::size_t>(step);
  }
  if (::fchmod(fd, 0644) != 0) fail("cannot set permissions");
  if (::fsync(fd) != 0) fail("cannot flush");
  if (::close(fd) != 0) {
    const int code = errno;
    ::unlink(temporary.c_str());
    throw IoError(path.string(), detail::message("cannot close: ", std::strerror(code)));
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const int code = errno;
    ::unlink(temporary.c_str());
    throw IoError(path.string(), detail::message("cannot replace the file: ", std::strerror(code)));
  }
}

std::string read_file(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw IoError(path.string(), "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), detail::message("cannot open: ", std::strerror(errno)));
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw IoError(path.string(), "read failed");
  return content.str();
}

}  // namespace patchwork
