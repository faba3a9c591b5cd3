// The SCNE payload: map + GLB, round trip and the decoder's refusals.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "formats/sections/scne.h"

namespace lodbake {
namespace {

Bytes minimal_glb() {
  const std::string json = R"({"asset":{"version":"2.0"}})";  // 27 bytes, padded to 28
  Bytes glb = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 0, 0, 0, 0};
  const uint32_t chunk = 28;
  for (int i = 0; i < 4; ++i)
    glb.push_back(static_cast<uint8_t>(chunk >> (8 * i)));
  for (char c : std::string("JSON"))
    glb.push_back(static_cast<uint8_t>(c));
  glb.insert(glb.end(), json.begin(), json.end());
  glb.push_back(' ');
  glb[8] = static_cast<uint8_t>(glb.size());
  return glb;
}

SceneSection sample() {
  SceneSection s;
  s.meshes = {{0, 0, {12, 4}}, {2, 1, {100}}};
  s.glb = minimal_glb();
  return s;
}

TEST(ScneSection, RoundTrips) {
  Result<Bytes> bytes = encode_scne(sample());
  ASSERT_TRUE(bytes.is_ok()) << bytes.status().message();
  Result<SceneSection> back = decode_scne(bytes.value().data(), bytes.value().size());
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value(), sample());
  // The seed the fuzz target starts from.
  if (const char* dir = std::getenv("LODBAKE_WRITE_SEEDS")) {
    std::ofstream(std::string(dir) + "/scne_section/two_meshes.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.value().data()), bytes.value().size());
  }
}

TEST(ScneSection, RefusesABrokenMapOrGlb) {
  SceneSection twice = sample();
  twice.meshes[1].group = 0;
  EXPECT_FALSE(encode_scne(twice).is_ok());
  Bytes bytes = encode_scne(sample()).value();
  Bytes truncated(bytes.begin(), bytes.end() - 1);
  Result<SceneSection> t = decode_scne(truncated.data(), truncated.size());
  ASSERT_FALSE(t.is_ok());
  EXPECT_NE(t.status().message().find("the GLB header says"), std::string::npos)
      << t.status().message();
  Bytes bad_map = bytes;
  bad_map[4] = '[';
  EXPECT_FALSE(decode_scne(bad_map.data(), bad_map.size()).is_ok());
  Bytes huge = bytes;
  huge[3] = 0x7f;  // map length beyond the payload
  Result<SceneSection> h = decode_scne(huge.data(), huge.size());
  ASSERT_FALSE(h.is_ok());
  EXPECT_EQ(h.status().code(), 23);
}

}  // namespace
}  // namespace lodbake
