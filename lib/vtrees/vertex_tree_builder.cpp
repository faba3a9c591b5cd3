// Vertex trees of To, Lau & Green (Presence 2001, sections 3-5) built from a
// recorded progressive mesh instead of their own edge decimation: split k
// is the inverse of their collapse of the child vertex vt = B + k into the
// parent vertex vs.
//
// Choices where the paper is vague:
// - Fans are taken in the sequential mesh right after the split (before
//   the collapse, in the paper's terms), neighbours by PM vertex id, so a
//   fan may name vertices the client has not received yet; the client maps
//   them to their first visible ancestor (the paper's server does it).
// - A vertex fan is clockwise; a closed one starts at its smallest
//   neighbour. A vertex whose faces do not form one fan (non-manifold) gets
//   several runs, each with its own closed flag.
// - Equations (1)-(3): TRing(e) is every face around vs or vt before the
//   collapse; S_max its largest triangle state; both vertices' state is 1
//   when S_max is 0, else 0 (equation (2) as printed); then every face of
//   TRing(e) gains 1. A face keeps its state when the collapse moves it from
//   vt to vs. The base node's state is its vertex's after the last collapse
//   into it (0 when none). The client does not select triangles with these
//   states (see lib/vtrees/visible_vertex_list.h for why); they are stored
//   as the paper's records carry them.
#include "lib/vtrees/vertex_tree_builder.h"

#include <algorithm>
#include <new>
#include <string>

#include "lib/dag/split_simulator.h"

namespace lodbake {
namespace {

void append_fan(const std::vector<FanRun>& runs, VertexTrees* out) {
  for (const FanRun& run : runs) {
    out->run_closed.push_back(run.closed ? 1 : 0);
    out->fan_vertices.insert(out->fan_vertices.end(), run.vertices.begin(), run.vertices.end());
    out->vertex_offsets.push_back(static_cast<uint32_t>(out->fan_vertices.size()));
  }
  out->run_offsets.push_back(static_cast<uint32_t>(out->run_closed.size()));
}

}  // namespace

Result<VertexTrees> build_vertex_trees(const ProgressiveMesh& pm) {
  try {
    LODBAKE_ASSIGN_OR_RETURN(SplitSimulator sim, SplitSimulator::create(pm));
    VertexTrees out;
    const uint32_t b = static_cast<uint32_t>(pm.base.vertex_count());
    const size_t splits = pm.splits.size();
    out.base_vertex_count = b;
    out.positions = pm.base.positions;
    out.positions.reserve(b + splits);
    out.parent_vertex.reserve(splits);
    for (uint32_t v = 0; v < b; ++v)
      append_fan(sim.fan(v), &out);

    // TRing of each split's collapse, as face slots, for equations (1)-(3).
    std::vector<uint32_t> ring_offsets{0};
    std::vector<uint32_t> rings;
    SplitSimulator::Effect effect;
    for (size_t k = 0; k < splits; ++k) {
      const VertexSplit& s = pm.splits[k];
      if (s.vs < out.positions.size() && s.vs_position != out.positions[s.vs]) {
        return unsupported("vertex split " + std::to_string(k) +
                           " moves its split vertex; vertex trees need half-edge placement");
      }
      LODBAKE_RETURN_IF_ERROR(sim.split_next(&effect));
      const uint32_t vt = b + static_cast<uint32_t>(k);
      out.parent_vertex.push_back(s.vs);
      out.positions.push_back(s.vt_position);
      append_fan(sim.fan(vt), &out);
      append_fan(sim.fan(s.vs), &out);
      const size_t first = rings.size();
      rings.insert(rings.end(), sim.faces_of(s.vs).begin(), sim.faces_of(s.vs).end());
      rings.insert(rings.end(), sim.faces_of(vt).begin(), sim.faces_of(vt).end());
      std::sort(rings.begin() + static_cast<std::ptrdiff_t>(first), rings.end());
      rings.erase(std::unique(rings.begin() + static_cast<std::ptrdiff_t>(first), rings.end()),
                  rings.end());
      ring_offsets.push_back(static_cast<uint32_t>(rings.size()));
    }

    std::vector<uint32_t> triangle_state(sim.faces().size(), 0);
    std::vector<uint8_t> split_state(splits, 0);
    for (size_t k = splits; k-- > 0;) {
      uint32_t s_max = 0;
      for (uint32_t r = ring_offsets[k]; r < ring_offsets[k + 1]; ++r)
        s_max = std::max(s_max, triangle_state[rings[r]]);
      split_state[k] = s_max == 0 ? 1 : 0;
      for (uint32_t r = ring_offsets[k]; r < ring_offsets[k + 1]; ++r)
        ++triangle_state[rings[r]];
    }
    out.vertex_states.assign(b, 0);
    for (size_t k = splits; k-- > 0;) {
      const uint32_t vs = pm.splits[k].vs;
      if (vs < b) out.vertex_states[vs] = split_state[k];  // the last collapse into vs wins
    }
    out.vertex_states.insert(out.vertex_states.end(), split_state.begin(), split_state.end());
    return out;
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory while building the vertex trees");
  }
}

}  // namespace lodbake
