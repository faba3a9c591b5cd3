// The streaming OBJ reader of out-of-core runs against the in-memory OBJ
// reader: the same positions and triangles, across buffer cuts, line
// continuations, CRLF and lone CR line ends, polygons and relative indices;
// and the in-memory reader's messages for bad faces.
#include "lib/meshio/obj_stream_reader.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "lib/meshio/mesh_readers.h"

namespace lodbake {
namespace {

struct Streamed {
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;
};

Result<Streamed> stream(const std::string& text) {
  std::istringstream in(text);
  LODBAKE_ASSIGN_OR_RETURN(std::unique_ptr<ObjStreamReader> reader,
                           ObjStreamReader::open(&in, text.size()));
  Streamed s;
  LODBAKE_RETURN_IF_ERROR(reader->for_each_vertex([&](uint64_t i, const float* p) {
    EXPECT_EQ(i, s.positions.size());
    s.positions.push_back({p[0], p[1], p[2]});
    return Status::ok();
  }));
  EXPECT_EQ(reader->vertex_count(), s.positions.size());
  LODBAKE_RETURN_IF_ERROR(reader->for_each_triangle(s.positions, [&](uint64_t, const uint32_t* t) {
    s.triangles.push_back({t[0], t[1], t[2]});
    return Status::ok();
  }));
  return s;
}

void expect_same_as_in_memory(const std::string& text) {
  Result<Streamed> streamed = stream(text);
  ASSERT_TRUE(streamed.is_ok()) << streamed.status().message();
  ImportReport report;
  Result<TriangleMesh> mesh =
      parse_obj(reinterpret_cast<const uint8_t*>(text.data()), text.size(), &report);
  ASSERT_TRUE(mesh.is_ok()) << mesh.status().message();
  EXPECT_EQ(streamed.value().positions, mesh.value().positions);
  EXPECT_EQ(streamed.value().triangles, mesh.value().triangles);
}

// A strip of quads and pentagons (one of them not convex) long enough to
// cross several 1 MiB buffers, written with `eol` line ends, backslash
// continuations, comments and statements the reader skips.
std::string strip_obj(int columns, const char* eol) {
  std::ostringstream out;
  out << "\xef\xbb\xbf# strip" << eol << "mtllib a.mtl" << eol;
  for (int x = 0; x < columns; ++x) {
    out << "v " << x << " 0 0" << eol << "v " << x << ".5 -0.25 0 \\" << eol << " # w" << eol;
    out << "v " << x << " 1 0" << eol << "vt 0.5 0.5" << eol << "vn 0 0 1" << eol;
    if (x == 0) continue;
    // The last three vertices and the three before them, relative.
    if (x % 2 == 0) {
      out << "f -6/-2/-2 -5/-1/-1 -3/-1/-1 \\" << eol << "-1/-1/-1 -4/-2/-2 # a pentagon" << eol;
    } else {
      out << "usemtl m" << x << eol << "f " << 3 * x - 2 << " " << 3 * x + 1 << " " << 3 * x + 3
          << " " << 3 * x << eol;
    }
  }
  return out.str();
}

TEST(ObjStreamReader, ReadsWhatTheInMemoryReaderReads) {
  for (const char* eol : {"\n", "\r\n", "\r"}) {
    SCOPED_TRACE(testing::Message() << "line end " << static_cast<int>(eol[0]));
    const std::string text = strip_obj(30000, eol);
    ASSERT_GT(text.size(), size_t{2} << 20);
    expect_same_as_in_memory(text);
  }
  expect_same_as_in_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3");  // no final line end
  // A BOM before a first statement longer than the first buffer: skipped by
  // the first scan, several reads later, so the vertex is still read.
  expect_same_as_in_memory("\xef\xbb\xbfv 0 0 0" + std::string(size_t{3} << 19, ' ') +
                           "\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
}

TEST(ObjStreamReader, BadFacesGiveTheInMemoryMessages) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const std::string& face :
       {std::string("f 1 2 4\n"), std::string("f -1 -2 -4\n"), std::string("f 1 2\n"),
        std::string("f 1/1 2 3\n"), std::string("f 0 1 2\n"), std::string("f 1 2 x\n"),
        std::string("f 1//1 2//1 3//1\n")}) {
    const std::string text = head + face;
    Result<Streamed> streamed = stream(text);
    ASSERT_FALSE(streamed.is_ok()) << face;
    Result<TriangleMesh> mesh =
        parse_obj(reinterpret_cast<const uint8_t*>(text.data()), text.size(), nullptr);
    ASSERT_FALSE(mesh.is_ok()) << face;
    EXPECT_EQ(streamed.status().message(), mesh.status().message()) << face;
  }
  Result<Streamed> r = stream(head + "v nan 0 0\nf 1 2 3\n");
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(), "line 4: a vertex coordinate 'nan' is not finite");
  r = stream(head);
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(), "no faces found (3 vertices)");
  r = stream(head + "f 1 2 3\n" + std::string("\0", 1));
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().message(), "binary data where text was expected: NUL byte at byte 32");
  r = stream("\xff\xfev\0");
  ASSERT_FALSE(r.is_ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kUnsupported);
}

}  // namespace
}  // namespace lodbake
