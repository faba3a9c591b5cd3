// The loaders are the replay modes' own first steps, moved here from
// lodbake-replay so that --validate and the fuzz target run the same code.
#include "lib/replay/structure_loading.h"

#include <new>
#include <utility>

#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/dage.h"
#include "formats/sections/fanh.h"
#include "formats/sections/vhie.h"
#include "formats/sections/vspl.h"
#include "formats/sections/vtre.h"
#include "formats/sections/wedg.h"

namespace lodbake {
namespace {

struct Needs {
  std::vector<const char*> tags;
  const char* purpose;
  const char* producer;
};

Needs needs_of(ReplayStructure kind) {
  switch (kind) {
    case ReplayStructure::kVhier:
      return {{kBaseTag, kVhieTag, kRfinTag}, "mode vhier", "lodbake-hierarchy --sections vhie"};
    case ReplayStructure::kDag:
      return {{kBaseTag, kVsplTag, kDageTag}, "mode dag", "lodbake-hierarchy --sections dage"};
    case ReplayStructure::kFan:
      return {{kBaseTag, kFanhTag}, "mode fan", "lodbake-fan"};
    case ReplayStructure::kSets:
      return {{kBaseTag, kVsplTag, kSetsTag}, "mode sets", "lodbake-strips"};
    case ReplayStructure::kStream:
      return {{kBaseTag, kVhieTag, kRfinTag}, "mode stream", "lodbake-hierarchy --sections vhie"};
    case ReplayStructure::kVtrees:
      return {{kBaseTag, kVhieTag, kRfinTag, kVtreTag},
              "mode vtrees",
              "lodbake-hierarchy --sections vhie,vtre"};
  }
  return {{}, "", ""};
}

// BASE + VHIE of `group` as a hierarchy on the heap.
Result<std::unique_ptr<VertexHierarchy>> load_hierarchy(const Container& decoded, uint32_t group) {
  LODBAKE_ASSIGN_OR_RETURN(const Section* base, decoded.require(kBaseTag, group));
  LODBAKE_ASSIGN_OR_RETURN(const Section* vhie, decoded.require(kVhieTag, group));
  LODBAKE_ASSIGN_OR_RETURN(TriangleMesh base_mesh, decode_base(base->data, base->size));
  LODBAKE_ASSIGN_OR_RETURN(VertexHierarchy h,
                           decode_vhie(vhie->data, vhie->size, std::move(base_mesh)));
  return std::make_unique<VertexHierarchy>(std::move(h));
}

// BASE + VSPL of `group` as a progressive mesh on the heap.
Result<std::unique_ptr<ProgressiveMesh>> load_pm(const Container& decoded, uint32_t group) {
  LODBAKE_ASSIGN_OR_RETURN(const Section* base, decoded.require(kBaseTag, group));
  LODBAKE_ASSIGN_OR_RETURN(const Section* vspl, decoded.require(kVsplTag, group));
  LODBAKE_ASSIGN_OR_RETURN(ProgressiveMesh pm,
                           decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size));
  return std::make_unique<ProgressiveMesh>(std::move(pm));
}

// WEDG over `pm`: its wedges and the corner lookup every mesh made of the
// PM's face slots takes its corners' wedges from. A WEDG that does not
// replay with the PM (another progressive mesh's) is kInvalidInput.
Status load_corner_wedges(const ProgressiveMesh& pm, const Section& wedg,
                          std::unique_ptr<PmWedges>* wedges, std::optional<CornerWedges>* lookup) {
  LODBAKE_ASSIGN_OR_RETURN(PmWedges decoded, decode_wedg(wedg.data, wedg.size));
  *wedges = std::make_unique<PmWedges>(std::move(decoded));
  Result<CornerWedges> made = CornerWedges::create(pm, **wedges);
  if (!made.is_ok())
    return Status(made.status().kind(), "section WEDG: " + made.status().message());
  lookup->emplace(std::move(made).value());
  return Status::ok();
}

// VSPL and WEDG beside the hierarchy, and the front rule over them. A PM
// or WEDG that is not the hierarchy's own is kInvalidInput.
Result<FrontWedges> load_front_wedges(const Container& decoded, uint32_t group,
                                      const VertexHierarchy& h, const Section& wedg,
                                      std::unique_ptr<ProgressiveMesh>* pm,
                                      std::unique_ptr<PmWedges>* wedges) {
  LODBAKE_ASSIGN_OR_RETURN(*pm, load_pm(decoded, group));
  LODBAKE_ASSIGN_OR_RETURN(PmWedges decoded_wedges, decode_wedg(wedg.data, wedg.size));
  *wedges = std::make_unique<PmWedges>(std::move(decoded_wedges));
  Result<FrontWedges> front = FrontWedges::create(h, **pm, **wedges);
  if (!front.is_ok())
    return Status(front.status().kind(), "section WEDG: " + front.status().message());
  return front;
}

Result<StreamStructure> stream_structure(const Container& decoded, uint32_t group,
                                         bool with_wedges) {
  LODBAKE_ASSIGN_OR_RETURN(const Section* rfin, decoded.require(kRfinTag, group));
  StreamStructure out;
  LODBAKE_ASSIGN_OR_RETURN(out.h, load_hierarchy(decoded, group));
  LODBAKE_ASSIGN_OR_RETURN(std::vector<RfinRecord> records,
                           decode_rfin_records(rfin->data, rfin->size, *out.h));
  LODBAKE_ASSIGN_OR_RETURN(StreamHierarchy db, StreamHierarchy::create(*out.h, std::move(records)));
  out.db = std::make_unique<StreamHierarchy>(std::move(db));
  const Section* wedg = decoded.find(kWedgTag, group);
  if (with_wedges && wedg != nullptr && decoded.find(kVsplTag, group) != nullptr) {
    LODBAKE_ASSIGN_OR_RETURN(
        FrontWedges front, load_front_wedges(decoded, group, *out.h, *wedg, &out.pm, &out.wedges));
    out.front.emplace(std::move(front));
    Result<StreamWedgeTable> table = stream_wedge_table(*out.h, *out.pm, *out.wedges);
    if (!table.is_ok())
      return Status(table.status().kind(), "section WEDG: " + table.status().message());
    LODBAKE_RETURN_IF_ERROR(out.db->set_wedges(std::move(table).value()));
  }
  return out;
}

// Runs `load` with out of memory turned into kRuntime.
template <typename T, typename F>
Result<T> guarded(F&& load) {
  try {
    return load();
  } catch (const std::bad_alloc&) {
    return runtime_error("out of memory loading the container");
  }
}

}  // namespace

