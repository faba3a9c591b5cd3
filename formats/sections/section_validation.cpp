#include "formats/sections/section_validation.h"

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/meta.h"

namespace lodbake {
namespace {

// META's counts, when present, must agree with the sections they describe.
void check_meta_counts(const MetaSection& meta, const BaseSummary& base,
                       std::vector<SectionFinding>* findings) {
  auto expect = [&](const char* key, uint64_t actual) {
    auto it = meta.counts.find(key);
    if (it != meta.counts.end() && it->second != actual) {
      findings->push_back({kMetaTag, std::string("counts.") + key + " is " +
                                         std::to_string(it->second) + " but BASE holds " +
                                         std::to_string(actual)});
    }
  };
  expect("vertices", base.vertex_count);
  expect("triangles", base.triangle_count);
}

}  // namespace

std::vector<SectionFinding> validate_sections(const Container& container) {
  std::vector<SectionFinding> findings;
  std::optional<MetaSection> meta;
  std::optional<BaseSummary> base;
  for (const Section& section : container.sections) {
    if (section.tag() == kMetaTag) {
      Result<MetaSection> decoded = decode_meta(section.data, section.size);
      if (decoded.is_ok()) {
        meta = std::move(decoded).value();
      } else {
        findings.push_back({kMetaTag, decoded.status().message()});
      }
    } else if (section.tag() == kBaseTag) {
      for (std::string& finding : validate_base_payload(section.data, section.size))
        findings.push_back({kBaseTag, std::move(finding)});
      Result<BaseSummary> summary = read_base_summary(section.data, section.size);
      if (summary.is_ok()) base = summary.value();
    }
  }
  if (meta && base) check_meta_counts(*meta, *base, &findings);
  return findings;
}

}  // namespace lodbake
