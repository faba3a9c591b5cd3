// Helpers shared by the mesh writers: a check that a TriangleMesh is
// consistent before it is written (a writer must never emit indices that
// point nowhere), and a text builder that prints floats in their shortest
// round-trip form.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

/// kInvalidInput when an index of `mesh` is out of range, an attribute's
/// value array does not match its binding, or a count exceeds 32-bit indices.
Status check_writable(const TriangleMesh& mesh);

/// Appends text to a byte buffer without iostreams or locales.
class TextOut {
 public:
  explicit TextOut(Bytes* out) : out_(out) {}

  void text(std::string_view s) { out_->insert(out_->end(), s.begin(), s.end()); }
  void ch(char c) { out_->push_back(static_cast<uint8_t>(c)); }
  /// The shortest decimal that reads back as exactly `f` (std::to_chars).
  void real(float f) {
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof(buf), f);
    out_->insert(out_->end(), buf, r.ptr);
  }
  /// `count` floats as real() prints them, separated by single spaces.
  void reals(const float* values, size_t count) {
    for (size_t i = 0; i < count; ++i) {
      if (i != 0) ch(' ');
      real(values[i]);
    }
  }
  void integer(uint64_t v) {
    char buf[24];
    auto r = std::to_chars(buf, buf + sizeof(buf), v);
    out_->insert(out_->end(), buf, r.ptr);
  }

 private:
  Bytes* out_;
};

}  // namespace lodbake
