// Container writer, strict reader and lenient lister: round trip, the exact
// layout, determinism, every error code from a crafted file, truncation at
// every length, every bit flip in header and table, appended bytes, and
// required versus optional unknown sections.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "formats/container/container_errors.h"
#include "formats/container/container_layout.h"
#include "formats/container/container_listing.h"
#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/support/crc32c.h"
#include "tests/unit/test_support.h"

namespace lodbake {
namespace {

using testing_util::text_bytes;

// META (optional, 13 bytes), BASE (required, 29 bytes), XTRA (optional,
// unknown, empty): odd sizes so the file has padding, an empty section, and
// one section of each flag.
Bytes sample_container() {
  ContainerWriter writer;
  EXPECT_TRUE(writer.add_section("META", text_bytes("{\"tool\":\"x\"}\n"), false).is_ok());
  Bytes base(29);
  for (size_t i = 0; i < base.size(); ++i)
    base[i] = static_cast<uint8_t>(i * 7 + 1);
  EXPECT_TRUE(writer.add_section("BASE", base, true).is_ok());
  EXPECT_TRUE(writer.add_section("XTRA", {}, false).is_ok());
  Result<Bytes> bytes = writer.finish();
  EXPECT_TRUE(bytes.is_ok());
  return bytes.value();
}

// Reads from an exact-size heap copy so that AddressSanitizer sees any read
// past the end.
Result<Container> read_copy(const Bytes& file, Bytes* keep) {
  *keep = file;
  keep->shrink_to_fit();
  return read_container(keep->data(), keep->size());
}

int error_code(const Bytes& file) {
  Bytes copy(file);
  Result<Container> result = read_container(copy.data(), copy.size());
  return result.is_ok() ? 0 : result.status().code();
}

// Rewrites the header with `header` (header CRC recomputed).
void put_header(Bytes* file, const ContainerHeader& header) {
  encode_header(header, file->data());
}

// Rewrites entry `index` of the table and recomputes the table and header CRCs.
void put_entry(Bytes* file, size_t index, const SectionEntry& entry) {
  ContainerHeader header = decode_header(file->data());
  encode_entry(entry, file->data() + header.table_offset + index * kTableEntrySize);
  header.table_crc32c =
      crc32c(file->data() + header.table_offset, header.section_count * kTableEntrySize);
  put_header(file, header);
}

SectionEntry entry_of(const Bytes& file, size_t index) {
  const ContainerHeader header = decode_header(file.data());
  return decode_entry(file.data() + header.table_offset + index * kTableEntrySize);
}

TEST(Container, RoundTrip) {
  const Bytes file = sample_container();
  Bytes keep;
  Result<Container> read = read_copy(file, &keep);
  ASSERT_TRUE(read.is_ok()) << read.status().message();
  const Container& c = read.value();
  EXPECT_EQ(c.header.major, 1);
  EXPECT_EQ(c.header.minor, 0);
  EXPECT_EQ(c.header.file_size, file.size());
  ASSERT_EQ(c.sections.size(), 3u);
  EXPECT_EQ(c.sections[0].tag(), "META");
  EXPECT_FALSE(c.sections[0].required());
  EXPECT_TRUE(c.sections[0].known);
  EXPECT_EQ(std::string(c.sections[0].data, c.sections[0].data + c.sections[0].size),
            "{\"tool\":\"x\"}\n");
  EXPECT_EQ(c.sections[1].tag(), "BASE");
  EXPECT_TRUE(c.sections[1].required());
  ASSERT_EQ(c.sections[1].size, 29u);
  for (size_t i = 0; i < 29; ++i)
    EXPECT_EQ(c.sections[1].data[i], static_cast<uint8_t>(i * 7 + 1));
  EXPECT_EQ(c.sections[2].tag(), "XTRA");
  EXPECT_FALSE(c.sections[2].known);  // unknown optional: accepted, marked unknown
  EXPECT_EQ(c.sections[2].size, 0u);
  EXPECT_EQ(c.find("BASE"), &c.sections[1]);
  EXPECT_EQ(c.find("NONE"), nullptr);
  ASSERT_TRUE(c.require("META").is_ok());
  Result<const Section*> missing = c.require("VSPL");
  ASSERT_FALSE(missing.is_ok());
  EXPECT_EQ(missing.status().code(), 24);
  EXPECT_EQ(missing.status().message(), "LBK-E024: the container has no VSPL section");
}

TEST(Container, ExactLayout) {
  ContainerWriter writer;
  ASSERT_TRUE(writer.add_section("TEST", text_bytes("abc"), true).is_ok());
  Result<Bytes> result = writer.finish();
  ASSERT_TRUE(result.is_ok());
  const Bytes& f = result.value();
  // 48 header + 3 payload + 5 padding + 40 table.
  ASSERT_EQ(f.size(), 96u);
  const uint8_t magic[8] = {0x89, 'L', 'B', 'K', '\r', '\n', 0x1A, '\n'};
  EXPECT_EQ(std::memcmp(f.data(), magic, 8), 0);
  auto u16 = [&](size_t at) { return static_cast<unsigned>(f[at] | f[at + 1] << 8); };
  auto u32 = [&](size_t at) {
    return static_cast<uint32_t>(f[at]) | static_cast<uint32_t>(f[at + 1]) << 8 |
           static_cast<uint32_t>(f[at + 2]) << 16 | static_cast<uint32_t>(f[at + 3]) << 24;
  };
  auto u64 = [&](size_t at) { return u32(at) | static_cast<uint64_t>(u32(at + 4)) << 32; };
  EXPECT_EQ(u16(8), 1u);    // major
  EXPECT_EQ(u16(10), 0u);   // minor
  EXPECT_EQ(u32(12), 0u);   // flags
  EXPECT_EQ(u64(16), 96u);  // file size
  EXPECT_EQ(u64(24), 56u);  // table offset
  EXPECT_EQ(u32(32), 1u);   // section count
  EXPECT_EQ(u32(36), crc32c(f.data() + 56, 40));
  EXPECT_EQ(u32(40), 0u);  // reserved
  EXPECT_EQ(u32(44), crc32c(f.data(), 44));
  EXPECT_EQ(std::string(f.begin() + 48, f.begin() + 51), "abc");
  for (size_t i = 51; i < 56; ++i)
    EXPECT_EQ(f[i], 0u);
  EXPECT_EQ(std::string(f.begin() + 56, f.begin() + 60), "TEST");
  EXPECT_EQ(u16(60), 0u);   // codec raw
  EXPECT_EQ(u16(62), 1u);   // flags: required
  EXPECT_EQ(u64(64), 48u);  // offset
  EXPECT_EQ(u64(72), 3u);   // stored size
  EXPECT_EQ(u64(80), 3u);   // decoded size
  EXPECT_EQ(u32(88), crc32c(f.data() + 48, 3));
  EXPECT_EQ(u32(92), 0u);  // reserved
}

TEST(Container, EmptyContainerIsJustAHeader) {
  Result<Bytes> result = ContainerWriter().finish();
  ASSERT_TRUE(result.is_ok());
  ASSERT_EQ(result.value().size(), kHeaderSize);
  Bytes keep;
  Result<Container> read = read_copy(result.value(), &keep);
  ASSERT_TRUE(read.is_ok()) << read.status().message();
  EXPECT_TRUE(read.value().sections.empty());
}

TEST(Container, WritesAreDeterministic) {
  const Bytes a = sample_container();
  const Bytes b = sample_container();
  EXPECT_EQ(a, b);
  ContainerWriter writer;
  ASSERT_TRUE(writer.add_section("BASE", text_bytes("payload"), true).is_ok());
  Result<Bytes> first = writer.finish();
  Result<Bytes> second = writer.finish();
  ASSERT_TRUE(first.is_ok() && second.is_ok());
  EXPECT_EQ(first.value(), second.value());
}

TEST(Container, FinishAndClearGivesTheSameBytesAndEmptiesTheWriter) {
  ContainerWriter writer;
  ASSERT_TRUE(writer.add_section("META", text_bytes("{\"tool\":\"x\"}\n"), false).is_ok());
  ASSERT_TRUE(writer.add_section("BASE", Bytes(29, 7), true).is_ok());
  ASSERT_TRUE(writer.add_section("XTRA", {}, false).is_ok());
  ASSERT_TRUE(writer.add_section("MORE", text_bytes("abc"), false, 1).is_ok());
  Result<Bytes> kept = writer.finish();
  Result<Bytes> cleared = writer.finish_and_clear();
  ASSERT_TRUE(kept.is_ok() && cleared.is_ok());
  EXPECT_EQ(kept.value(), cleared.value());
  EXPECT_EQ(writer.section_count(), 0u);
  // Cleared, so the same tags can be added again and give the same file.
  ASSERT_TRUE(writer.add_section("META", text_bytes("{\"tool\":\"x\"}\n"), false).is_ok());
  ASSERT_TRUE(writer.add_section("BASE", Bytes(29, 7), true).is_ok());
  ASSERT_TRUE(writer.add_section("XTRA", {}, false).is_ok());
  ASSERT_TRUE(writer.add_section("MORE", text_bytes("abc"), false, 1).is_ok());
  Result<Bytes> again = writer.finish_and_clear();
  ASSERT_TRUE(again.is_ok());
  EXPECT_EQ(again.value(), kept.value());
}

TEST(Container, WriterRefusesBadAndDuplicateTags) {
  ContainerWriter writer;
  Status bad = writer.add_section("AB C", {}, false);
  EXPECT_EQ(bad.code(), 16);
  EXPECT_EQ(writer.add_section("ABC", {}, false).code(), 16);
  EXPECT_EQ(writer.add_section(std::string("AB\0C", 4), {}, false).code(), 16);
  ASSERT_TRUE(writer.add_section("ABCD", {}, false).is_ok());
  Status dup = writer.add_section("ABCD", {}, true);
  EXPECT_EQ(dup.code(), 17);
  EXPECT_EQ(dup.message(), "LBK-E017: section ABCD was already added");
  EXPECT_EQ(writer.section_count(), 1u);
}

// Groups (format 1.1): one tag per group, groups in order, and the lowest
// version that holds them.
TEST(Container, GroupsRoundTripAndNeedFormat11) {
  ContainerWriter writer;
  ASSERT_TRUE(writer.add_section("ABCD", text_bytes("a"), true).is_ok());
  EXPECT_EQ(writer.add_section("WXYZ", {}, false, 2).code(), 25);
  ASSERT_TRUE(writer.add_section("ABCD", text_bytes("b"), true, 1).is_ok());
  EXPECT_EQ(writer.add_section("ABCD", {}, false, 1).code(), 17);
  EXPECT_EQ(writer.add_section("WXYZ", {}, false, 0).code(), 25);
  ASSERT_TRUE(writer.add_section("WXYZ", text_bytes("c"), false, 1).is_ok());
  const Bytes file = writer.finish().value();
  EXPECT_EQ(decode_header(file.data()).minor, 1);
  Result<Container> read = read_container(file.data(), file.size(), {"ABCD", "WXYZ"});
  ASSERT_TRUE(read.is_ok()) << read.status().message();
  const Container& c = read.value();
  EXPECT_EQ(c.group_count(), 2u);
  ASSERT_NE(c.find("ABCD", 1), nullptr);
  EXPECT_EQ(std::string(c.find("ABCD", 1)->data, c.find("ABCD", 1)->data + 1), "b");
  EXPECT_EQ(std::string(c.find("ABCD")->data, c.find("ABCD")->data + 1), "a");
  EXPECT_EQ(c.find("WXYZ"), nullptr);
  EXPECT_EQ(c.require("WXYZ", 0).status().message(), "LBK-E024: the container has no WXYZ section");
  EXPECT_EQ(c.require("QQQQ", 1).status().message(), "LBK-E024: group 1 has no QQQQ section");

  // Without groups the writer still writes 1.0.
  ContainerWriter plain;
  ASSERT_TRUE(plain.add_section("ABCD", text_bytes("a"), true).is_ok());
  EXPECT_EQ(decode_header(plain.finish().value().data()).minor, 0);
}

TEST(Container, WriterTakesKnownTagsFlagsFromTheRegistry) {
  // docs/format.md section 4: only BASE is required.
  for (const SectionKind& kind : known_section_kinds())
    EXPECT_EQ(section_required(kind.tag), std::string(kind.tag) == kBaseTag) << kind.tag;
  EXPECT_FALSE(section_required("xTRA"));

  ContainerWriter writer;
  for (const SectionKind& kind : known_section_kinds())
    ASSERT_TRUE(writer.add_known_section(kind.tag, text_bytes(kind.tag)).is_ok()) << kind.tag;
  Status unknown = writer.add_known_section("xTRA", text_bytes("x"));
  EXPECT_EQ(unknown.kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(unknown.message(), "section xTRA is not a known tag: its required flag must be given");
  Result<Bytes> file = writer.finish();
  ASSERT_TRUE(file.is_ok());
  Result<Container> c = read_container(file.value().data(), file.value().size());
  ASSERT_TRUE(c.is_ok()) << c.status().message();
  ASSERT_EQ(c.value().sections.size(), known_section_kinds().size());
  for (const Section& section : c.value().sections)
    EXPECT_EQ(section.required(), section_required(section.tag())) << section.tag();
}

TEST(Container, TruncationAtEveryLength) {
  const Bytes file = sample_container();
  for (size_t length = 0; length < file.size(); ++length) {
    Bytes prefix(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(length));
    prefix.shrink_to_fit();
    Result<Container> read = read_container(prefix.empty() ? nullptr : prefix.data(), length);
    ASSERT_FALSE(read.is_ok()) << "accepted a prefix of " << length << " bytes";
    EXPECT_EQ(read.status().kind(), ErrorKind::kInvalidInput);
    EXPECT_EQ(read.status().code(), length < kHeaderSize ? 1 : 7) << "length " << length;
    ContainerListing listing = list_container(prefix.empty() ? nullptr : prefix.data(), length);
    EXPECT_EQ(listing.status.code(), read.status().code());
    EXPECT_EQ(listing.header_read, length >= kHeaderSize);
  }
  Bytes keep;
  const std::string message =
      read_copy(Bytes(file.begin(), file.begin() + 100), &keep).status().message();
  EXPECT_EQ(message, "LBK-E007: file is truncated: header says " + std::to_string(file.size()) +
                         " bytes, file has 100");
}

TEST(Container, EveryBitFlipInHeaderAndTableIsAnError) {
  const Bytes file = sample_container();
  const ContainerHeader header = decode_header(file.data());
  std::vector<size_t> positions;
  for (size_t i = 0; i < kHeaderSize; ++i)
    positions.push_back(i);
  for (size_t i = header.table_offset; i < file.size(); ++i)
    positions.push_back(i);
  for (size_t byte : positions) {
    for (int bit = 0; bit < 8; ++bit) {
      Bytes flipped = file;
      flipped[byte] ^= static_cast<uint8_t>(1u << bit);
      const int code = error_code(flipped);
      int expected;
      if (byte < 8) {
        expected = 2;  // magic
      } else if (byte < 10) {
        expected = 4;  // major version: checked before the header CRC
      } else if (byte < kHeaderSize) {
        expected = 3;  // header checksum
      } else {
        expected = 11;  // table checksum
      }
      ASSERT_EQ(code, expected) << "byte " << byte << " bit " << bit;
      ContainerListing listing = list_container(flipped.data(), flipped.size());
      EXPECT_EQ(listing.status.code(), expected);
    }
  }
}

TEST(Container, EveryBitFlipInSectionsIsAnError) {
  const Bytes file = sample_container();
  for (size_t byte = kHeaderSize; byte < decode_header(file.data()).table_offset; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      Bytes flipped = file;
      flipped[byte] ^= static_cast<uint8_t>(1u << bit);
      const int code = error_code(flipped);
      // Inside a section: its checksum; in the padding: nonzero padding.
      ASSERT_TRUE(code == 19 || code == 15)
          << "byte " << byte << " bit " << bit << " code " << code;
    }
  }
}

TEST(Container, AppendedBytesAreTrailingBytes) {
  const Bytes file = sample_container();
  for (size_t extra = 1; extra <= 17; ++extra) {
    Bytes longer = file;
    longer.resize(file.size() + extra, 0);
    Bytes keep;
    Result<Container> read = read_copy(longer, &keep);
    ASSERT_FALSE(read.is_ok());
    EXPECT_EQ(read.status().code(), 8);
    EXPECT_EQ(read.status().message(), "LBK-E008: " + std::to_string(extra) +
                                           " trailing bytes: header says " +
                                           std::to_string(file.size()) + " bytes, file has " +
                                           std::to_string(file.size() + extra));
  }
}

TEST(Container, UnknownRequiredSectionIsRefusedUnknownOptionalIsSkipped) {
  ContainerWriter writer;
  ASSERT_TRUE(writer.add_section("BASE", text_bytes("b"), true).is_ok());
  ASSERT_TRUE(writer.add_section("ZZZZ", text_bytes("z"), true).is_ok());
  Bytes file = writer.finish().value();
  Result<Container> refused = read_container(file.data(), file.size());
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.status().code(), 22);
  EXPECT_EQ(refused.status().kind(), ErrorKind::kInvalidInput);
  EXPECT_EQ(refused.status().message(),
            "LBK-E022: section ZZZZ is marked required but this reader does not know it");

