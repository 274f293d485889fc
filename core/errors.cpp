#include "core/errors.h"

#include <utility>

namespace patchwork {

ParseError::ParseError(std::string path, std::int64_t line, std::int64_t column,
                       const std::string& message)
    : std::runtime_error(detail::message(path, ':', line, ':', column, ": ", message)),
      path_(std::move(path)),
      line_(line),
      column_(column) {}

IoError::IoError(std::string path, const std::string& message)
    : std::runtime_error(detail::message(path, ": ", message)), path_(std::move(path)) {}

}  // namespace patchwork
