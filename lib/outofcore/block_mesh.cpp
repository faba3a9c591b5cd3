#include "lib/outofcore/block_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace lodbake {
namespace {

constexpr uint8_t kMagic[4] = {'L', 'B', 'O', 'B'};
constexpr uint32_t kVersion = 1;

// Work files are read back on the machine type that wrote them (x86-64 and
// ARM64 build farms are little-endian); a big-endian host would need swaps.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "work files are little-endian");

template <typename T>
void put(Bytes* out, const T& value) {
  const auto* p = reinterpret_cast<const uint8_t*>(&value);
  out->insert(out->end(), p, p + sizeof(T));
}

template <typename T>
void put_array(Bytes* out, const std::vector<T>& values) {
  const auto* p = reinterpret_cast<const uint8_t*>(values.data());
  out->insert(out->end(), p, p + values.size() * sizeof(T));
}

}  // namespace

Bytes encode_block(const BlockMesh& block) {
  Bytes out;
  out.reserve(24 + block.ids.size() * 16 + block.triangles.size() * 12);
  out.insert(out.end(), kMagic, kMagic + 4);
  put(&out, kVersion);
  put(&out, uint64_t{block.ids.size()});
  put(&out, uint64_t{block.triangles.size()});
  put_array(&out, block.ids);
  put_array(&out, block.positions);
  put_array(&out, block.triangles);
  return out;
}

Result<BlockMesh> decode_block(const Bytes& bytes) {
  if (bytes.size() < 24 || std::memcmp(bytes.data(), kMagic, 4) != 0)
    return invalid_input("not a lodbake block file");
  uint32_t version = 0;
  uint64_t vertices = 0, triangles = 0;
  std::memcpy(&version, bytes.data() + 4, 4);
  std::memcpy(&vertices, bytes.data() + 8, 8);
  std::memcpy(&triangles, bytes.data() + 16, 8);
  if (version != kVersion)
    return invalid_input("block file version " + std::to_string(version) + ", expected " +
                         std::to_string(kVersion));
  const uint64_t body = bytes.size() - 24;
  if (vertices > body / 16 || triangles > body / 12 || vertices * 16 + triangles * 12 != body)
    return invalid_input("block file counts do not match its size");
  BlockMesh block;
  block.ids.resize(vertices);
  block.positions.resize(vertices);
  block.triangles.resize(triangles);
  const uint8_t* p = bytes.data() + 24;
  std::memcpy(block.ids.data(), p, vertices * 4);
  std::memcpy(block.positions.data(), p + vertices * 4, vertices * 12);
  std::memcpy(block.triangles.data(), p + vertices * 16, triangles * 12);
  for (size_t v = 0; v < vertices; ++v) {
    if (v > 0 && block.ids[v] < block.ids[v - 1])
      return invalid_input("block file vertex ids decrease");
    for (float c : block.positions[v])
      if (!std::isfinite(c)) return invalid_input("block file has a non-finite position");
  }
  for (const Triangle& t : block.triangles)
    for (uint32_t v : t)
      if (v >= vertices) return invalid_input("block file has a vertex index out of range");
  return block;
}