  // The same file is fine for a reader that knows ZZZZ ...
  Result<Container> known = read_container(file.data(), file.size(), {"BASE", "ZZZZ"});
  ASSERT_TRUE(known.is_ok()) << known.status().message();
  EXPECT_TRUE(known.value().sections[1].known);

  // ... and with the flag cleared, for any reader.
  SectionEntry entry = entry_of(file, 1);
  entry.flags = 0;
  put_entry(&file, 1, entry);
  Result<Container> skipped = read_container(file.data(), file.size());
  ASSERT_TRUE(skipped.is_ok()) << skipped.status().message();
  EXPECT_FALSE(skipped.value().sections[1].known);
  EXPECT_TRUE(skipped.value().sections[0].known);
}

TEST(Container, VersionsAreUnsupported) {
  const Bytes file = sample_container();
  {
    Bytes newer = file;
    ContainerHeader header = decode_header(newer.data());
    header.minor = 2;
    put_header(&newer, header);
    Result<Container> read = read_container(newer.data(), newer.size());
    ASSERT_FALSE(read.is_ok());
    EXPECT_EQ(read.status().kind(), ErrorKind::kUnsupported);
    EXPECT_EQ(read.status().code(), 5);
    EXPECT_EQ(read.status().message(),
              "LBK-E005: format version 1.2 is newer than this reader (1.1)");
  }
  for (uint16_t major : {0, 2, 65535}) {
    Bytes other = file;
    ContainerHeader header = decode_header(other.data());
    header.major = major;
    put_header(&other, header);
    Result<Container> read = read_container(other.data(), other.size());
    ASSERT_FALSE(read.is_ok());
    EXPECT_EQ(read.status().kind(), ErrorKind::kUnsupported);
    EXPECT_EQ(read.status().code(), 4);
  }
  // A future major version may use a different header: 12 bytes decide it.
  Bytes short_future(file.begin(), file.begin() + 12);
  short_future[8] = 2;
  EXPECT_EQ(error_code(short_future), 4);
}

// One crafted file per error code: the code, the kind and a message that
// starts with the code's id.
class ErrorCodes : public ::testing::Test {
 protected:
  void expect(const Bytes& file, int code, const std::string& message_part) {
    Bytes keep;
    Result<Container> read = read_copy(file, &keep);
    ASSERT_FALSE(read.is_ok()) << "expected LBK-E0" << code;
    EXPECT_EQ(read.status().code(), code) << read.status().message();
    const ContainerError error = static_cast<ContainerError>(code);
    EXPECT_EQ(read.status().message().rfind(container_error_id(error) + ": ", 0), 0u);
    EXPECT_NE(read.status().message().find(message_part), std::string::npos)
        << read.status().message();
    const bool unsupported_kind = code == 4 || code == 5 || code == 20;
    EXPECT_EQ(read.status().kind(),
              unsupported_kind ? ErrorKind::kUnsupported : ErrorKind::kInvalidInput);
    EXPECT_EQ(read.status().message().find('\n'), std::string::npos);
    ContainerListing listing = list_container(keep.data(), keep.size());
    EXPECT_EQ(listing.status.code(), code);
    reached_.push_back(code);
  }

