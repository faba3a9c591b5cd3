// Fuzz target for a bare SETS payload: summary and decode agree, what decodes
// round-trips through the encoder, validation never crashes, and recovery
// (lib/strips) on any decoded graph fails cleanly or, on a graph that
// validates, succeeds with coherent recovery equal to fresh recovery.
#include <cstdint>

#include "formats/sections/sets.h"
#include "lib/strips/sets_recovery.h"
#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  using namespace lodbake::fuzz;
  Result<SetsSummary> summary = read_sets_summary(data, size);
  Result<SetsGraph> graph = decode_sets(data, size);
  if (!graph.is_ok()) {
    require_decode_error(graph.status(), "SETS decode error without LBK-E023");
    return 0;
  }
  const SetsGraph& g = graph.value();
  require(summary.is_ok(), "SETS decodes but its summary does not");
  require(summary.value().node_count == g.node_count(), "summary node count");
  Result<Bytes> again = encode_sets(g);
  require(again.is_ok(), "decoded graph does not encode");
  Result<SetsGraph> redecoded = decode_sets(again.value().data(), again.value().size());
  require(redecoded.is_ok() && redecoded.value() == g, "SETS round trip");

  const bool valid = validate_sets(g).empty();
  Result<StripRecovery> fresh = StripRecovery::create(g);
  Result<StripRecovery> coherent = StripRecovery::create(g);
  if (valid) require(fresh.is_ok() && coherent.is_ok(), "valid graph refused by recovery");
  if (!fresh.is_ok() || !coherent.is_ok()) return 0;
  // A few LoDs down and back up; bounded work for any input.
  const uint32_t count = g.lod_count;
  const uint32_t step = count / 16 + 1;
  for (int pass = 0; pass < 2; ++pass) {
    for (uint32_t i = 0; i < count; i += step) {
      const uint32_t lod = pass == 0 ? i : count - 1 - i;
      const bool a = fresh.value().recover(lod).is_ok();
      const bool b = coherent.value().recover_coherent(lod).is_ok();
      if (valid) {
        require(a && b, "valid graph fails to recover");
        require(fresh.value().to_strips() == coherent.value().to_strips(),
                "coherent recovery differs from fresh");
      }
      if (!a || !b) return 0;
    }
  }
  return 0;
}
