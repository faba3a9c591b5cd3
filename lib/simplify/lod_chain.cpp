#include "lib/simplify/lod_chain.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "lib/simplify/pm_replay.h"

namespace lodbake {

namespace {

uint64_t triangles_added(const VertexSplit& split) {
  return (split.vl == kNoVertex || split.vr == kNoVertex) ? 1 : 2;
}

}  // namespace

Result<std::vector<TriangleMesh>> extract_lods(const ProgressiveMesh& pm,
                                               const std::vector<uint64_t>& triangle_targets) {
  // Visit the targets from the smallest up, so one refinement pass serves all.
  std::vector<size_t> order(triangle_targets.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return triangle_targets[a] < triangle_targets[b]; });
  LODBAKE_ASSIGN_OR_RETURN(PmRefiner refiner, PmRefiner::create(pm));
  std::vector<TriangleMesh> lods(triangle_targets.size());
  for (size_t index : order) {
    while (!refiner.fully_refined()) {
      // A split adds two faces, one when a wing is missing (a boundary edge).
      const uint64_t added = triangles_added(pm.splits[refiner.applied_splits()]);
      if (refiner.mesh().triangle_count() + added > triangle_targets[index]) break;
      LODBAKE_RETURN_IF_ERROR(refiner.split_next());
    }
    lods[index] = refiner.mesh();
  }
  return lods;
}

Result<LodRequest> parse_lod_request(const std::string& text) {
  auto fail = [&] {
    return Status(ErrorKind::kUsage,
                  "--lod takes a vertex count (5000), a triangle count (5000t) "
                  "or a ratio (0.25), not '" +
                      text + "'");
  };
  LodRequest request;
  if (text.find('.') != std::string::npos) {
    char* end = nullptr;
    request.kind = LodRequest::Kind::kRatio;
    request.ratio = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !(request.ratio > 0 && request.ratio <= 1))
      return fail();
    return request;
  }
  std::string digits = text;
  if (!digits.empty() && digits.back() == 't') {
    request.kind = LodRequest::Kind::kTriangles;
    digits.pop_back();
  }
  if (digits.empty() || digits.size() > 19 ||
      digits.find_first_not_of("0123456789") != std::string::npos)
    return fail();
  request.count = std::stoull(digits);
  return request;
}

size_t lod_vertex_count(const ProgressiveMesh& pm, const LodRequest& request) {
  const size_t base = pm.base.vertex_count();
  if (request.kind == LodRequest::Kind::kVertices)
    return static_cast<size_t>(std::clamp<uint64_t>(request.count, base, pm.full_vertex_count()));
  uint64_t limit = request.count;
  if (request.kind == LodRequest::Kind::kRatio) {
    uint64_t full = pm.base.triangle_count();
    for (const VertexSplit& split : pm.splits)
      full += triangles_added(split);
    limit = static_cast<uint64_t>(std::floor(request.ratio * static_cast<double>(full)));
  }
  uint64_t triangles = pm.base.triangle_count();
  size_t splits = 0;
  while (splits < pm.splits.size() && triangles + triangles_added(pm.splits[splits]) <= limit)
    triangles += triangles_added(pm.splits[splits++]);
  return base + splits;
}

}  // namespace lodbake