  void header_cases();
  void section_cases();

  static Bytes with_header(Bytes file, void (*edit)(ContainerHeader*)) {
    ContainerHeader header = decode_header(file.data());
    edit(&header);
    put_header(&file, header);
    return file;
  }

  static Bytes with_entry(Bytes file, size_t index, void (*edit)(SectionEntry*)) {
    SectionEntry entry = entry_of(file, index);
    edit(&entry);
    put_entry(&file, index, entry);
    return file;
  }

  std::vector<int> reached_;
};

void ErrorCodes::header_cases() {
  const Bytes file = sample_container();
  expect(Bytes(file.begin(), file.begin() + 30), 1,
         "file has 30 bytes, a container header needs 48");
  {
    Bytes png = file;
    png[1] = 'P';
    expect(png, 2, "not a lodbake container: file starts with 89 50 42 4B");
  }
  {
    Bytes bad = file;
    bad[20] ^= 0x10;
    expect(bad, 3, "header checksum mismatch");
  }
  expect(with_header(file, [](ContainerHeader* h) { h->major = 3; }), 4,
         "format major version 3 is not supported");
  expect(with_header(file, [](ContainerHeader* h) { h->minor = 7; }), 5, "1.7 is newer");
  expect(with_header(file, [](ContainerHeader* h) { h->flags = 4; }), 6,
         "unknown header flags 0x00000004");
  expect(with_header(file, [](ContainerHeader* h) { h->reserved = 1; }), 6,
         "header reserved field is 0x00000001");
  expect(with_header(file, [](ContainerHeader* h) { h->file_size += 8; }), 7, "truncated");
  expect(with_header(file, [](ContainerHeader* h) { h->file_size -= 8; }), 8, "8 trailing bytes");
  expect(with_header(file, [](ContainerHeader* h) { h->table_offset = 40; }), 9,
         "section table offset 40 is outside");
  expect(with_header(file, [](ContainerHeader* h) { h->table_offset = h->file_size + 8; }), 9,
         "is outside");
  expect(with_header(file, [](ContainerHeader* h) { h->table_offset = UINT64_MAX; }), 9,
         "is outside");
  expect(with_header(file, [](ContainerHeader* h) { h->table_offset += 4; }), 9,
         "is not a multiple of 8");
  expect(with_header(file, [](ContainerHeader* h) { h->section_count = 2; }), 10,
         "section count 2 needs 80 table bytes, but 120 bytes follow");
  expect(with_header(file, [](ContainerHeader* h) { h->section_count = UINT32_MAX; }), 10, "needs");
  expect(with_header(file, [](ContainerHeader* h) { h->table_crc32c ^= 1; }), 11,
         "section table checksum mismatch");
}

void ErrorCodes::section_cases() {
  const Bytes file = sample_container();  // META at 48 (13 bytes), BASE at 64 (29), XTRA at 96
  expect(with_entry(file, 1, [](SectionEntry* e) { e->offset = 4096; }), 12,
         "section BASE (offset 4096, 29 bytes) lies outside the section area 48..96");
  expect(with_entry(file, 1, [](SectionEntry* e) { e->stored_size = UINT64_MAX - 8; }), 12,
         "lies outside");
  expect(with_entry(file, 0, [](SectionEntry* e) { e->offset = 16; }), 12, "lies outside");
  expect(with_entry(file, 1, [](SectionEntry* e) { e->offset = 65; }), 13,
         "section BASE offset 65 is not a multiple of 8");
  expect(with_entry(file, 1, [](SectionEntry* e) { e->offset = 56; }), 14,
         "section BASE at offset 56 starts before the previous section ends (61)");
  // Listed out of file order: the empty XTRA claims the start of the area.
  expect(with_entry(file, 2, [](SectionEntry* e) { e->offset = 48; }), 14,
         "section XTRA at offset 48 starts before the previous section ends (93)");
  expect(with_entry(file, 0, [](SectionEntry* e) { e->stored_size = 3; }), 15,
         "13 bytes between offset 51 and section BASE at 64, at most 7 padding bytes allowed");
  {
    Bytes dirty = file;
    dirty[62] = 0x20;  // padding after META's 13 bytes at 48..60
    expect(dirty, 15, "nonzero padding byte 0x20 at offset 62 before section BASE");
  }
  // A gap before the empty XTRA at 96: BASE shortened to end at 80.
  expect(with_entry(file, 1, [](SectionEntry* e) { e->stored_size = 16; }), 15,
         "16 bytes between offset 80 and section XTRA at 96");
  {
    Bytes dirty = file;
    dirty[94] = 1;  // padding after BASE's 29 bytes at 64..92
    expect(dirty, 15, "nonzero padding byte 0x01 at offset 94 before section XTRA");
  }
  {
    // The table must follow the last section directly: move it 8 bytes on.
    Bytes moved(file.begin(), file.begin() + 96);
    moved.resize(104, 0);
    moved.insert(moved.end(), file.begin() + 96, file.end());
    ContainerHeader header = decode_header(moved.data());
    header.table_offset = 104;
    header.file_size = moved.size();
    put_header(&moved, header);
    expect(moved, 15, "8 bytes between offset 96 and the section table at 104");
  }
  expect(with_entry(file, 2, [](SectionEntry* e) { e->tag = std::string("X\x01TR", 4); }), 16,
         "section 2 tag \"X\\x01TR\" is not 4 printable ASCII characters");
  expect(with_entry(file, 2, [](SectionEntry* e) { e->tag = "a b "; }), 16, "not 4 printable");
  expect(with_entry(file, 2, [](SectionEntry* e) { e->tag = "META"; }), 17,
         "section 2 repeats tag META");
  expect(with_entry(file, 1, [](SectionEntry* e) { e->flags = 0x8001; }), 18,
         "section BASE has unknown flags 0x8001");
  expect(with_entry(file, 1, [](SectionEntry* e) { e->group = 9; }), 18,
         "section BASE reserved field is 0x00000009, must be 0 in format 1.0");
  {
    // In 1.1 the field is the group: 0, 1, 2, ... in table order.
    const Bytes grouped = with_header(file, [](ContainerHeader* h) { h->minor = 1; });
    expect(with_entry(grouped, 1, [](SectionEntry* e) { e->group = 2; }), 25,
           "section 1 (BASE) is in group 2 after group 0");
    expect(with_entry(grouped, 0, [](SectionEntry* e) { e->group = 1; }), 25,
           "section 0 (META) is in group 1 after group 0");
    Bytes two = with_entry(grouped, 1, [](SectionEntry* e) { e->group = 1; });
    expect(with_entry(two, 2, [](SectionEntry* e) { e->group = 0; }), 25,
           "section 2 (XTRA) is in group 0 after group 1");
    expect(with_entry(with_entry(two, 2, [](SectionEntry* e) { e->group = 1; }), 2,
                      [](SectionEntry* e) { e->tag = "BASE"; }),
           17, "section 2 repeats tag BASE in group 1");
  }
  {
    Bytes corrupt = file;
    corrupt[70] ^= 0x40;
    expect(corrupt, 19, "section BASE checksum mismatch");
  }
  expect(with_entry(file, 1, [](SectionEntry* e) { e->codec = 3; }), 20,
         "section BASE uses unknown codec 3");
  expect(with_entry(file, 1, [](SectionEntry* e) { e->decoded_size = 1000; }), 21,
         "decoded size 1000 differs from its stored size 29");
  expect(with_entry(file, 2, [](SectionEntry* e) { e->flags = kSectionFlagRequired; }), 22,
         "section XTRA is marked required");
}

TEST_F(ErrorCodes, EachCodeFromACraftedFile) {
  header_cases();
  section_cases();
  // Codes 23 and 24 come from the section decoders and Container::require
  // (meta_section_test, base_section_test, Container.RoundTrip).
  std::vector<bool> seen(kLastContainerError + 1, false);
  for (int code : reached_)
    seen[code] = true;
  for (int code = 1; code <= 22; ++code)
    EXPECT_TRUE(seen[code]) << "LBK-E0" << code;
  EXPECT_TRUE(seen[25]) << "LBK-E025";
}

TEST(ContainerErrors, IdsSummariesAndKinds) {
  EXPECT_EQ(container_error_id(ContainerError::kTruncated), "LBK-E007");
  EXPECT_EQ(container_error_id(ContainerError::kMissingSection), "LBK-E024");
  for (int code = 1; code <= kLastContainerError; ++code) {
    const auto error = static_cast<ContainerError>(code);
    EXPECT_STRNE(container_error_summary(error), "unknown error") << code;
    const Status status = container_error(error, "detail");
    EXPECT_EQ(status.code(), code);
    EXPECT_EQ(status.message(), container_error_id(error) + ": detail");
  }
  EXPECT_EQ(malformed_section("BASE", "bad").message(), "LBK-E023: section BASE: bad");
}

TEST(ContainerListing, ValidFile) {
  const Bytes file = sample_container();
  ContainerListing listing = list_container(file.data(), file.size());
  EXPECT_TRUE(listing.status.is_ok());
  EXPECT_TRUE(listing.magic_ok);
  EXPECT_TRUE(listing.header_read);
  EXPECT_TRUE(listing.header_crc_ok);
  EXPECT_TRUE(listing.table_read);
  EXPECT_TRUE(listing.table_complete);
  EXPECT_TRUE(listing.table_crc_ok);
  ASSERT_EQ(listing.sections.size(), 3u);
  for (const SectionListing& s : listing.sections) {
    EXPECT_TRUE(s.in_file);
    EXPECT_TRUE(s.crc_checked);
    EXPECT_TRUE(s.crc_ok) << s.display_tag;
  }
  EXPECT_TRUE(listing.sections[1].known);
  EXPECT_FALSE(listing.sections[2].known);
  EXPECT_EQ(listing.sections[1].size, 29u);
}

TEST(ContainerListing, BrokenFilesStillShowWhatTheyCan) {
  const Bytes file = sample_container();
  {
    Bytes corrupt = file;
    corrupt[70] ^= 1;  // inside BASE
    ContainerListing listing = list_container(corrupt.data(), corrupt.size());
    EXPECT_EQ(listing.status.code(), 19);
    ASSERT_EQ(listing.sections.size(), 3u);
    EXPECT_TRUE(listing.sections[0].crc_ok);
    EXPECT_FALSE(listing.sections[1].crc_ok);
    EXPECT_TRUE(listing.sections[1].crc_checked);
  }
  {
    // Truncated inside the table: the entries that fit are listed.
    Bytes cut(file.begin(), file.end() - 50);
    cut.shrink_to_fit();
    ContainerListing listing = list_container(cut.data(), cut.size());
    EXPECT_EQ(listing.status.code(), 7);
    EXPECT_TRUE(listing.table_read);
    EXPECT_FALSE(listing.table_complete);
    EXPECT_EQ(listing.sections.size(), 1u);
  }
  {
    // Unprintable tag: shown escaped.
    Bytes odd = file;
    SectionEntry entry = entry_of(odd, 2);
    entry.tag = std::string("\x01XY\\", 4);
    put_entry(&odd, 2, entry);
    ContainerListing listing = list_container(odd.data(), odd.size());
    EXPECT_EQ(listing.status.code(), 16);
    ASSERT_EQ(listing.sections.size(), 3u);
    EXPECT_EQ(listing.sections[2].display_tag, "\\x01XY\\x5C");
  }
  {
    const Bytes junk = text_bytes("solid cube\nfacet normal 0 0 1\nendsolid\n...........");
    ContainerListing listing = list_container(junk.data(), junk.size());
    EXPECT_EQ(listing.status.code(), 2);
    EXPECT_FALSE(listing.magic_ok);
    EXPECT_TRUE(listing.header_read);
    EXPECT_FALSE(listing.table_read);
  }
  {
    ContainerListing listing = list_container(nullptr, 0);
    EXPECT_EQ(listing.status.code(), 1);
    EXPECT_FALSE(listing.header_read);
  }
}

TEST(ContainerListing, OverlappingEntriesDoNotCostQuadraticTime) {
  // 2000 entries that all cover the whole section area of a broken file.
  const size_t count = 2000;
  const size_t area = 64 * 1024;
  Bytes file(kHeaderSize + area + count * kTableEntrySize, 0);
  ContainerHeader header;
  header.file_size = file.size();
  header.table_offset = kHeaderSize + area;
  header.section_count = count;
  for (size_t i = 0; i < count; ++i) {
    SectionEntry entry;
    entry.tag = "S" + std::to_string(1000 + i).substr(1);
    entry.offset = kHeaderSize;
    entry.stored_size = area;
    entry.decoded_size = area;
    encode_entry(entry, file.data() + header.table_offset + i * kTableEntrySize);
  }
  header.table_crc32c = crc32c(file.data() + header.table_offset, count * kTableEntrySize);
  put_header(&file, header);
  ContainerListing listing = list_container(file.data(), file.size());
  EXPECT_EQ(listing.status.code(), 14);
  ASSERT_EQ(listing.sections.size(), count);
  size_t checked = 0;
  for (const SectionListing& s : listing.sections)
    checked += s.crc_checked ? 1 : 0;
  EXPECT_LE(checked * area, file.size());
  EXPECT_GE(checked, 1u);
}

TEST(SectionRegistry, KnowsMetaAndBase) {
  EXPECT_TRUE(is_known_section("META"));
  EXPECT_TRUE(is_known_section("BASE"));
  EXPECT_FALSE(is_known_section("XTRA"));
  EXPECT_FALSE(is_known_section("BAS"));
  EXPECT_NE(section_description("BASE"), nullptr);
  for (const SectionKind& kind : known_section_kinds())
    EXPECT_TRUE(is_valid_tag(kind.tag));
}

}  // namespace
}  // namespace lodbake