uint64_t split_vertex_fans(BlockMesh* block) {
  // Corners grouped by vertex, in triangle order within a vertex.
  std::vector<std::pair<uint32_t, uint32_t>> corners;  // (vertex, triangle * 3 + corner)
  corners.reserve(block->triangles.size() * 3);
  for (size_t t = 0; t < block->triangles.size(); ++t)
    for (uint32_t k = 0; k < 3; ++k)
      corners.emplace_back(block->triangles[t][k], static_cast<uint32_t>(t * 3 + k));
  std::sort(corners.begin(), corners.end());
  const size_t original = block->ids.size();
  std::vector<uint32_t> new_vertices;  // the source vertex of each copy
  std::vector<uint32_t> parent;
  std::vector<std::pair<uint32_t, uint32_t>> edge_owner;  // (other vertex, local corner index)
  std::vector<std::pair<uint32_t, uint32_t>> moves;       // (corner, new vertex)
  for (size_t begin = 0; begin < corners.size();) {
    size_t end = begin;
    while (end < corners.size() && corners[end].first == corners[begin].first)
      ++end;
    const uint32_t v = corners[begin].first;
    const size_t n = end - begin;
    if (n > 1) {
      // Union the faces around v that share an edge (v, w).
      parent.resize(n);
      for (size_t i = 0; i < n; ++i)
        parent[i] = static_cast<uint32_t>(i);
      auto find = [&](uint32_t i) {
        while (parent[i] != i)
          i = parent[i] = parent[parent[i]];
        return i;
      };
      edge_owner.clear();
      for (size_t i = 0; i < n; ++i) {
        const uint32_t c = corners[begin + i].second;
        const Triangle& t = block->triangles[c / 3];
        edge_owner.emplace_back(t[(c % 3 + 1) % 3], static_cast<uint32_t>(i));
        edge_owner.emplace_back(t[(c % 3 + 2) % 3], static_cast<uint32_t>(i));
      }
      std::sort(edge_owner.begin(), edge_owner.end());
      for (size_t e = 1; e < edge_owner.size(); ++e) {
        if (edge_owner[e].first != edge_owner[e - 1].first) continue;
        const uint32_t a = find(edge_owner[e].second), b = find(edge_owner[e - 1].second);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
      // The fan of the first triangle keeps v; each other fan gets a copy.
      std::vector<std::pair<uint32_t, uint32_t>> fan_vertex;  // (root, vertex)
      for (size_t i = 0; i < n; ++i) {
        const uint32_t root = find(static_cast<uint32_t>(i));
        if (root == 0) continue;
        auto found = std::find_if(fan_vertex.begin(), fan_vertex.end(),
                                  [&](const auto& f) { return f.first == root; });
        uint32_t copy;
        if (found == fan_vertex.end()) {
          copy = static_cast<uint32_t>(original + new_vertices.size());
          new_vertices.push_back(v);
          fan_vertex.emplace_back(root, copy);
        } else {
          copy = found->second;
        }
        moves.emplace_back(corners[begin + i].second, copy);
      }
    }
    begin = end;
  }
  if (new_vertices.empty()) return 0;
  for (const auto& [corner, vertex] : moves)
    block->triangles[corner / 3][corner % 3] = vertex;
  // Copies go right after their source so that ids stay non-decreasing:
  // renumber all vertices.
  const size_t total = original + new_vertices.size();
  std::vector<uint32_t> copies_of_start(original + 1, 0);
  for (uint32_t source : new_vertices)
    ++copies_of_start[source + 1];
  for (size_t v = 0; v < original; ++v)
    copies_of_start[v + 1] += copies_of_start[v];
  std::vector<uint32_t> new_index(total);
  std::vector<uint32_t> next_copy(original, 0);
  for (size_t v = 0; v < original; ++v)
    new_index[v] = static_cast<uint32_t>(v + copies_of_start[v]);
  for (size_t k = 0; k < new_vertices.size(); ++k) {
    const uint32_t src = new_vertices[k];
    new_index[original + k] = new_index[src] + 1 + next_copy[src]++;
  }
  std::vector<uint32_t> ids(total);
  std::vector<Vec3f> positions(total);
  for (size_t v = 0; v < total; ++v) {
    const uint32_t src = v < original ? static_cast<uint32_t>(v) : new_vertices[v - original];
    ids[new_index[v]] = block->ids[src];
    positions[new_index[v]] = block->positions[src];
  }
  for (Triangle& t : block->triangles)
    for (uint32_t& v : t)
      v = new_index[v];
  block->ids = std::move(ids);
  block->positions = std::move(positions);
  return new_vertices.size();
}

std::vector<uint8_t> border_band(size_t vertex_count, const std::vector<Triangle>& triangles) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(triangles.size() * 3);
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k)
      edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::vector<uint8_t> border(vertex_count, 0);
  for (size_t begin = 0; begin < edges.size();) {
    size_t end = begin + 1;
    while (end < edges.size() && edges[end] == edges[begin])
      ++end;
    if (end - begin == 1) border[edges[begin].first] = border[edges[begin].second] = 1;
    begin = end;
  }
  std::vector<uint8_t> band = border;
  for (const Triangle& t : triangles) {
    if (!(border[t[0]] | border[t[1]] | border[t[2]])) continue;
    for (uint32_t v : t)
      band[v] = 1;
  }
  return band;
}

Status BlockStitcher::add(const BlockMesh& block) {
  for (const Triangle& t : block.triangles) {
    for (uint32_t v : t)
      if (v >= block.ids.size()) return invalid_input("block has a vertex index out of range");
    triangles_.push_back({block.ids[t[0]], block.ids[t[1]], block.ids[t[2]]});
  }
  for (size_t v = 0; v < block.ids.size(); ++v)
    vertices_.push_back({block.ids[v], block.positions[v]});
  return Status::ok();
}

Result<TriangleMesh> BlockStitcher::finish() {
  std::stable_sort(vertices_.begin(), vertices_.end(),
                   [](const Vertex& a, const Vertex& b) { return a.id < b.id; });
  TriangleMesh mesh;
  std::vector<uint32_t> ids;
  for (const Vertex& v : vertices_) {
    if (!ids.empty() && ids.back() == v.id) {
      if (mesh.positions.back() != v.position)
        return invalid_input("two blocks hold input vertex " + std::to_string(v.id) +
                             " at different positions");
      continue;
    }
    ids.push_back(v.id);
    mesh.positions.push_back(v.position);
  }
  vertices_ = std::vector<Vertex>();
  mesh.triangles.reserve(triangles_.size());
  for (const Triangle& t : triangles_) {
    Triangle local;
    for (int k = 0; k < 3; ++k)
      local[k] =
          static_cast<uint32_t>(std::lower_bound(ids.begin(), ids.end(), t[k]) - ids.begin());
    mesh.triangles.push_back(local);
  }
  triangles_ = std::vector<Triangle>();
  return mesh;
}

}  // namespace lodbake
