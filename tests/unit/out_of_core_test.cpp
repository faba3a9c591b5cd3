// lib/outofcore: memory sizes, the block partition, fan splitting, the
// border band, block files, stitching, the streaming PLY reader, and the
// three stages end to end on a generated mesh, from PLY and from OBJ.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "formats/support/file_io.h"
#include "lib/meshio/ply_stream_reader.h"
#include "lib/meshio/text_scanner.h"
#include "lib/outofcore/block_mesh.h"
#include "lib/outofcore/block_partition.h"
#include "lib/outofcore/memory_size.h"
#include "lib/outofcore/out_of_core.h"

namespace lodbake {
namespace {

namespace fs = std::filesystem;

TEST(MemorySize, ParsesSuffixes) {
  EXPECT_EQ(parse_memory_size("512M").value(), uint64_t{512} << 20);
  EXPECT_EQ(parse_memory_size("2G").value(), uint64_t{2} << 30);
  EXPECT_EQ(parse_memory_size("2gib").value(), uint64_t{2} << 30);
  EXPECT_EQ(parse_memory_size("64KB").value(), uint64_t{64} << 10);
  EXPECT_EQ(parse_memory_size("1000").value(), 1000u);
  EXPECT_EQ(parse_memory_size("1000B").value(), 1000u);
}

TEST(MemorySize, RefusesBadValues) {
  for (const char* bad : {"", "M", "0", "0G", "-1G", "1.5G", "12Q", "1GG", "2 G", "9999999T",
                          "99999999999999999999999"}) {
    Result<uint64_t> parsed = parse_memory_size(bad);
    ASSERT_FALSE(parsed.is_ok()) << bad;
    EXPECT_EQ(parsed.status().kind(), ErrorKind::kInvalidInput) << bad;
  }
}

TEST(BlockPartition, BlocksStayWithinBudgetAndCoverEveryTriangle) {
  BlockGrid grid = make_block_grid({0, 0, 0}, {4, 2, 1}, 8);
  EXPECT_EQ(grid.dims[0], 8u);
  EXPECT_EQ(grid.dims[1], 4u);
  EXPECT_EQ(grid.dims[2], 2u);
  std::vector<uint64_t> counts(grid.cell_count(), 0);
  // Dense on one side, empty cells in between.
  for (size_t c = 0; c < counts.size(); ++c)
    counts[c] = (c % 8 < 3) ? 50 : (c % 5 == 0 ? 0 : 7);
  partition_blocks(counts, 200, &grid);
  ASSERT_GT(grid.block_count, 1u);
  std::vector<uint64_t> per_block(grid.block_count, 0);
  for (size_t c = 0; c < counts.size(); ++c) {
    if (counts[c] == 0) continue;
    ASSERT_NE(grid.cell_block[c], kNoBlock);
    per_block[grid.cell_block[c]] += counts[c];
  }
  for (uint64_t n : per_block) {
    EXPECT_GT(n, 0u);
    EXPECT_LE(n, 200u);
  }
  BlockGrid again = make_block_grid({0, 0, 0}, {4, 2, 1}, 8);
  partition_blocks(counts, 200, &again);
  EXPECT_EQ(again.cell_block, grid.cell_block);
}

TEST(BlockPartition, OneCellOverBudgetIsOneBlock) {
  BlockGrid grid = make_block_grid({0, 0, 0}, {1, 1, 1}, 2);
  std::vector<uint64_t> counts(grid.cell_count(), 1);
  counts[3] = 1000;
  partition_blocks(counts, 10, &grid);
  uint32_t holding = 0;
  for (size_t c = 0; c < counts.size(); ++c)
    holding += grid.cell_block[c] == grid.cell_block[3];
  EXPECT_EQ(holding, 1u);
}

TEST(BlockPartition, CentroidCellIsClamped) {
  BlockGrid grid = make_block_grid({0, 0, 0}, {1, 1, 1}, 4);
  EXPECT_EQ(grid.cell_of({0, 0, 0}, {0, 0, 0}, {0, 0, 0}), 0u);
  EXPECT_EQ(grid.cell_of({1, 1, 1}, {1, 1, 1}, {1, 1, 1}), grid.cell_count() - 1);
  EXPECT_EQ(grid.cell_of({-5, 0, 0}, {-5, 0, 0}, {-5, 0, 0}), 0u);
}

// Two triangles meeting at vertex 0 only (a bow tie), plus a third on one side.
BlockMesh bow_tie() {
  BlockMesh b;
  b.ids = {10, 11, 12, 13, 14, 15};
  b.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, {2, 1, 0}};
  b.triangles = {{0, 1, 2}, {0, 3, 4}, {1, 5, 2}};
  return b;
}

TEST(SplitVertexFans, GivesEachFanItsOwnVertex) {
  BlockMesh b = bow_tie();
  EXPECT_EQ(split_vertex_fans(&b), 1u);
  ASSERT_EQ(b.ids.size(), 7u);
  EXPECT_TRUE(std::is_sorted(b.ids.begin(), b.ids.end()));
  EXPECT_EQ(b.ids[0], 10u);
  EXPECT_EQ(b.ids[1], 10u);
  EXPECT_NE(b.triangles[0][0], b.triangles[1][0]);
  // Every corner keeps its input vertex and position.
  const BlockMesh before = bow_tie();
  for (size_t t = 0; t < b.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(b.ids[b.triangles[t][k]], before.ids[before.triangles[t][k]]);
      EXPECT_EQ(b.positions[b.triangles[t][k]], before.positions[before.triangles[t][k]]);
    }
  BlockMesh fan = bow_tie();
  fan.triangles.pop_back();
  fan.triangles[1] = {0, 2, 3};  // now one fan around 0
  EXPECT_EQ(split_vertex_fans(&fan), 0u);
}

TEST(BorderBand, LocksTheBorderAndItsNeighbours) {
  // A 4x4 grid of quads: border ring, its neighbours, and the centre free.
  const int n = 5;
  std::vector<Triangle> triangles;
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const uint32_t a = y * n + x, b = a + 1, c = a + n, d = c + 1;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
  const std::vector<uint8_t> band = border_band(n * n, triangles);
  EXPECT_EQ(band[0], 1);
  EXPECT_EQ(band[6], 1);   // next to the border
  EXPECT_EQ(band[12], 0);  // the centre
}

TEST(BlockFile, RoundTripsAndRefusesDamage) {
  BlockMesh b = bow_tie();
  const Bytes bytes = encode_block(b);
  Result<BlockMesh> back = decode_block(bytes);
  ASSERT_TRUE(back.is_ok()) << back.status().message();
  EXPECT_EQ(back.value().ids, b.ids);
  EXPECT_EQ(back.value().positions, b.positions);
  EXPECT_EQ(back.value().triangles, b.triangles);
  for (size_t cut = 0; cut < bytes.size(); ++cut) {
    Bytes truncated(bytes.begin(), bytes.begin() + static_cast<long>(cut));
    EXPECT_FALSE(decode_block(truncated).is_ok()) << cut;
  }
  Bytes bad_index = bytes;
  bad_index[bad_index.size() - 4] = 0xff;
  EXPECT_FALSE(decode_block(bad_index).is_ok());
  Bytes nan = bytes;
  const float q = std::nanf("");
  std::memcpy(nan.data() + 24 + b.ids.size() * 4, &q, 4);
  EXPECT_FALSE(decode_block(nan).is_ok());
}

TEST(BlockStitcher, JoinsSharedVerticesById) {
  BlockMesh left, right;
  left.ids = {1, 2, 3};
  left.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  left.triangles = {{0, 1, 2}};
  right.ids = {2, 3, 4};
  right.positions = {{1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  right.triangles = {{0, 2, 1}};
  BlockStitcher stitcher;
  ASSERT_TRUE(stitcher.add(left).is_ok());
  ASSERT_TRUE(stitcher.add(right).is_ok());
  Result<TriangleMesh> mesh = stitcher.finish();
  ASSERT_TRUE(mesh.is_ok());
  EXPECT_EQ(mesh.value().positions.size(), 4u);
  ASSERT_EQ(mesh.value().triangles.size(), 2u);
  EXPECT_EQ(mesh.value().triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.value().triangles[1], (Triangle{1, 3, 2}));

  BlockStitcher moved;
  right.positions[0] = {1, 0.5f, 0};
  ASSERT_TRUE(moved.add(left).is_ok());
  ASSERT_TRUE(moved.add(right).is_ok());
  Result<TriangleMesh> refused = moved.finish();
  ASSERT_FALSE(refused.is_ok());
  EXPECT_NE(refused.status().message().find("input vertex 2"), std::string::npos);
}

// A bumpy n x n height field as PLY text (ASCII) or binary little-endian.
std::string grid_ply(int n, bool binary) {
  std::ostringstream out;
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\nelement vertex "
      << n * n << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
      << 2 * (n - 1) * (n - 1) << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float p[3] = {static_cast<float>(x), static_cast<float>(y),
                          static_cast<float>(std::sin(x * 0.3) * std::cos(y * 0.2) * 3)};
      if (binary) {
        out.write(reinterpret_cast<const char*>(p), 12);
      } else {
        out << p[0] << " " << p[1] << " " << p[2] << "\n";
      }
    }
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const int32_t a = y * n + x, b = a + 1, c = a + n, d = c + 1;
      for (const std::array<int32_t, 3>& t : {std::array<int32_t, 3>{a, b, d}, {a, d, c}}) {
        if (binary) {
          const uint8_t three = 3;
          out.write(reinterpret_cast<const char*>(&three), 1);
          out.write(reinterpret_cast<const char*>(t.data()), 12);
        } else {
          out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
        }
      }
    }
  return out.str();
}

struct Streamed {
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;
};

Result<Streamed> stream(const std::string& text) {
  std::istringstream in(text);
  LODBAKE_ASSIGN_OR_RETURN(std::unique_ptr<PlyStreamReader> reader,
                           PlyStreamReader::open(&in, text.size()));
  Streamed s;
  LODBAKE_RETURN_IF_ERROR(reader->for_each_vertex([&](uint64_t, const float* p) {
    s.positions.push_back({p[0], p[1], p[2]});
  }));
  LODBAKE_RETURN_IF_ERROR(reader->for_each_triangle([&](uint64_t, const uint32_t* t) {
    s.triangles.push_back({t[0], t[1], t[2]});
    return Status::ok();
  }));
  return s;
}

TEST(PlyStreamReader, AsciiAndBinaryReadTheSameMesh) {
  Result<Streamed> ascii = stream(grid_ply(6, false));
  Result<Streamed> binary = stream(grid_ply(6, true));
  ASSERT_TRUE(ascii.is_ok()) << ascii.status().message();
  ASSERT_TRUE(binary.is_ok()) << binary.status().message();
  EXPECT_EQ(ascii.value().triangles, binary.value().triangles);
  ASSERT_EQ(ascii.value().positions.size(), 36u);
  for (size_t v = 0; v < 36; ++v)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(ascii.value().positions[v][k], binary.value().positions[v][k], 1e-4);
}

TEST(PlyStreamReader, RefusesBadBodies) {
  std::string text = grid_ply(3, false);
  std::string out_of_range = text;
  out_of_range.replace(out_of_range.rfind("3 "), 2, "3 9");
  Result<Streamed> r = stream(out_of_range);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.status().message().find("out of range"), std::string::npos);

