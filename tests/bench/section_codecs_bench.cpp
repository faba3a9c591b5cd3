// Encode and decode times of every coded section of lodbake containers
// (issue 7: "encode and decode times" in docs/benchmarks.md, "Every section
// kind"): for each section stored with a codec, the median wall time of
// recoding its raw payload into the stored bytes (encode) and of turning
// the stored bytes back into the raw payload (decode), the way lodbake-pack
// and every reader do. tests/bench/pack_sections.sh runs it on the
// containers lodbake-pack writes.
//
//   bench_section_codecs [--runs N] FILE.lbk...
//
// One line per section: FILE TAG CODEC STORED_BYTES RAW_BYTES ENCODE_S
// DECODE_S (raw sections: 0 0). A compact re-encoding must give the stored
// bytes again (checked); a Draco BASE is re-encoded from its decoded mesh
// with the stored options, which times the same work but need not give the
// same bytes (the positions were quantized once already).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "formats/container/container_layout.h"
#include "formats/container/container_reader.h"
#include "formats/container/section_codecs.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/compact_sections.h"
#include "formats/sections/draco_codec.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/vspl_compact.h"
#include "formats/support/file_io.h"
#include "tests/bench/bench_support.h"

namespace lodbake {
namespace {

int fail(const std::string& what, const Status& status) {
  std::fprintf(stderr, "bench_section_codecs: %s: %s\n", what.c_str(), status.message().c_str());
  return 4;
}

int run_file(const std::string& path, int runs) {
  Result<Bytes> file = read_file(path);
  if (!file.is_ok()) return fail(path, file.status());
  Result<Container> stored = read_container(file.value().data(), file.value().size());
  if (!stored.is_ok()) return fail(path, stored.status());
  Result<Container> decoded = read_container(file.value().data(), file.value().size());
  std::vector<Bytes> storage;
  const Status codecs = decode_section_codecs(&decoded.value(), &storage);
  if (!codecs.is_ok()) return fail(path, codecs);
  TriangleMesh base;
  if (const Section* b = decoded.value().find(kBaseTag)) {
    Result<TriangleMesh> mesh = decode_base(b->data, b->size);
    if (!mesh.is_ok()) return fail(path, mesh.status());
    base = std::move(mesh).value();
  }
  for (size_t i = 0; i < stored.value().sections.size(); ++i) {
    const Section& s = stored.value().sections[i];
    const Section& raw = decoded.value().sections[i];
    const uint16_t codec = s.entry.codec;
    double encode = 0, decode = 0;
    bool ok = true;
    if (codec == static_cast<uint16_t>(SectionCodec::kCompact)) {
      // VSPL, FANH and STRP code against the decoded BASE, the others alone.
      auto encode_one = [&]() -> Result<Bytes> {
        if (s.tag() == kVsplTag) return encode_vspl_compact(raw.data, raw.size, base);
        if (has_base_compact_codec(s.tag()))
          return encode_section_compact(s.tag(), raw.data, raw.size, base);
        return encode_section_compact(s.tag(), raw.data, raw.size);
      };
      auto decode_one = [&]() -> Result<Bytes> {
        if (s.tag() == kVsplTag) return decode_vspl_compact(s.data, s.size, base);
        if (has_base_compact_codec(s.tag()))
          return decode_section_compact(s.tag(), s.data, s.size, base);
        return decode_section_compact(s.tag(), s.data, s.size);
      };
      encode = bench::median_seconds(runs, [&] {
        Result<Bytes> again = encode_one();
        ok = ok && again.is_ok() && again.value() == Bytes(s.data, s.data + s.size);
      });
      decode = bench::median_seconds(runs, [&] {
        Result<Bytes> back = decode_one();
        ok = ok && back.is_ok() && back.value() == Bytes(raw.data, raw.data + raw.size);
      });
    } else if (codec == static_cast<uint16_t>(SectionCodec::kDraco)) {
      Result<DracoOptions> options = read_draco_base_options(s.data, s.size);
      if (!options.is_ok()) return fail(path, options.status());
      encode = bench::median_seconds(
          runs, [&] { ok = ok && encode_base_draco(base, options.value()).is_ok(); });
      decode = bench::median_seconds(runs, [&] {
        Result<Bytes> back = decode_base_stored(s);
        ok = ok && back.is_ok() && back.value() == Bytes(raw.data, raw.data + raw.size);
      });
    }
    if (!ok) return fail(path + " " + s.tag(), invalid_input("a codec round trip differs"));
    std::printf("%s %s %s %llu %llu %.6f %.6f\n", path.c_str(), s.tag().c_str(),
                codec_name(codec) != nullptr ? codec_name(codec) : "?",
                static_cast<unsigned long long>(s.entry.stored_size),
                static_cast<unsigned long long>(s.entry.decoded_size), encode, decode);
  }
  return 0;
}

}  // namespace
}  // namespace lodbake

int main(int argc, char** argv) {
  int runs = 5;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
    } else {
      files.push_back(argv[i]);
    }
  }
  if (files.empty() || runs < 1) {
    std::fprintf(stderr, "usage: bench_section_codecs [--runs N] FILE.lbk...\n");
    return 1;
  }
  for (const std::string& file : files) {
    if (int code = lodbake::run_file(file, runs); code != 0) return code;
  }
  return 0;
}