Result<uint32_t> structure_group(const OpenedContainer& file, ReplayStructure kind) {
  const Needs needs = needs_of(kind);
  return file.group_with(needs.tags, needs.purpose, needs.producer);
}

Result<VhierStructure> load_vhier_structure(const Container& decoded, uint32_t group) {
  return guarded<VhierStructure>([&]() -> Result<VhierStructure> {
    LODBAKE_ASSIGN_OR_RETURN(const Section* rfin, decoded.require(kRfinTag, group));
    VhierStructure out;
    LODBAKE_ASSIGN_OR_RETURN(out.h, load_hierarchy(decoded, group));
    LODBAKE_ASSIGN_OR_RETURN(out.data, decode_rfin(rfin->data, rfin->size, *out.h));
    LODBAKE_ASSIGN_OR_RETURN(SelectiveRefiner refiner, SelectiveRefiner::create(*out.h));
    out.refiner.emplace(std::move(refiner));
    const Section* wedg = decoded.find(kWedgTag, group);
    if (wedg != nullptr && decoded.find(kVsplTag, group) != nullptr) {
      LODBAKE_ASSIGN_OR_RETURN(FrontWedges front, load_front_wedges(decoded, group, *out.h, *wedg,
                                                                    &out.pm, &out.wedges));
      out.front.emplace(std::move(front));
    }
    return out;
  });
}

Result<DagStructure> load_dag_structure(const Container& decoded, uint32_t group) {
  return guarded<DagStructure>([&]() -> Result<DagStructure> {
    LODBAKE_ASSIGN_OR_RETURN(const Section* dage, decoded.require(kDageTag, group));
    DagStructure out;
    LODBAKE_ASSIGN_OR_RETURN(out.pm, load_pm(decoded, group));
    LODBAKE_ASSIGN_OR_RETURN(VsplitDag dag, decode_dage(dage->data, dage->size));
    out.dag = std::make_unique<VsplitDag>(std::move(dag));
    if (const Section* wedg = decoded.find(kWedgTag, group)) {
      LODBAKE_RETURN_IF_ERROR(load_corner_wedges(*out.pm, *wedg, &out.wedges, &out.lookup));
    }
    return out;
  });
}