  std::string nan = text;
  nan.replace(nan.find("end_header\n") + 11, 1, "nan");
  r = stream(nan);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.status().message().find("non-finite"), std::string::npos);

  std::string quad = text;
  quad.replace(quad.rfind("\n3 ") + 1, 1, "4");
  r = stream(quad + " 0\n");
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kUnsupported);

  std::string truncated = text.substr(0, text.size() - 10);
  EXPECT_FALSE(stream(truncated).is_ok());

  std::string huge = text;
  huge.replace(huge.find("vertex 9"), 8, "vertex 999999999999");
  r = stream(huge);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kInvalidInput);
}

// The streaming reader reads ASCII values as the in-memory reader does
// (text_scanner.h): a float32 rounded once, not through double, and no hex.
TEST(PlyStreamReader, AsciiValuesAreTheInMemoryReadersValues) {
  const std::string text = grid_ply(3, false);
  const size_t first = text.find("end_header\n") + 11;
  // Just above the midpoint between 1 and the next float: rounded once it
  // is the next float; rounded to double first it is the midpoint, which
  // ties to 1.
  const std::string above_midpoint = "1.0000000596046447753906250001";
  float once = 0;
  ASSERT_EQ(parse_float(above_midpoint, &once), NumberStatus::kOk);
  ASSERT_EQ(once, std::nextafter(1.0f, 2.0f));
  ASSERT_EQ(static_cast<float>(std::stod(above_midpoint)), 1.0f);
  std::string fine = text;
  fine.replace(first, 1, above_midpoint);
  Result<Streamed> r = stream(fine);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().positions[0][0], once);

  std::string plus = text;
  plus.replace(first, 1, "+2");
  r = stream(plus);
  ASSERT_TRUE(r.is_ok()) << r.status().message();
  EXPECT_EQ(r.value().positions[0][0], 2.0f);

  std::string hex = text;
  hex.replace(first, 1, "0x1p0");
  float ignored = 0;
  ASSERT_EQ(parse_float("0x1p0", &ignored), NumberStatus::kMalformed);
  EXPECT_FALSE(stream(hex).is_ok());

  std::string hex_index = text;
  hex_index.replace(hex_index.rfind("\n3 ") + 3, 1, "0x0");
  EXPECT_FALSE(stream(hex_index).is_ok());
}

