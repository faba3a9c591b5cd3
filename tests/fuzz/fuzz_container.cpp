// Fuzz target for the container: strict reader, lenient lister, and the
// decoders of every section found (VSPL against the file's BASE when that
// decodes), and the deep cross-section validation of valid files.
// Invariants: the lister reports exactly the strict reader's verdict; a
// valid file is canonical (re-writing its sections reproduces it byte for
// byte); section round trips hold.
#include <cstdint>
#include <cstring>
#include <optional>
#include <utility>

#include "formats/container/container_layout.h"
#include "formats/container/container_listing.h"
#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/section_payloads.h"
#include "formats/sections/section_validation.h"
#include "tests/fuzz/fuzz_section_checks.h"

using namespace lodbake;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Result<Container> container = read_container(data, size);
  ContainerListing listing = list_container(data, size);
  fuzz::require(listing.status.code() == (container.is_ok() ? 0 : container.status().code()),
                "listing and reader disagree");

  std::optional<TriangleMesh> base;
  for (const SectionListing& section : listing.sections) {
    if (section.data == nullptr) continue;
    if (section.entry.tag == kMetaTag) fuzz::check_meta_payload(section.data, section.size);
    if (section.entry.tag == kBaseTag) {
      fuzz::check_base_payload(section.data, section.size);
      Result<TriangleMesh> mesh = decode_base(section.data, section.size);
      if (mesh.is_ok()) base = std::move(mesh).value();
    }
  }
  for (const SectionListing& section : listing.sections) {
    if (section.data == nullptr || section.entry.tag != kVsplTag) continue;
    fuzz::check_vspl_payload(section.data, section.size, base ? &*base : nullptr);
  }

  if (container.is_ok()) {
    fuzz::require(listing.table_complete && listing.table_crc_ok, "valid file, broken listing");
    ContainerWriter writer;
    for (const Section& section : container.value().sections) {
      fuzz::require(
          writer
              .add_stored_section(section.tag(), Bytes(section.data, section.data + section.size),
                                  static_cast<SectionCodec>(section.entry.codec),
                                  section.entry.decoded_size, section.required(), section.group())
              .is_ok(),
          "valid file has a section the writer refuses");
    }
    // Coded sections (compact VSPL, Draco BASE) decode to raw payloads,
    // which the section checks then see like any other.
    Container decoded = container.value();
    std::vector<Bytes> storage;
    if (decode_section_codecs(&decoded, &storage).is_ok()) {
      for (const Section& section : decoded.sections) {
        if (section.entry.codec == 0) continue;
        if (section.tag() == kBaseTag) fuzz::check_base_payload(section.data, section.size);
      }
      (void)validate_sections(decoded);
    }
    Result<Bytes> rewritten = writer.finish();
    fuzz::require(rewritten.is_ok() && rewritten.value().size() == size,
                  "valid container is not canonical");
    // The writer writes the lowest minor version the sections need; a valid
    // file may name a newer one (a 1.1 file with one group).
    ContainerHeader header = decode_header(rewritten.value().data());
    fuzz::require(header.minor <= container.value().header.minor, "writer needs a newer version");
    header.minor = container.value().header.minor;
    encode_header(header, rewritten.value().data());
    fuzz::require(std::memcmp(rewritten.value().data(), data, size) == 0,
                  "valid container is not canonical");
  }
  return 0;
}
