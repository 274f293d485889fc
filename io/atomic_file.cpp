#include "io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/assert.h"
#include "core/errors.h"

namespace patchwork {

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  AtomicFile file(path);
  file.write(content);
  file.commit();
}

AtomicFile::AtomicFile(std::filesystem::path path) : path_(std::move(path)) {
  const std::filesystem::path folder = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  // Built with append: GCC 12 warns falsely (-Wrestrict) on a chain of string operator+.
  std::string hidden_name(".");
  hidden_name.append(path_.filename().string()).append(".XXXXXX");
  const std::string pattern = (folder / hidden_name).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0) throw IoError(path_.string(), detail::message("cannot create a temporary file: ", std::strerror(errno)));
  temporary_ = name.data();
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
  const int code = errno;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  temporary_.clear();
  errno = code;
}

void AtomicFile::fail(const char* what) {
  const int code = errno;
  discard();
  throw IoError(path_.string(), detail::message(what, ": ", std::strerror(code)));
}

void AtomicFile::write(std::string_view bytes) {
  PATCHWORK_ASSERT(fd_ >= 0, "AtomicFile::write after commit or a failure");
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t step = ::write(fd_, bytes.data() + written, bytes.size() - written);
    if (step < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    written += static_cast<std::size_t>(step);
  }
}

void AtomicFile::commit() {
  PATCHWORK_ASSERT(fd_ >= 0, "AtomicFile::commit after commit or a failure");
  if (::fchmod(fd_, 0644) != 0) fail("cannot set permissions");
  if (::fsync(fd_) != 0) fail("cannot flush");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("cannot close");
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail("cannot replace the file");
  temporary_.clear();  // renamed: nothing to remove
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