class OutOfCoreStages : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ =
        fs::temp_directory_path() /
        ("lodbake_ooc_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    input_ = (root_ / "grid.ply").string();
    std::ofstream(input_, std::ios::binary) << grid_ply(60, true);
  }
  void TearDown() override { fs::remove_all(root_); }

  Result<TriangleMesh> run(const std::string& work, unsigned threads, OutOfCorePlan* plan_out,
                           const std::string& input = "") {
    fs::create_directories(work);
    OutOfCoreOptions options;
    options.memory_limit = 800000;  // about a third of the mesh per block
    options.simplify.target_ratio = 0.2;
    LODBAKE_ASSIGN_OR_RETURN(OutOfCorePlan plan,
                             split_input(input.empty() ? input_ : input, work, options, nullptr));
    LODBAKE_ASSIGN_OR_RETURN(OutOfCorePlan reread, read_plan(work));
    EXPECT_EQ(reread.block_triangles, plan.block_triangles);
    for (uint32_t b = 0; b < plan.block_count(); ++b)
      LODBAKE_RETURN_IF_ERROR(simplify_block(work, reread, b, threads));
    LODBAKE_ASSIGN_OR_RETURN(MergeResult merged, merge_blocks(work, reread, threads, nullptr));
    *plan_out = plan;
    return merged.mesh;
  }

  fs::path root_;
  std::string input_;
};

