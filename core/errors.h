#pragma once
// The one exception family of patchwork, derived from the standard exception types.
//
//   std::invalid_argument <- InvalidInput <- TopologyError   (bad input: caller's data is wrong)
//   std::runtime_error    <- ParseError{path, line, column}  (a file's content is wrong)
//   std::runtime_error    <- IoError{path}                   (the file system failed us)
//   std::runtime_error    <- NumericalError                  (a computation cannot deliver its contract)
//
// Messages name the function and the element: "BezierCurve: control point 3 is not finite (nan, 0)".

#include <charconv>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>

namespace patchwork {

/// The caller passed data that violates a documented precondition.
class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Mesh connectivity that is not what the operation requires (non-manifold, out of range, ...).
class TopologyError : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

/// A file's content could not be parsed; carries where (line and column are 1-based, 0 if unknown).
class ParseError : public std::runtime_error {
 public:
  /// Builds "path:line:column: message".
  ParseError(std::string path, std::int64_t line, std::int64_t column, const std::string& message);
  const std::string& path() const noexcept { return path_; }
  std::int64_t line() const noexcept { return line_; }
  std::int64_t column() const noexcept { return column_; }

 private:
  std::string path_;
  std::int64_t line_;
  std::int64_t column_;
};

/// Reading or writing a file failed at the operating-system level.
class IoError : public std::runtime_error {
 public:
  /// Builds "path: message".
  IoError(std::string path, const std::string& message);
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
};

/// A numerical procedure cannot meet its contract (no convergence, undefined quantity).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {

/// Writes one part of a message: doubles in the shortest form that reads back to the same value
/// (1e-12, not 9.9999999999999998e-13), everything else with operator<<.
template <class Part>
void append_part(std::ostringstream& out, const Part& part) {
  if constexpr (std::is_floating_point_v<Part>) {
    char buffer[32];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, static_cast<double>(part));
    out.write(buffer, error == std::errc() ? end - buffer : 0);
  } else {
    out << part;
  }
}

/// Concatenates the arguments into one message string (see append_part).
template <class... Parts>
std::string message(const Parts&... parts) {
  std::ostringstream out;
  out.precision(17);
  (append_part(out, parts), ...);
  return out.str();
}

}  // namespace detail
}  // namespace patchwork