Result<FanStructure> load_fan_structure(const Container& decoded, uint32_t group) {
  return guarded<FanStructure>([&]() -> Result<FanStructure> {
    LODBAKE_ASSIGN_OR_RETURN(const Section* base, decoded.require(kBaseTag, group));
    LODBAKE_ASSIGN_OR_RETURN(const Section* fanh, decoded.require(kFanhTag, group));
    FanStructure out;
    LODBAKE_ASSIGN_OR_RETURN(out.input, decode_base(base->data, base->size));
    LODBAKE_ASSIGN_OR_RETURN(out.h, decode_fanh(fanh->data, fanh->size));
    LODBAKE_ASSIGN_OR_RETURN(FanReplay replay, FanReplay::create(out.input, out.h));
    out.replay.emplace(std::move(replay));
    if (const Section* wedg = decoded.find(kWedgTag, group)) {
      LODBAKE_ASSIGN_OR_RETURN(PmWedges wedges, decode_wedg(wedg->data, wedg->size));
      out.wedges = std::make_unique<PmWedges>(std::move(wedges));
      Result<FanWedges> fronts = FanWedges::create(out.input, out.h, *out.wedges);
      if (!fronts.is_ok())
        return Status(fronts.status().kind(), "section WEDG: " + fronts.status().message());
      out.fronts.emplace(std::move(fronts).value());
    }
    return out;
  });
}

Result<SetsStructure> load_sets_structure(const Container& decoded, uint32_t group) {
  return guarded<SetsStructure>([&]() -> Result<SetsStructure> {
    LODBAKE_ASSIGN_OR_RETURN(const Section* sets, decoded.require(kSetsTag, group));
    SetsStructure out;
    LODBAKE_ASSIGN_OR_RETURN(out.pm, load_pm(decoded, group));
    LODBAKE_ASSIGN_OR_RETURN(SetsGraph graph, decode_sets(sets->data, sets->size));
    out.graph = std::make_unique<SetsGraph>(std::move(graph));
    if (const Section* wedg = decoded.find(kWedgTag, group))
      LODBAKE_RETURN_IF_ERROR(load_corner_wedges(*out.pm, *wedg, &out.wedges, &out.lookup));
    return out;
  });
}

Result<StreamStructure> load_stream_structure(const Container& decoded, uint32_t group) {
  return guarded<StreamStructure>([&] { return stream_structure(decoded, group, true); });
}

Result<VtreesStructure> load_vtrees_structure(const Container& decoded, uint32_t group) {
  return guarded<VtreesStructure>([&]() -> Result<VtreesStructure> {
    LODBAKE_ASSIGN_OR_RETURN(const Section* vtre, decoded.require(kVtreTag, group));
    // The same dequantized refinement data as mode stream's server; VTRE is
    // decoded after, as the mode always did.
    LODBAKE_ASSIGN_OR_RETURN(StreamStructure refinement, stream_structure(decoded, group, false));
    VtreesStructure out;
    LODBAKE_ASSIGN_OR_RETURN(VertexTrees trees, decode_vtre(vtre->data, vtre->size));
    out.trees = std::make_unique<VertexTrees>(std::move(trees));
    LODBAKE_ASSIGN_OR_RETURN(
        VtreesDatabase db, VtreesDatabase::create(*out.trees, *refinement.h, refinement.db->data));
    out.db = std::make_unique<VtreesDatabase>(std::move(db));
    out.h = std::move(refinement.h);
    const Section* wedg = decoded.find(kWedgTag, group);
    if (wedg != nullptr && decoded.find(kVsplTag, group) != nullptr) {
      LODBAKE_ASSIGN_OR_RETURN(FrontWedges front, load_front_wedges(decoded, group, *out.h, *wedg,
                                                                    &out.pm, &out.wedges));
      out.front = std::make_unique<FrontWedges>(std::move(front));
      Result<VtreesWedgeTable> table = vtrees_wedge_table(*out.trees, *out.pm, *out.wedges);
      if (!table.is_ok())
        return Status(table.status().kind(), "section WEDG: " + table.status().message());
      LODBAKE_RETURN_IF_ERROR(out.db->set_wedges(std::move(table).value()));
      LODBAKE_ASSIGN_OR_RETURN(
          VtreesFrontReference reference,
          VtreesFrontReference::create(*out.h, *out.trees, *out.db->wedges, *out.front));
      out.reference.emplace(std::move(reference));
    }
    return out;
  });
}

}  // namespace lodbake
