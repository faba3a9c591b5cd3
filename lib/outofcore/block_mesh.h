// One block of an out-of-core run as it goes between stages: its vertices
// with their ids in the whole input, and its triangles on those vertices;
// and the stitching of simplified blocks back into one mesh by those ids.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/file_io.h"
#include "formats/support/status.h"

namespace lodbake {

struct BlockMesh {
  // Input vertex id of each vertex, non-decreasing: a vertex whose faces in
  // the block form separate fans is one vertex per fan (split_vertex_fans()).
  std::vector<uint32_t> ids;
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;  // on the block's own vertices
};

/// Gives each separate fan of faces around a vertex its own copy of the
/// vertex (same id and position), appended after the vertex: a cut through
/// a vertex's fan by centroid leaves it several fans in one block, which the
/// engine refuses as non-manifold. Copies are on the block's border and stay
/// locked, and stitching joins them again by id. Returns the copies added.
/// Deterministic: fans in the order of their first triangle.
uint64_t split_vertex_fans(BlockMesh* block);

/// The band a block keeps as it is: its border vertices (on an edge with one
/// face) and their neighbours, one flag per vertex. Locking the border alone
/// is not enough: a collapse next to it may join two border vertices by an
/// edge inside the block, and the neighbour block the same two by another,
/// which stitched is an edge with four faces. With the neighbours locked
/// too, no border vertex gains a neighbour.
std::vector<uint8_t> border_band(size_t vertex_count, const std::vector<Triangle>& triangles);

/// The block as bytes of a work file: "LBOB", a version, counts, then the
/// arrays in little-endian order.
Bytes encode_block(const BlockMesh& block);
/// Reads encode_block()'s bytes back; fails (kInvalidInput) on a wrong
/// magic or version, counts the bytes cannot hold, ids that do not
/// decrease, a non-finite position or an index out of range.
Result<BlockMesh> decode_block(const Bytes& bytes);

/// Joins blocks into one mesh: vertices with one input id become one vertex
/// (the stitched mesh's vertices in id order), triangles in the order the
/// blocks were added.
class BlockStitcher {
 public:
  /// Fails when the block is malformed (an index out of range).
  Status add(const BlockMesh& block);
  /// Fails (kInvalidInput) when two blocks hold one id at two positions
  /// (a border that moved).
  Result<TriangleMesh> finish();

 private:
  struct Vertex {
    uint32_t id;
    Vec3f position;
  };
  std::vector<Vertex> vertices_;
  std::vector<Triangle> triangles_;  // on input ids
};

}  // namespace lodbake
