#include "lib/meshio/ply_stream_reader.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "lib/meshio/text_scanner.h"

namespace lodbake {
namespace {

// The header is read from a prefix of the file: no real header is longer.
constexpr size_t kMaxHeaderBytes = size_t{1} << 20;
constexpr size_t kBufferBytes = size_t{1} << 20;

// Values from the body, binary (either byte order) or ASCII tokens, through
// one fixed buffer.
class StreamSource {
 public:
  StreamSource(std::istream* in, PlyFormat format) : in_(in), format_(format) {
    buffer_.resize(kBufferBytes);
  }

  bool read_double(PlyType type, double* out) {
    if (format_ == PlyFormat::kAscii) {
      if (!next_token()) return false;
      if (ply_type_is_integer(type)) {
        int64_t i = 0;
        if (!token_int(type, &i)) return false;
        *out = static_cast<double>(i);
        return true;
      }
      // The in-memory reader's parsers (lib/meshio/text_scanner.h), so that
      // both read the same values: a float32 value rounded once to float
      // (not through double), and no spelling one takes that the other
      // refuses (strtod took hex).
      if (type == PlyType::kFloat32) {
        float f = 0;
        if (parse_float(token_, &f) != NumberStatus::kOk) return false;
        *out = f;
        return true;
      }
      return parse_double(token_, out) == NumberStatus::kOk;
    }
    switch (type) {
      case PlyType::kFloat32: {
        float f;
        if (!read_raw(&f, 4)) return false;
        *out = f;
        return true;
      }
      case PlyType::kFloat64:
        return read_raw(out, 8);
      default: {
        int64_t i = 0;
        if (!read_int(type, &i)) return false;
        *out = static_cast<double>(i);
        return true;
      }
    }
  }

  // An integer-typed value (plan_ply() gives lists integer types only).
  bool read_int(PlyType type, int64_t* out) {
    if (format_ == PlyFormat::kAscii) return next_token() && token_int(type, out);
    switch (type) {
      case PlyType::kInt8: {
        int8_t v;
        if (!read_raw(&v, 1)) return false;
        *out = v;
        return true;
      }
      case PlyType::kUint8: {
        uint8_t v;
        if (!read_raw(&v, 1)) return false;
        *out = v;
        return true;
      }
      case PlyType::kInt16: {
        int16_t v;
        if (!read_raw(&v, 2)) return false;
        *out = v;
        return true;
      }
      case PlyType::kUint16: {
        uint16_t v;
        if (!read_raw(&v, 2)) return false;
        *out = v;
        return true;
      }
      case PlyType::kInt32: {
        int32_t v;
        if (!read_raw(&v, 4)) return false;
        *out = v;
        return true;
      }
      case PlyType::kUint32: {
        uint32_t v;
        if (!read_raw(&v, 4)) return false;
        *out = v;
        return true;
      }
      default:
        return false;
    }
  }

 private:
  bool fill() {
    if (in_->eof() || in_->fail()) return false;
    in_->read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(kBufferBytes));
    end_ = static_cast<size_t>(in_->gcount());
    pos_ = 0;
    return end_ > 0;
  }

  // `n` bytes in the file's byte order, into a host value.
  bool read_raw(void* out, size_t n) {
    uint8_t bytes[8];
    for (size_t k = 0; k < n; ++k) {
      if (pos_ == end_ && !fill()) return false;
      bytes[k] = buffer_[pos_++];
    }
    const bool swap = (format_ == PlyFormat::kBinaryBigEndian) == kHostLittle;
    if (swap) {
      for (size_t k = 0; k < n / 2; ++k)
        std::swap(bytes[k], bytes[n - 1 - k]);
    }
    std::memcpy(out, bytes, n);
    return true;
  }

  bool next_token() {
    token_.clear();
    for (;;) {
      if (pos_ == end_ && !fill()) return !token_.empty();
      const char c = static_cast<char>(buffer_[pos_]);
      const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
      if (space) {
        ++pos_;
        if (!token_.empty()) return true;
        continue;
      }
      // A token longer than any number is not one.
      if (token_.size() > 64) return false;
      token_.push_back(c);
      ++pos_;
    }
  }

  bool token_int(PlyType type, int64_t* out) const {
    int64_t v = 0;
    if (parse_int64(token_, &v) != NumberStatus::kOk) return false;
    int64_t lo = 0, hi = 0;
    switch (type) {
      case PlyType::kInt8:
        lo = INT8_MIN, hi = INT8_MAX;
        break;
      case PlyType::kUint8:
        lo = 0, hi = UINT8_MAX;
        break;
      case PlyType::kInt16:
        lo = INT16_MIN, hi = INT16_MAX;
        break;
      case PlyType::kUint16:
        lo = 0, hi = UINT16_MAX;
        break;
      case PlyType::kInt32:
        lo = INT32_MIN, hi = INT32_MAX;
        break;
      case PlyType::kUint32:
        lo = 0, hi = UINT32_MAX;
        break;
      default:
        return false;
    }
    if (v < lo || v > hi) return false;
    *out = v;
    return true;
  }