TEST_F(OutOfCoreStages, SeveralBlocksReachTheTargetTheSameForAnyThreads) {
  OutOfCorePlan plan;
  Result<TriangleMesh> one = run((root_ / "w1").string(), 1, &plan);
  ASSERT_TRUE(one.is_ok()) << one.status().message();
  EXPECT_GT(plan.block_count(), 2u);
  EXPECT_EQ(plan.input_triangles, 2u * 59 * 59);
  uint64_t sum = 0;
  for (uint64_t n : plan.block_triangles) {
    EXPECT_LE(n, plan.block_budget);
    sum += n;
  }
  EXPECT_EQ(sum, plan.input_triangles);
  EXPECT_LE(one.value().triangles.size(), *plan.final_triangles);
  EXPECT_GT(one.value().triangles.size(), *plan.final_triangles / 2);
  OutOfCorePlan plan3;
  Result<TriangleMesh> three = run((root_ / "w3").string(), 3, &plan3);
  ASSERT_TRUE(three.is_ok());
  EXPECT_EQ(one.value(), three.value());
  // The one-shot's cleanup leaves nothing of the stages behind.
  remove_work_files((root_ / "w1").string());
  EXPECT_FALSE(fs::exists(root_ / "w1"));
}

// The grid of grid_ply(n, true) as OBJ text: the same floats (9 significant
// digits give a float back exactly), half the faces by relative indices,
// with comments, groups and CRLF line ends between.
std::string grid_obj(int n) {
  std::ostringstream out;
  out << "# grid\r\no grid\r\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      char line[96];
      std::snprintf(line, sizeof(line), "v %.9g %.9g %.9g\r\n", static_cast<float>(x),
                    static_cast<float>(y),
                    static_cast<float>(std::sin(x * 0.3) * std::cos(y * 0.2) * 3));
      out << line;
    }
  const int count = n * n;
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x, b = a + 1, c = a + n, d = c + 1;
      out << "f " << a + 1 << " " << b + 1 << " " << d + 1 << "\r\n";
      out << "f " << a - count << " " << d - count << " " << c - count << " # relative\r\n";
    }
  return out.str();
}

