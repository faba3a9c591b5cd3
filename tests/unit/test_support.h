// Helpers shared by the unit tests: environment lookups (CTest sets the
// variables, tests/CMakeLists.txt LODBAKE_TEST_ENV), reading files and the
// shared test data named by LODBAKE_SHARED_DATA, text as bytes, import-note
// matching and the error contract every lib/ and formats/ failure keeps.
// In-memory meshes for the check and repair tests are in test_meshes.h.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <initializer_list>
#include <string>

#include "formats/support/file_io.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {
namespace testing_util {

/// The value of environment variable `name`, or `fallback` when it is unset.
inline std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr ? value : fallback;
}

/// The value of environment variable `name`; a test failure and "" when it
/// is unset.
inline std::string env_or_fail(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr) {
    ADD_FAILURE() << name << " is not set (run the tests through ctest)";
    return "";
  }
  return value;
}

/// The bytes of the file at `path`; a test failure and no bytes when it
/// cannot be read.
inline Bytes read_bytes(const std::string& path) {
  Result<Bytes> bytes = read_file(path);
  EXPECT_TRUE(bytes.is_ok()) << path << ": " << bytes.status().message();
  return bytes.is_ok() ? std::move(bytes).value() : Bytes{};
}

/// The bytes of `relative` (e.g. "bad/hw_garbage.obj") under
/// LODBAKE_SHARED_DATA; a test failure and no bytes when that is unset or
/// the file cannot be read.
inline Bytes shared_file(const std::string& relative) {
  const std::string root = env_or_fail("LODBAKE_SHARED_DATA");
  if (root.empty()) return {};
  return read_bytes(root + "/" + relative);
}

inline Bytes text_bytes(const std::string& text) {
  return Bytes(text.begin(), text.end());
}

/// True when some note of `report` contains `text`.
inline bool has_note(const ImportReport& report, const std::string& text) {
  for (const std::string& note : report.notes) {
    if (note.find(text) != std::string::npos) return true;
  }
  return false;
}

/// The notes of `report`, one per line, for failure messages.
inline std::string all_notes(const ImportReport& report) {
  std::string out;
  for (const std::string& note : report.notes)
    out += "\n  " + note;
  return out;
}

/// `result` failed with `kind` and a message that contains `fragment` and
/// is one non-empty line.
template <typename T>
void expect_error(const Result<T>& result, ErrorKind kind, const std::string& fragment) {
  ASSERT_FALSE(result.is_ok()) << "expected an error containing: " << fragment;
  const std::string& message = result.status().message();
  EXPECT_EQ(result.status().kind(), kind) << message;
  EXPECT_NE(message.find(fragment), std::string::npos)
      << "message: " << message << "\nexpected fragment: " << fragment;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_FALSE(message.empty());
}

/// expect_error() for kInvalidInput, the kind of every malformed file.
template <typename T>
void expect_rejected(const Result<T>& result, const std::string& phrase) {
  expect_error(result, ErrorKind::kInvalidInput, phrase);
}

/// A file under LODBAKE_SHARED_DATA that a reader must reject, and a phrase
/// its message must contain.
struct BadFile {
  const char* file;
  const char* message;
};

/// expect_rejected(parse_shared(c.file), c.message) for each case.
template <typename ParseShared>
void expect_bad_files_rejected(std::initializer_list<BadFile> cases, ParseShared parse_shared) {
  for (const BadFile& c : cases) {
    SCOPED_TRACE(c.file);
    expect_rejected(parse_shared(c.file), c.message);
  }
}

/// `text` with its first `from` replaced by `to`; a test failure (and
/// `text` unchanged) when `from` does not occur.
inline std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  return text.replace(at, from.size(), to);
}

}  // namespace testing_util
}  // namespace lodbake
