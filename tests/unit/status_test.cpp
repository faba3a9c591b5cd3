#include "formats/support/status.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <string>

#include "formats/support/byte_reader.h"
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

TEST(FileIo, ReadingAFifoFailsInsteadOfWaitingForAWriter) {
  std::string path = ::testing::TempDir() + "lodbake_file_io_fifo_in";
  ::unlink(path.c_str());
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  Result<Bytes> r = read_file(path);  // blocked forever before the fix
  ::unlink(path.c_str());
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kIo);
  EXPECT_EQ(r.status().message(), "not a regular file");
}

TEST(FileIo, WritingOverAFifoOrAFolderIsRefusedAndLeavesItInPlace) {
  std::string fifo = ::testing::TempDir() + "lodbake_file_io_fifo_out";
  ::unlink(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  Status s = write_file_atomic(fifo, std::string("x"));
  struct stat st {};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));  // not replaced by a regular file
  ::unlink(fifo.c_str());
  EXPECT_EQ(s.kind(), ErrorKind::kIo);
  EXPECT_NE(s.message().find("not a regular file"), std::string::npos) << s.message();

  std::string folder = ::testing::TempDir() + "lodbake_file_io_folder_out";
  ::mkdir(folder.c_str(), 0700);
  s = write_file_atomic(folder, std::string("x"));
  EXPECT_EQ(s.kind(), ErrorKind::kIo);
  EXPECT_EQ(s.message(), "is a directory");
  ASSERT_EQ(::stat(folder.c_str(), &st), 0);
  EXPECT_TRUE(S_ISDIR(st.st_mode));
}

bool exists(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0;
}

TEST(FileIo, StagedOutputsAppearOnlyOnCommit) {
  std::string a = ::testing::TempDir() + "lodbake_staged_a.bin";
  std::string b = ::testing::TempDir() + "lodbake_staged_b.bin";
  ::unlink(a.c_str());
  ::unlink(b.c_str());
  StagedOutputs outputs;
  ASSERT_TRUE(outputs.stage(a, Bytes{1, 2, 3}).is_ok());
  ASSERT_TRUE(outputs.stage(b, Bytes{4}).is_ok());
  EXPECT_FALSE(exists(a));
  EXPECT_FALSE(exists(b));
  ASSERT_TRUE(outputs.commit().is_ok());
  Result<Bytes> back = read_file(a);
  ASSERT_TRUE(back.is_ok());
  EXPECT_EQ(back.value(), (Bytes{1, 2, 3}));
  EXPECT_TRUE(exists(b));
}

TEST(FileIo, StagedOutputsNotCommittedLeaveNothing) {
  std::string a = ::testing::TempDir() + "lodbake_staged_kept.bin";
  ASSERT_TRUE(write_file_atomic(a, std::string("old")).is_ok());
  {
    StagedOutputs outputs;
    ASSERT_TRUE(outputs.stage(a, Bytes{9}).is_ok());
    // The second output cannot be written: the run fails before commit().
    Status s = outputs.stage("/nonexistent/lodbake/out.lbk", Bytes{1});
    EXPECT_EQ(s.kind(), ErrorKind::kIo);
  }
  Result<Bytes> back = read_file(a);  // the earlier file, untouched
  ASSERT_TRUE(back.is_ok());
  EXPECT_EQ(std::string(back.value().begin(), back.value().end()), "old");
}

TEST(ByteReader, ReadsBothEndiansAndStopsAtTheEnd) {
  const uint8_t bytes[] = {0x01, 0x02, 0x03, 0x04, 0x05};
  ByteReader reader(bytes, sizeof(bytes));
  uint32_t little = 0;
  ASSERT_TRUE(reader.read(&little));
  EXPECT_EQ(little, 0x04030201u);
  uint32_t more = 0;
  EXPECT_FALSE(reader.read(&more));  // only one byte left
  EXPECT_EQ(reader.position(), 4u);
  ASSERT_TRUE(reader.seek(0));
  uint16_t big = 0;
  ASSERT_TRUE(reader.read(&big, Endian::kBig));
  EXPECT_EQ(big, 0x0102u);
  EXPECT_FALSE(reader.seek(6));
  EXPECT_FALSE(reader.skip(4));
  EXPECT_TRUE(reader.skip(3));
  EXPECT_TRUE(reader.at_end());
}

TEST(ByteWriter, WritesLittleEndian) {
  std::vector<uint8_t> out;
  ByteWriter writer(&out);
  writer.write<uint32_t>(0x0A0B0C0Du);
  writer.write<float>(1.0f);
  ASSERT_EQ(out.size(), 8u);
  EXPECT_EQ(out[0], 0x0D);
  EXPECT_EQ(out[3], 0x0A);
  ByteReader reader(out.data(), out.size());
  uint32_t a = 0;
  float b = 0;
  ASSERT_TRUE(reader.read(&a));
  ASSERT_TRUE(reader.read(&b));
  EXPECT_EQ(a, 0x0A0B0C0Du);
  EXPECT_EQ(b, 1.0f);
}

}  // namespace
}  // namespace lodbake
