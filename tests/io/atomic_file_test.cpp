#include "io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "tests/support/temporary_directory.h"

namespace patchwork {
namespace {

TEST(AtomicFile, PiecesReplaceTheTargetOnlyOnCommit) {
  const testing::TemporaryDirectory folder("patchwork_atomic_file_test");
  const std::filesystem::path target = folder.path() / "file.bin";
  write_file_atomically(target, "old");
  {
    AtomicFile file(target);
    file.write("new ");
    file.write("");
    file.write(std::string("con\0tent", 8));
    // Until the commit the target keeps its content, and the pieces wait in a hidden file.
    EXPECT_EQ(read_file(target), "old");
    EXPECT_EQ(folder.entries().size(), 2u);
    file.commit();
  }
  EXPECT_EQ(read_file(target), std::string("new con\0tent", 12));
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"file.bin"});
}

TEST(AtomicFile, AnExceptionBetweenPiecesLeavesTheTargetAndNoTemporaryFile) {
  const testing::TemporaryDirectory folder("patchwork_atomic_file_test");
  const std::filesystem::path target = folder.path() / "file.bin";
  write_file_atomically(target, "old");
  try {
    AtomicFile file(target);
    file.write("half of the ");
    throw std::runtime_error("the producer failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read_file(target), "old");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"file.bin"});
  // A target that was not there stays absent.
  {
    AtomicFile file(folder.path() / "new.bin");
    file.write("never committed");
  }
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"file.bin"});
}

TEST(AtomicFile, FailuresNameTheTarget) {
  const testing::TemporaryDirectory folder("patchwork_atomic_file_test");
  const std::filesystem::path missing = folder.path() / "no such folder" / "file.bin";
  try {
    AtomicFile file(missing);
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), missing.string());
  }
  // The target is a folder: the rename fails and the temporary file goes.
  const std::filesystem::path taken = folder.path() / "taken";
  std::filesystem::create_directory(taken);
  AtomicFile file(taken);
  file.write("content");
  EXPECT_THROW(file.commit(), IoError);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"taken"});
}

}  // namespace
}  // namespace patchwork
