// Helpers for the OBJ, OFF and writer tests: reading the shared test data
// named by LODBAKE_SHARED_DATA (set by CTest) and parsing in-memory text.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "formats/support/file_io.h"
#include "lib/meshio/import_report.h"

namespace lodbake {
namespace testing_util {

inline Bytes shared_file(const std::string& relative) {
  const char* root = std::getenv("LODBAKE_SHARED_DATA");
  if (root == nullptr) {
    ADD_FAILURE() << "LODBAKE_SHARED_DATA is not set (run the tests through ctest)";
    return {};
  }
  Result<Bytes> bytes = read_file(std::string(root) + "/" + relative);
  EXPECT_TRUE(bytes.is_ok()) << relative << ": " << bytes.status().message();
  return bytes.is_ok() ? std::move(bytes).value() : Bytes{};
}

inline Bytes text_bytes(const std::string& text) {
  return Bytes(text.begin(), text.end());
}

inline bool has_note(const ImportReport& report, const std::string& text) {
  for (const std::string& note : report.notes) {
    if (note.find(text) != std::string::npos) return true;
  }
  return false;
}

inline std::string all_notes(const ImportReport& report) {
  std::string out;
  for (const std::string& note : report.notes)
    out += "\n  " + note;
  return out;
}

}  // namespace testing_util
}  // namespace lodbake
