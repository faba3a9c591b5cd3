// Loading what each replay mode runs on from an opened container: the
// group that holds the mode's sections, their payloads decoded and the
// runtime structures built over them. lodbake-replay, `lodbake-inspect
// --validate` (structure_validation.h) and the consumer fuzz target all
// load through these, so that a file --validate passes is a file the modes
// accept. Every failure is a Status: damaged data is kInvalidInput (with
// the decoder's or the runtime's message), a missing section LBK-E024,
// out of memory kRuntime.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "formats/mesh/fan_hierarchy.h"
#include "formats/mesh/pm_wedges.h"
#include "formats/mesh/progressive_mesh.h"
#include "formats/mesh/triangle_mesh.h"
#include "formats/mesh/vertex_hierarchy.h"
#include "formats/mesh/vertex_trees.h"
#include "formats/mesh/vsplit_dag.h"
#include "formats/sections/open_container.h"
#include "formats/sections/rfin.h"
#include "formats/sections/sets.h"
#include "formats/support/status.h"
#include "lib/fanmerge/fan_wedges.h"
#include "lib/hierarchy/front_wedges.h"
#include "lib/hierarchy/selective_refiner.h"
#include "lib/replay/fan_replay.h"
#include "lib/replay/stream_server.h"
#include "lib/replay/vtrees_server.h"

namespace lodbake {

/// The structures the replay modes run on.
enum class ReplayStructure { kVhier, kDag, kFan, kSets, kStream, kVtrees };

/// The first group of `file` that holds every section `kind` needs
/// (OpenedContainer::group_with() with the mode's wording, e.g. "mode
/// vhier needs BASE + VHIE + RFIN (lodbake-hierarchy --sections vhie)").
Result<uint32_t> structure_group(const OpenedContainer& file, ReplayStructure kind);

/// Mode vhier: BASE + VHIE + RFIN, and a SelectiveRefiner at the base mesh.
/// The hierarchy is on the heap so that the refiner's pointer survives moves.
/// With VSPL and WEDG in the group (an asset's hierarchy), also the
/// wedges of every front: the VSPL must then be the hierarchy's own
/// progressive mesh (FrontWedges::create()), or the load fails.
struct VhierStructure {
  std::unique_ptr<VertexHierarchy> h;
  std::vector<NodeRefinement> data;
  std::optional<SelectiveRefiner> refiner;
  std::unique_ptr<ProgressiveMesh> pm;  // with wedges only
  std::unique_ptr<PmWedges> wedges;
  std::optional<FrontWedges> front;
};
Result<VhierStructure> load_vhier_structure(const Container& decoded, uint32_t group);

/// Mode dag: the progressive mesh (BASE + VSPL) and its split DAG (DAGE).
/// DagReplay::create() over them is the mode's own step.
/// With WEDG in the group (an asset's hierarchy), also the corner wedges
/// of every cut (CornerWedges over the PM; a WEDG that does not replay
/// with the PM fails the load).
struct DagStructure {
  std::unique_ptr<ProgressiveMesh> pm;
  std::unique_ptr<VsplitDag> dag;
  std::unique_ptr<PmWedges> wedges;
  std::optional<CornerWedges> lookup;
};
Result<DagStructure> load_dag_structure(const Container& decoded, uint32_t group);

/// Mode fan: BASE and FANH, and the replay at the coarsest mesh
/// (FanReplay::create(), which fails when the merges cannot all be made).
/// With WEDG in the group (an asset's fan), also the wedges of every front:
/// WEDG must then give BASE's own corners and follow FANH's steps
/// (FanWedges::create()), or the load fails.
struct FanStructure {
  TriangleMesh input;
  FanHierarchy h;
  std::optional<FanReplay> replay;
  std::unique_ptr<PmWedges> wedges;
  std::optional<FanWedges> fronts;
};
Result<FanStructure> load_fan_structure(const Container& decoded, uint32_t group);

/// Mode sets: the progressive mesh (BASE + VSPL) and its strip graph
/// (SETS). SetsReplay::create() over them is the mode's own step.
/// With WEDG in the group (an asset's strips), also the corner wedges of
/// every recovered LoD (CornerWedges over the PM; a WEDG that is not that
/// VSPL's, so does not replay with it, fails the load).
struct SetsStructure {
  std::unique_ptr<ProgressiveMesh> pm;
  std::unique_ptr<SetsGraph> graph;
  std::unique_ptr<PmWedges> wedges;
  std::optional<CornerWedges> lookup;
};
Result<SetsStructure> load_sets_structure(const Container& decoded, uint32_t group);

/// Mode stream's database: the hierarchy (BASE + VHIE) and its RFIN records
/// as StreamHierarchy::create() takes them. With VSPL and WEDG in the
/// group (an asset's hierarchy), the database also carries the wedges
/// (stream_wedge_table(), StreamHierarchy::set_wedges()), and `front`
/// gives every front's corner wedges over the whole hierarchy, for
/// --validate; a VSPL that is not the hierarchy's own fails the load.
struct StreamStructure {
  std::unique_ptr<VertexHierarchy> h;  ///< db points at it
  std::unique_ptr<StreamHierarchy> db;
  std::unique_ptr<ProgressiveMesh> pm;  // with wedges only
  std::unique_ptr<PmWedges> wedges;
  std::optional<FrontWedges> front;
};
Result<StreamStructure> load_stream_structure(const Container& decoded, uint32_t group);

/// Mode vtrees' database: the hierarchy, the stream's dequantized
/// refinement data and the vertex trees (VTRE) checked against them by
/// VtreesDatabase::create(). With VSPL and WEDG in the group (an asset's
/// hierarchy), the database also carries the wedges (vtrees_wedge_table(),
/// VtreesDatabase::set_wedges()) and `reference` gives every corner's wedge
/// by FrontWedges over the whole hierarchy, for --validate; the VSPL must
/// be the trees' own progressive mesh, or the load fails.
struct VtreesStructure {
  std::unique_ptr<VertexHierarchy> h;
  std::unique_ptr<VertexTrees> trees;  ///< db points at it
  std::unique_ptr<VtreesDatabase> db;
  std::unique_ptr<ProgressiveMesh> pm;  // with wedges only
  std::unique_ptr<PmWedges> wedges;
  std::unique_ptr<FrontWedges> front;  ///< reference points at it
  std::optional<VtreesFrontReference> reference;
};
Result<VtreesStructure> load_vtrees_structure(const Container& decoded, uint32_t group);

}  // namespace lodbake
