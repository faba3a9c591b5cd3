#include "formats/support/status.h"

#include <gtest/gtest.h>

#include <string>

#include "formats/support/file_io.h"

namespace lodbake {
namespace {

Result<int> parse_positive(int x) {
  if (x <= 0) return invalid_input("not positive", 42);
  return x;
}

Result<int> twice_positive(int x) {
  LODBAKE_ASSIGN_OR_RETURN(int v, parse_positive(x));
  return 2 * v;
}

TEST(Status, CarriesKindCodeAndMessage) {
  Result<int> bad = twice_positive(-1);
  ASSERT_FALSE(bad.is_ok());
  EXPECT_EQ(bad.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(bad.status().code(), 42);
  EXPECT_EQ(bad.status().message(), "not positive");
  Result<int> good = twice_positive(4);
  ASSERT_TRUE(good.is_ok());
  EXPECT_EQ(good.value(), 8);
}

TEST(FileIo, AtomicWriteThenReadBack) {
  std::string path = ::testing::TempDir() + "lodbake_file_io_test.bin";
  ASSERT_TRUE(write_file_atomic(path, std::string("abc\0def", 7)).is_ok());
  Result<Bytes> back = read_file(path);
  ASSERT_TRUE(back.is_ok());
  EXPECT_EQ(back.value().size(), 7u);
  EXPECT_EQ(back.value()[4], 'd');
}

TEST(FileIo, MissingFileIsAnIoError) {
  Result<Bytes> r = read_file("/nonexistent/lodbake/nothing.obj");
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kIo);
}

TEST(FileIo, WriteIntoMissingFolderFailsAndLeavesNothing) {
  Status s = write_file_atomic("/nonexistent/lodbake/out.lbk", std::string("x"));
  EXPECT_EQ(s.kind(), ErrorKind::kIo);
}

TEST(FileIo, SizeLimitIsEnforced) {
  std::string path = ::testing::TempDir() + "lodbake_file_io_limit.bin";
  ASSERT_TRUE(write_file_atomic(path, std::string(100, 'x')).is_ok());
  Result<Bytes> r = read_file(path, 10);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
}

}  // namespace
}  // namespace lodbake
