// Fuzz target for --validate's guarantee: a container that
// validate_container() passes is one every consumer accepts. The input is a
// container; the custom mutator changes ONE section's payload (its stored
// bytes, or for a coded section sometimes its decoded payload stored raw)
// and rewrites the container with every CRC and size recomputed, so that
// the container layer accepts it and only the sections' meaning is damaged,
// as a buggy writer or a hand-edited file would. When validation finds
// nothing, every consumer runs as lodbake-replay --validate does (modes
// vhier, dag with its three traversals, fan, sets, stream and vtrees along
// sampled built-in camera paths, every frame checked, an asset fan's corner
// wedges too) and as `lodbake-inspect --extract` does (BASE, STRP, the PM at
// several LoDs); any refusal aborts.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "formats/container/container_reader.h"
#include "formats/container/container_writer.h"
#include "formats/container/section_registry.h"
#include "formats/sections/base.h"
#include "formats/sections/open_container.h"
#include "formats/sections/strp.h"
#include "lib/replay/camera_path.h"
#include "lib/replay/dag_replay.h"
#include "lib/replay/replay_check.h"
#include "lib/replay/sets_replay.h"
#include "lib/replay/stream_session.h"
#include "lib/replay/stream_wedge_check.h"
#include "lib/replay/structure_cross_check.h"
#include "lib/replay/structure_loading.h"
#include "lib/replay/vhier_replay.h"
#include "lib/replay/vtrees_session.h"
#include "lib/simplify/pm_replay.h"
#include "lib/validate/structure_validation.h"

using namespace lodbake;

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size)
    __attribute__((weak));

