#pragma once
// Bad input as a ParseError at the right place: shared by the tests of the readers.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.h"

namespace patchwork::testing {

/// The ParseError that `parse()` throws, or nothing; then the test has failed (it parsed, or
/// threw something else).
template <class Parse>
std::optional<ParseError> parse_error_of(const Parse& parse) {
  try {
    parse();
  } catch (const ParseError& error) {
    return error;
  } catch (const std::exception& other) {
    ADD_FAILURE() << "expected ParseError, got another exception: " << other.what();
    return std::nullopt;
  }
  ADD_FAILURE() << "expected ParseError, but the text parsed";
  return std::nullopt;
}

/// A malformed text, and the line, column and message parts its ParseError must have.
struct Malformed {
  const char* what;
  std::string text;
  std::int64_t line;
  std::int64_t column;
  std::vector<std::string> message_parts;
};

/// Checks each case's ParseError from `parse(text, name)`: its path, line and column, the
/// message's "name:line:column: " start and parts, and no NUL byte cutting what() short.
template <class Parse>
void expect_parse_errors(const std::vector<Malformed>& cases, const std::string& name, const Parse& parse) {
  for (const Malformed& c : cases) {
    SCOPED_TRACE(c.what);
    const auto error = parse_error_of([&] { parse(c.text, name); });
    if (!error) continue;
    EXPECT_EQ(error->path(), name);
    EXPECT_EQ(error->line(), c.line);
    EXPECT_EQ(error->column(), c.column);
    const std::string message = error->what();
    EXPECT_EQ(message.rfind(name + ":" + std::to_string(c.line) + ":" + std::to_string(c.column) + ": ", 0), 0U)
        << message;
    EXPECT_EQ(std::strlen(error->what()), message.size());
    for (const std::string& part : c.message_parts) {
      EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
    }
  }
}

}  // namespace patchwork::testing
