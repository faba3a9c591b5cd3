// META section: deterministic compact JSON, round trip including unknown
// keys, and refusal (LBK-E023, never a crash) of hostile or wrong documents.
#include "formats/sections/meta.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "formats/support/version.h"

namespace lodbake {
namespace {

Result<MetaSection> decode_text(const std::string& text) {
  Bytes bytes(text.begin(), text.end());
  bytes.shrink_to_fit();
  return decode_meta(bytes.data(), bytes.size());
}

MetaSection sample_meta() {
  MetaSection meta = make_meta("lodbake-simplify");
  meta.options = {{"target_ratio", 0.25}, {"quantize_bits", 16}, {"repair", false}};
  meta.input = MetaInput{"bunny.ply", std::string(64, 'a'), 1234567};
  meta.counts = {{"vertices", 8}, {"triangles", 12}};
  return meta;
}

TEST(MetaSection, MakeMetaUsesTheLodbakeVersion) {
  const MetaSection meta = make_meta("lodbake-pack");
  EXPECT_EQ(meta.tool, "lodbake-pack");
  EXPECT_EQ(meta.version, kLodbakeVersion);
  EXPECT_EQ(std::string(kLodbakeVersion), "0.1.0");
}

TEST(MetaSection, EncodesCompactSortedJson) {
  Result<Bytes> bytes = encode_meta(sample_meta());
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  const std::string text(bytes.value().begin(), bytes.value().end());
  EXPECT_EQ(text,
            "{\"counts\":{\"triangles\":12,\"vertices\":8},"
            "\"input\":{\"bytes\":1234567,\"file\":\"bunny.ply\",\"sha256\":\"" +
                std::string(64, 'a') +
                "\"},"
                "\"options\":{\"quantize_bits\":16,\"repair\":false,\"target_ratio\":0.25},"
                "\"tool\":\"lodbake-simplify\",\"version\":\"0.1.0\"}");
  Result<Bytes> again = encode_meta(sample_meta());
  ASSERT_TRUE(again.is_ok());
  EXPECT_EQ(again.value(), bytes.value());
}

TEST(MetaSection, RoundTripKeepsUnknownKeys) {
  MetaSection meta = sample_meta();
  meta.tool = "lodbake-h\xC3\xA9";  // UTF-8 passes through unescaped
  meta.extra = {{"zz_future", {1, 2, 3}}, {"note", "hello"}};
  Result<Bytes> bytes = encode_meta(meta);
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  Result<MetaSection> back = decode_meta(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value(), meta);
  Result<nlohmann::json> doc = decode_meta_json(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(doc.is_ok());
  EXPECT_EQ(doc.value()["zz_future"][2], 3);
}

TEST(MetaSection, MinimalDocument) {
  Result<MetaSection> meta = decode_text("{\"tool\":\"t\",\"version\":\"9.9\"}");
  ASSERT_TRUE(meta.is_ok()) << meta.status().message();
  EXPECT_EQ(meta.value().tool, "t");
  EXPECT_FALSE(meta.value().input.has_value());
  EXPECT_TRUE(meta.value().counts.empty());
  EXPECT_TRUE(meta.value().options.is_object());
}

TEST(MetaSection, RejectsWrongDocuments) {
  const std::string sha = std::string(64, '0');
  const struct {
    std::string text;
    std::string message;
  } cases[] = {
      {"", "LBK-E023: section META: not valid JSON (error at byte 1)"},
      {"{\"tool\":\"t\",", "not valid JSON"},
      {"[1,2]", "LBK-E023: section META: JSON is array, expected an object"},
      {"\"str\"", "JSON is string"},
      {"{\"version\":\"1\"}", "key \"tool\" must be a string"},
      {"{\"tool\":3,\"version\":\"1\"}", "key \"tool\" must be a string"},
      {"{\"tool\":\"t\"}", "key \"version\" must be a string"},
      {"{\"tool\":\"t\",\"version\":\"1\",\"options\":[]}", "key \"options\" must be an object"},
      {"{\"tool\":\"t\",\"version\":\"1\",\"input\":5}", "key \"input\" must be an object"},
      {"{\"tool\":\"t\",\"version\":\"1\",\"input\":{\"sha256\":\"" + sha + "\",\"bytes\":1}}",
       "key \"input.file\""},
      {"{\"tool\":\"t\",\"version\":\"1\",\"input\":{\"file\":\"f\",\"sha256\":\"ABC\",\"bytes\":1}"
       "}",
       "key \"input.sha256\" must be 64 lower-case hex digits"},
      {"{\"tool\":\"t\",\"version\":\"1\",\"input\":{\"file\":\"f\",\"sha256\":\"" + sha +
           "\",\"bytes\":-1}}",
       "key \"input.bytes\" must be an unsigned integer"},
      {"{\"tool\":\"t\",\"version\":\"1\",\"counts\":{\"v\":1.5}}",
       "count \"v\" must be an unsigned integer"},
      {"{\"tool\":\"t\",\"version\":\"1\",\"counts\":[]}", "key \"counts\" must be an object"},
      {"{\"tool\":\"\xFF\",\"version\":\"1\"}", "not valid JSON"},
      {"{\"tool\":\"t\",\"version\":\"1\"} x", "not valid JSON"},
  };
  for (const auto& c : cases) {
    Result<MetaSection> meta = decode_text(c.text);
    ASSERT_FALSE(meta.is_ok()) << c.text;
    EXPECT_EQ(meta.status().code(), 23);
    EXPECT_EQ(meta.status().kind(), ErrorKind::kInvalidInput);
    EXPECT_NE(meta.status().message().find(c.message), std::string::npos)
        << meta.status().message();
    EXPECT_FALSE(
        decode_meta_json(reinterpret_cast<const uint8_t*>(c.text.data()), c.text.size()).is_ok());
  }
}

TEST(MetaSection, BoundsNestingAndSize) {
  // 100000 nested arrays: refused before parsing (a recursive dump would
  // overflow the stack).
  const std::string deep = "{\"tool\":\"t\",\"version\":\"1\",\"x\":" + std::string(100000, '[') +
                           std::string(100000, ']') + "}";
  Result<MetaSection> meta = decode_text(deep);
  ASSERT_FALSE(meta.is_ok());
  EXPECT_EQ(meta.status().message(), "LBK-E023: section META: JSON nests deeper than 64 levels");
  // Brackets inside strings do not count.
  const std::string quoted =
      "{\"tool\":\"t\",\"version\":\"1\",\"x\":\"" + std::string(1000, '[') + "\\\"\"}";
  EXPECT_TRUE(decode_text(quoted).is_ok());
  // Exactly at the limit is fine.
  const std::string at_limit = "{\"tool\":\"t\",\"version\":\"1\",\"x\":" + std::string(63, '[') +
                               std::string(63, ']') + "}";
  EXPECT_TRUE(decode_text(at_limit).is_ok());
  std::string big =
      "{\"tool\":\"t\",\"version\":\"1\",\"pad\":\"" + std::string(kMaxMetaBytes, 'x') + "\"}";
  Result<MetaSection> huge = decode_text(big);
  ASSERT_FALSE(huge.is_ok());
  EXPECT_NE(huge.status().message().find("at most 1048576 allowed"), std::string::npos);
}

TEST(MetaSection, EveryTruncationIsAnError) {
  Result<Bytes> bytes = encode_meta(sample_meta());
  ASSERT_TRUE(bytes.is_ok());
  for (size_t length = 0; length < bytes.value().size(); ++length) {
    Bytes prefix(bytes.value().begin(),
                 bytes.value().begin() + static_cast<std::ptrdiff_t>(length));
    prefix.shrink_to_fit();
    Result<MetaSection> meta = decode_meta(prefix.empty() ? nullptr : prefix.data(), length);
    ASSERT_FALSE(meta.is_ok()) << length;
    EXPECT_EQ(meta.status().code(), 23);
  }
}

TEST(MetaSection, EncoderRefusesWhatCannotRoundTrip) {
  MetaSection meta = sample_meta();
  meta.tool.clear();
  EXPECT_EQ(encode_meta(meta).status().message(), "META tool name is empty");
  meta = sample_meta();
  meta.options = nlohmann::json::array();
  EXPECT_FALSE(encode_meta(meta).is_ok());
  meta = sample_meta();
  meta.input->sha256_hex = "abc";
  EXPECT_FALSE(encode_meta(meta).is_ok());
  meta = sample_meta();
  meta.options["bad"] = std::string("\xC3\x28");
  EXPECT_EQ(encode_meta(meta).status().message(), "META holds a string that is not valid UTF-8");
  meta = sample_meta();
  meta.options["nan"] = std::nan("");
  EXPECT_EQ(encode_meta(meta).status().message(), "META document holds a non-finite number");
  meta = sample_meta();
  meta.extra["tool"] = "other";
  EXPECT_FALSE(encode_meta(meta).is_ok());
  meta = sample_meta();
  nlohmann::json deep = 1;
  for (int i = 0; i < 70; ++i)
    deep = nlohmann::json::array({deep});
  meta.options["deep"] = deep;
  EXPECT_NE(encode_meta(meta).status().message().find("nests deeper than 64"), std::string::npos);
}

}  // namespace
}  // namespace lodbake