namespace {

[[noreturn]] void refused(const std::string& consumer, const std::string& why) {
  std::fprintf(stderr, "fuzz invariant failed: --validate passed, %s refused: %s\n",
               consumer.c_str(), why.c_str());
  std::abort();
}

void require_ok(const Status& status, const std::string& consumer) {
  if (!status.is_ok()) refused(consumer, status.message());
}

void require_clean(const std::vector<std::string>& problems, const std::string& consumer) {
  if (!problems.empty()) refused(consumer, problems.front());
}

// A few frames of both built-in paths: enough views to refine and coarsen.
std::vector<CameraFrame> sample_path(const BoundingSphere& sphere) {
  std::vector<CameraFrame> out;
  for (const char* name : {"scan", "orbit"}) {
    Result<std::vector<CameraFrame>> path = builtin_path(name, sphere, 60);
    if (!path.is_ok()) refused("camera path", path.status().message());
    for (size_t i = 0; i < path.value().size(); i += 12)
      out.push_back(path.value()[i]);
  }
  return out;
}

// --validate's cross-structure check of modes vhier and dag: when the
// group's VSPL + DAGE are the hierarchy's (else the check is not made), the
// replay's front against the other structure after every frame.
struct Cross {
  std::optional<VhierStructure> h;
  std::optional<DagStructure> dag;
  std::optional<StructureCrossCheck> check;
};

void prepare_cross(const OpenedContainer& file, uint32_t group, Cross* cross) {
  const Container& c = file.decoded();
  if (c.find(kVhieTag, group) == nullptr || c.find(kRfinTag, group) == nullptr ||
      c.find(kVsplTag, group) == nullptr || c.find(kDageTag, group) == nullptr)
    return;
  Result<VhierStructure> h = load_vhier_structure(c, group);
  Result<DagStructure> dag = load_dag_structure(c, group);
  if (!h.is_ok() || !dag.is_ok()) return;
  cross->h.emplace(std::move(h).value());
  cross->dag.emplace(std::move(dag).value());
  Result<StructureCrossCheck> check =
      StructureCrossCheck::create(*cross->h->h, *cross->dag->pm, *cross->dag->dag);
  if (check.is_ok()) cross->check.emplace(std::move(check).value());
}

void run_vhier(const OpenedContainer& file, uint32_t group) {
  Result<VhierStructure> loaded = load_vhier_structure(file.decoded(), group);
  require_ok(loaded.status(), "mode vhier (load)");
  VhierStructure& s = loaded.value();
  const BoundingSphere sphere = bounding_sphere(s.h->position);
  Cross cross;
  prepare_cross(file, group, &cross);
  for (const CameraFrame& frame : sample_path(sphere)) {
    require_ok(adapt_vhier_frame(&*s.refiner, *s.h, s.data, sphere, frame, {}).status(),
               "mode vhier");
    require_clean(check_vhier_mesh(*s.refiner), "mode vhier --validate");
    if (cross.check) {
      std::vector<uint8_t> flags = cross.check->refiner_splits(*s.refiner);
      const bool own = cross.check->close(&flags);
      require_clean(cross.check->compare(flags, own ? &*s.refiner : nullptr, nullptr),
                    "mode vhier --validate (cross-check)");
    }
  }
}

void run_dag(const OpenedContainer& file, uint32_t group) {
  Result<DagStructure> loaded = load_dag_structure(file.decoded(), group);
  require_ok(loaded.status(), "mode dag (load)");
  const ProgressiveMesh& pm = *loaded.value().pm;
  std::vector<Vec3f> points = pm.base.positions;
  for (const VertexSplit& split : pm.splits)
    points.push_back(split.vt_position);
  const BoundingSphere sphere = bounding_sphere(points);
  for (DagTraversal t :
       {DagTraversal::kPriority, DagTraversal::kLinear, DagTraversal::kConstantTime}) {
    Result<DagReplay> replay = DagReplay::create(pm, *loaded.value().dag);
    require_ok(replay.status(), "mode dag (create)");
    DagReplayOptions options;
    options.traversal = t;
    Cross cross;
    prepare_cross(file, group, &cross);
    for (const CameraFrame& frame : sample_path(sphere)) {
      require_ok(replay.value().adapt(sphere, frame, options).status(), "mode dag");
      require_clean(replay.value().check(), "mode dag --validate");
      if (cross.check) {
        std::vector<uint8_t> flags = cross.check->dag_splits(replay.value().fronts());
        const bool own = cross.check->close(&flags);
        const std::vector<Triangle> cut =
            own ? replay.value().cut_triangles() : std::vector<Triangle>();
        require_clean(cross.check->compare(flags, nullptr, own ? &cut : nullptr),
                      "mode dag --validate (cross-check)");
      }
    }
  }
}

void run_fan(const OpenedContainer& file, uint32_t group) {
  Result<FanStructure> loaded = load_fan_structure(file.decoded(), group);
  require_ok(loaded.status(), "mode fan (load)");
  FanReplay& replay = *loaded.value().replay;
  const BoundingSphere sphere = bounding_sphere(loaded.value().input.positions);
  for (const CameraFrame& frame : sample_path(sphere)) {
    require_ok(replay.adapt(sphere, frame, {}).status(), "mode fan");
    require_clean(replay.check(), "mode fan --validate");
    if (loaded.value().fronts) {
      require_clean(
          check_fan_wedges(replay.runtime(), *loaded.value().fronts, *loaded.value().wedges),
          "mode fan --validate (wedges)");
    }
  }
}

void run_sets(const OpenedContainer& file, uint32_t group) {
  Result<SetsStructure> loaded = load_sets_structure(file.decoded(), group);
  require_ok(loaded.status(), "mode sets (load)");
  Result<SetsReplay> replay = SetsReplay::create(*loaded.value().pm, *loaded.value().graph);
  require_ok(replay.status(), "mode sets (create)");
  for (LodSpacing spacing : {LodSpacing::kLinear, LodSpacing::kExponential}) {
    for (double percent : {20.0, 100.0}) {
      const std::vector<uint32_t> lods =
          recovery_test_lods(replay.value().lod_count(), percent, spacing);
      require_ok(run_sets_test(&replay.value(), lods, true).status(), "mode sets --validate");
    }
  }
}

void run_stream(const OpenedContainer& file, uint32_t group) {
  Result<StreamStructure> loaded = load_stream_structure(file.decoded(), group);
  require_ok(loaded.status(), "mode stream (load)");
  const StreamHierarchy& db = *loaded.value().db;
  Result<StreamSession> session = StreamSession::create(db, {});
  require_ok(session.status(), "mode stream (create)");
  for (const CameraFrame& frame : sample_path(db.sphere)) {
    Result<StreamFrameStats> f = session.value().frame(frame, db.sphere);
    require_ok(f.status(), "mode stream");
    require_clean(check_vhier_mesh(session.value().client().refiner()), "mode stream --validate");
    if (loaded.value().front) {
      require_clean(check_stream_wedges(session.value().client(), db, *loaded.value().front,
                                        *loaded.value().wedges),
                    "mode stream --validate (wedges)");
    }
    if (f.value().missing != 0 || f.value().requests > 1)
      refused("mode stream --validate", "needed splits missing");
  }
}

void run_vtrees(const OpenedContainer& file, uint32_t group) {
  Result<VtreesStructure> loaded = load_vtrees_structure(file.decoded(), group);
  require_ok(loaded.status(), "mode vtrees (load)");
  const VtreesDatabase& db = *loaded.value().db;
  const VertexTrees& trees = *loaded.value().trees;
  Result<VtreesSession> session = VtreesSession::create(db, {});
  require_ok(session.status(), "mode vtrees (create)");
  for (const CameraFrame& frame : sample_path(db.sphere)) {
    VtreesSession& s = session.value();
    require_ok(s.frame(frame, db.sphere).status(), "mode vtrees");
    const VisibleVertexList& list = s.server().list();
    for (uint32_t v = 0; v < trees.positions.size(); ++v) {
      if (s.client().visible_node(v) != list.visible_node(v))
        refused("mode vtrees --validate", "the client's list is not the server's");
    }
    if (sorted_canonical(s.triangles()) != sorted_canonical(list.triangles()))
      refused("mode vtrees --validate", "the client's triangles are not the trees' selection");
  }
}

// lodbake-inspect --extract: BASE, or the strips' mesh, or the PM's LoDs.
void run_extract(const OpenedContainer& file, uint32_t group) {
  const Container& c = file.decoded();
  const Section* base = c.find(kBaseTag, group);
  if (base == nullptr) return;
  Result<TriangleMesh> mesh = decode_base(base->data, base->size);
  require_ok(mesh.status(), "--extract (BASE)");
  if (const Section* strp = c.find(kStrpTag, group)) {
    Result<TriangleStrips> strips = decode_strp(strp->data, strp->size);
    require_ok(strips.status(), "--extract (STRP)");
    require_ok(mesh_from_strips(strips.value(), mesh.value()).status(), "--extract (STRP)");
  }
  if (const Section* vspl = c.find(kVsplTag, group)) {
    Result<ProgressiveMesh> pm =
        decode_progressive_mesh(base->data, base->size, vspl->data, vspl->size);
    require_ok(pm.status(), "--extract --lod (load)");
    const size_t full = pm.value().full_vertex_count();
    const size_t from = pm.value().base.vertex_count();
    for (size_t v : {from, (from + full) / 2, full}) {
      Result<TriangleMesh> lod = mesh_at_lod(pm.value(), v);
      require_ok(lod.status(), "--extract --lod");
      if (v == full) require_ok(map_to_input(pm.value(), lod.value()).status(), "--extract --lod");
    }
  }
}

// Rewrites `c` with section `index`'s stored bytes replaced (CRCs, sizes
// and offsets recomputed by the writer).
Result<Bytes> rewrite(const Container& c, size_t index, Bytes stored, SectionCodec codec,
                      uint64_t decoded_size) {
  ContainerWriter writer;
  for (size_t i = 0; i < c.sections.size(); ++i) {
    const Section& s = c.sections[i];
    if (i == index) {
      LODBAKE_RETURN_IF_ERROR(writer.add_stored_section(s.tag(), std::move(stored), codec,
                                                        decoded_size, s.required(), s.group()));
    } else {
      LODBAKE_RETURN_IF_ERROR(writer.add_stored_section(
          s.tag(), Bytes(s.data, s.data + s.size), static_cast<SectionCodec>(s.entry.codec),
          s.entry.decoded_size, s.required(), s.group()));
    }
  }
  return writer.finish();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Result<OpenedContainer> opened = open_container(Bytes(data, data + size));
  if (!opened.is_ok()) return 0;
  const OpenedContainer& file = opened.value();
  if (!validate_container(file.decoded()).empty()) return 0;
  // Each consumer takes the first group with its sections, as the tools do.
  auto group_of = [&](ReplayStructure kind, uint32_t* group) {
    Result<uint32_t> g = structure_group(file, kind);
    if (g.is_ok()) *group = g.value();
    return g.is_ok();
  };
  uint32_t group = 0;
  if (group_of(ReplayStructure::kVhier, &group)) {
    run_vhier(file, group);
    run_stream(file, group);
  }
  if (group_of(ReplayStructure::kVtrees, &group)) run_vtrees(file, group);
  if (group_of(ReplayStructure::kDag, &group)) run_dag(file, group);
  if (group_of(ReplayStructure::kFan, &group)) run_fan(file, group);
  if (group_of(ReplayStructure::kSets, &group)) run_sets(file, group);
  for (uint32_t g = 0; g < std::max<uint32_t>(file.group_count(), 1); ++g)
    run_extract(file, g);
  return 0;
}

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t max_size,
                                          unsigned int seed) {
  Result<OpenedContainer> opened = open_container(Bytes(data, data + size));
  if (!opened.is_ok() || opened.value().stored().sections.empty())
    return LLVMFuzzerMutate(data, size, max_size);
  const Container& stored = opened.value().stored();
  std::minstd_rand rng(seed);
  const size_t index = rng() % stored.sections.size();
  const Section& s = stored.sections[index];
  const Section& d = opened.value().decoded().sections[index];
  // A coded section: half the time its decoded payload, mutated and stored
  // raw (the structure's own fields), else its coded bytes.
  const bool raw = s.entry.codec != 0 && rng() % 2 == 0;
  const Section& from = raw ? d : s;
  Bytes payload(from.data, from.data + from.size);
  // Whole-payload mutations mostly break the decoder; a word copied from
  // elsewhere in the payload or nudged by a few keeps the layout and
  // changes what it says (an index, a count, a label), which is the damage
  // only the deep checks can see.
  const unsigned kind = rng() % 3;
  if (kind != 0 && payload.size() >= 8) {
    const size_t words = payload.size() / 4;
    const size_t at = 4 * (rng() % words);
    uint32_t word;
    std::memcpy(&word, payload.data() + at, 4);
    if (kind == 1) {
      std::memcpy(&word, payload.data() + 4 * (rng() % words), 4);
    } else {
      const uint32_t delta = 1 + rng() % 3;
      word = rng() % 2 == 0 ? word + delta : word - delta;
    }
    std::memcpy(payload.data() + at, &word, 4);
  } else {
    const size_t room = payload.size() + 64;
    payload.resize(room);
    payload.resize(LLVMFuzzerMutate(payload.data(), from.size, room));
  }
  const size_t n = payload.size();
  const SectionCodec codec = raw ? SectionCodec::kRaw : static_cast<SectionCodec>(s.entry.codec);
  const uint64_t decoded_size = codec == SectionCodec::kRaw ? n : s.entry.decoded_size;
  Result<Bytes> out = rewrite(stored, index, std::move(payload), codec, decoded_size);
  if (!out.is_ok() || out.value().size() > max_size) return size;
  std::memcpy(data, out.value().data(), out.value().size());
  return out.value().size();
}