  static constexpr bool kHostLittle = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;
  std::istream* in_;
  PlyFormat format_;
  std::vector<uint8_t> buffer_;
  size_t pos_ = 0, end_ = 0;
  std::string token_;
};

std::string item(const char* kind, uint64_t i) {
  return std::string(kind) + " " + std::to_string(i);
}

}  // namespace

Result<std::unique_ptr<PlyStreamReader>> PlyStreamReader::open(std::istream* in, uint64_t size) {
  std::vector<uint8_t> prefix(static_cast<size_t>(std::min<uint64_t>(size, kMaxHeaderBytes)));
  in->clear();
  in->seekg(0);
  in->read(reinterpret_cast<char*>(prefix.data()), static_cast<std::streamsize>(prefix.size()));
  if (static_cast<size_t>(in->gcount()) != prefix.size()) return io_error("cannot read the header");
  LODBAKE_ASSIGN_OR_RETURN(PlyHeader header, parse_ply_header(prefix.data(), prefix.size()));
  std::unique_ptr<PlyStreamReader> reader(new PlyStreamReader(in, size, std::move(header)));
  ImportReport notes;  // ignored properties: this reader keeps positions only anyway
  LODBAKE_ASSIGN_OR_RETURN(reader->plan_,
                           plan_ply(reader->header_, size - reader->header_.body_offset, &notes));
  for (const PlyElementPlan& e : reader->plan_.elements) {
    if (e.role == PlyRole::kStrips)
      return unsupported("element '" + e.element->name +
                         "' holds triangle strips, which --memory-limit does not read");
  }
  return reader;
}

Status PlyStreamReader::for_each_vertex(const std::function<void(uint64_t, const float*)>& vertex) {
  return pass(Want::kVertices, vertex, nullptr);
}

Status PlyStreamReader::for_each_triangle(
    const std::function<Status(uint64_t, const uint32_t*)>& triangle) {
  return pass(Want::kFaces, nullptr, triangle);
}

Status PlyStreamReader::pass(Want want, const std::function<void(uint64_t, const float*)>& vertex,
                             const std::function<Status(uint64_t, const uint32_t*)>& triangle) {
  in_->clear();
  in_->seekg(static_cast<std::streamoff>(header_.body_offset));
  if (!*in_) return io_error("cannot seek to the body");
  StreamSource src(in_, header_.format);
  const uint64_t vertices = plan_.vertex_count;
  for (const PlyElementPlan& e : plan_.elements) {
    const PlyElement& element = *e.element;
    const bool vertex_element = e.role == PlyRole::kVertex;
    const bool face_element = e.role == PlyRole::kFace;
    for (uint64_t i = 0; i < element.count; ++i) {
      float xyz[3] = {0, 0, 0};
      uint32_t corners[3] = {0, 0, 0};
      for (size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& p = element.properties[k];
        const uint8_t slot = e.slots[k];
        if (p.is_list) {
          int64_t n = 0;
          if (!src.read_int(p.count_type, &n) || n < 0)
            return invalid_input("the body ends or is malformed in the list of " +
                                 item(element.name.c_str(), i));
          const bool indices = face_element && slot == kSlotIndices;
          for (int64_t j = 0; j < n; ++j) {
            int64_t index = 0;
            if (!src.read_int(p.type, &index))
              return invalid_input("the body ends or is malformed in the list of " +
                                   item(element.name.c_str(), i));
            if (!indices) continue;
            // Read whole first: a list running past the end is a broken
            // file, not a polygon.
            if (n != 3) {
              if (j + 1 == n)
                return unsupported(item("face", i) + " has " + std::to_string(n) +
                                   " vertices: --memory-limit reads triangles only");
              continue;
            }
            if (index < 0 || static_cast<uint64_t>(index) >= vertices)
              return invalid_input(item("face", i) + ": vertex index " + std::to_string(index) +
                                   " out of range (" + std::to_string(vertices) + " vertices)");
            corners[j] = static_cast<uint32_t>(index);
          }
          continue;
        }
        double value = 0;
        if (!src.read_double(p.type, &value))
          return invalid_input("the body ends or is malformed in " + item(element.name.c_str(), i) +
                               " (property '" + p.name + "')");
        if (vertex_element && slot <= kSlotZ) {
          xyz[slot] = static_cast<float>(value);
          if (!std::isfinite(xyz[slot]))
            return invalid_input(item("vertex", i) + " has a non-finite coordinate");
        }
      }
      if (vertex_element && want == Want::kVertices) vertex(i, xyz);
      if (face_element && want == Want::kFaces) LODBAKE_RETURN_IF_ERROR(triangle(i, corners));
    }
  }
  return Status::ok();
}

}  // namespace lodbake
