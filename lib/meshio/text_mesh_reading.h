// The steps around a text mesh reader that every text format shares: the
// bytes go through prepare_text() (byte-order marks, UTF-16, NUL bytes) with
// its note recorded, and allocation failure is caught at the entry point so
// that no exception crosses the lib/ API.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/meshio/import_report.h"
#include "lib/meshio/text_scanner.h"

namespace lodbake {

/// prepare_text() that records its decoding note (if any) in `report`.
/// On success `*data` and `*size` describe the text to scan; `storage` must
/// outlive it. \pre `report` is not null.
inline Status prepare_text_into_report(const uint8_t** data, size_t* size,
                                       std::vector<uint8_t>* storage, ImportReport* report) {
  std::string note;
  LODBAKE_RETURN_IF_ERROR(prepare_text(data, size, storage, &note));
  if (!note.empty()) report->notes.push_back(note);
  return Status::ok();
}

/// Prepares the text, then returns `Reader(data, size, report, extra...).read()`.
/// `report` may be null. std::bad_alloc and std::length_error become
/// "out of memory while reading the <format> file" (kRuntime).
template <typename Reader, typename... Extra>
Result<TriangleMesh> read_text_mesh(const uint8_t* data, size_t size, ImportReport* report,
                                    const char* format, Extra... extra) {
  ImportReport local;
  if (report == nullptr) report = &local;
  try {
    std::vector<uint8_t> decoded;
    LODBAKE_RETURN_IF_ERROR(prepare_text_into_report(&data, &size, &decoded, report));
    Reader reader(data, size, report, extra...);
    return reader.read();
  } catch (const std::bad_alloc&) {
    return runtime_error(std::string("out of memory while reading the ") + format + " file");
  } catch (const std::length_error&) {
    return runtime_error(std::string("out of memory while reading the ") + format + " file");
  }
}

}  // namespace lodbake