TEST_F(OutOfCoreStages, ObjInputGivesThePlyResult) {
  const std::string obj = (root_ / "grid.obj").string();
  std::ofstream(obj, std::ios::binary) << grid_obj(60);
  OutOfCorePlan from_ply, from_obj;
  Result<TriangleMesh> a = run((root_ / "wp").string(), 1, &from_ply);
  Result<TriangleMesh> b = run((root_ / "wo").string(), 1, &from_obj, obj);
  ASSERT_TRUE(a.is_ok()) << a.status().message();
  ASSERT_TRUE(b.is_ok()) << b.status().message();
  EXPECT_GT(from_obj.block_count(), 2u);
  EXPECT_EQ(from_obj.block_triangles, from_ply.block_triangles);
  EXPECT_EQ(from_obj.diagonal, from_ply.diagonal);
  EXPECT_EQ(a.value(), b.value());
}

TEST_F(OutOfCoreStages, ObjErrorsNameTheLine) {
  const std::string work = (root_ / "w").string();
  fs::create_directories(work);
  OutOfCoreOptions options;
  options.memory_limit = 800000;
  options.simplify.target_ratio = 0.2;
  const std::string obj = (root_ / "bad.obj").string();
  std::ofstream(obj, std::ios::binary) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n";
  Result<OutOfCorePlan> plan = split_input(obj, work, options, nullptr);
  ASSERT_FALSE(plan.is_ok());
  EXPECT_EQ(plan.status().message(), "line 5: vertex index 4 out of range (3 so far)");
  EXPECT_TRUE(fs::is_empty(work));
  const std::string off = (root_ / "mesh.off").string();
  std::ofstream(off, std::ios::binary) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  plan = split_input(off, work, options, nullptr);
  ASSERT_FALSE(plan.is_ok());
  EXPECT_EQ(plan.status().kind(), ErrorKind::kUnsupported);
}

TEST_F(OutOfCoreStages, MergeNamesAMissingBlock) {
  const std::string work = (root_ / "w").string();
  fs::create_directories(work);
  OutOfCoreOptions options;
  options.memory_limit = 800000;
  options.simplify.target_ratio = 0.2;
  Result<OutOfCorePlan> plan = split_input(input_, work, options, nullptr);
  ASSERT_TRUE(plan.is_ok());
  ASSERT_TRUE(simplify_block(work, plan.value(), 0, 1).is_ok());
  Result<MergeResult> merged = merge_blocks(work, plan.value(), 1, nullptr);
  ASSERT_FALSE(merged.is_ok());
  EXPECT_NE(merged.status().message().find("block 1 is not simplified yet"), std::string::npos);
  EXPECT_FALSE(simplify_block(work, plan.value(), plan.value().block_count(), 1).is_ok());
}

TEST_F(OutOfCoreStages, RefusesALimitTooSmallForThePositions) {
  const std::string work = (root_ / "w").string();
  fs::create_directories(work);
  OutOfCoreOptions options;
  options.memory_limit = 1000;
  options.simplify.target_ratio = 0.2;
  Result<OutOfCorePlan> plan = split_input(input_, work, options, nullptr);
  ASSERT_FALSE(plan.is_ok());
  EXPECT_EQ(plan.status().kind(), ErrorKind::kRuntime);
  EXPECT_TRUE(fs::is_empty(work));
}

}  // namespace
}  // namespace lodbake
