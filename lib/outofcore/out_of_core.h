// Simplification of a mesh larger than memory, in three stages that can run
// as separate processes on separate machines sharing a work folder:
//   split:  stream the PLY or OBJ input, cut it into spatial blocks
//           (block_partition.h), write each block's triangles and vertices
//           (with their input ids) to block_N.in, and the plan (plan.json);
//   block:  simplify one block in core with its border locked, so that the
//           cut stays where its neighbour expects it (block_N.out);
//   merge:  stitch the simplified blocks by input vertex id and simplify
//           the stitched mesh, borders free, to the final target.
// The same stages in one process give the same bytes (docs/simplify.md,
// "Larger than memory"). Only the split's vertex positions (12 bytes per
// vertex) are held for the whole input; everything else is per block.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"
#include "lib/simplify/simplify.h"

namespace lodbake {

// Bytes per triangle the in-core engine (without a progressive mesh) and
// its input mesh take at their peak, rounded up from measurements
// (docs/lab/out-of-core.md): the budget of a block and of the merge.
inline constexpr uint64_t kEngineBytesPerTriangle = 180;
// The program itself (code, libraries, thread stacks, allocator slack),
// resident whatever the mesh: about 20 MiB measured, kept out of the blocks'
// share of --memory-limit.
inline constexpr uint64_t kProgramBytes = uint64_t{24} << 20;
// Fine cells along the longest side of the box, to place block borders.
inline constexpr uint32_t kFineGridResolution = 64;
// More blocks than this means a limit far too small for the mesh.
inline constexpr uint32_t kMaxBlocks = 4096;

struct OutOfCoreOptions {
  uint64_t memory_limit = 0;  // bytes
  // Targets (target_ratio, target_triangles, max_error) and engine options;
  // record_pm must be false. lock_border locks the input's own borders in
  // the final pass too.
  SimplifyOptions simplify;
  // Blocks go to this many times the final ratio (more freedom for the
  // merge pass), capped by the memory the merge may take.
  double block_ratio_factor = 2.0;
};

// What the split decided, stored in the work folder as plan.json: the later
// stages read their options from it, so that every machine runs the same
// simplification.
struct OutOfCorePlan {
  uint64_t memory_limit = 0;
  uint64_t input_vertices = 0;       // in the file
  uint64_t referenced_vertices = 0;  // used by a triangle kept
  uint64_t input_triangles = 0;      // triangles kept (after dropping degenerate ones)
  uint64_t dropped_degenerate = 0;   // faces with a repeated vertex
  double diagonal = 0;               // of the referenced vertices' box
  uint64_t block_budget = 0;  // triangles per block at most (unless one fine cell holds more)
  std::vector<uint64_t> block_triangles;
  std::optional<double> block_ratio;        // each block's target ratio (unset: max_error only)
  std::optional<uint64_t> final_triangles;  // the final target (unset: max_error only)
  uint64_t peak_estimate = 0;               // bytes, the largest stage's arrays
  SimplifyOptions simplify;                 // the run's engine options and targets (no callbacks)

  uint32_t block_count() const { return static_cast<uint32_t>(block_triangles.size()); }
};

// Called with a stage's fraction done; may be empty.
using StageProgress = std::function<void(double)>;

/// The work folder's file names.
std::string plan_path(const std::string& work);
std::string block_input_path(const std::string& work, uint32_t block);
std::string block_output_path(const std::string& work, uint32_t block);

/// The split stage: reads `input` (binary or ASCII PLY with triangle faces,
/// or OBJ, its polygons split as in core; kUnsupported for anything else) in three streaming passes
/// and writes every block_N.in, then plan.json, into the existing folder `work`. Fails with
/// kInvalidInput on a malformed file (non-finite coordinates, indices out of range, counts the file
/// cannot hold) and kRuntime when the limit cannot hold the input's positions or the final target.
/// On failure the files it wrote are removed.
Result<OutOfCorePlan> split_input(const std::string& input, const std::string& work,
                                  const OutOfCoreOptions& options, const StageProgress& progress);

/// Reads and checks plan.json.
Result<OutOfCorePlan> read_plan(const std::string& work);

/// The block stage for block `block`: block_N.in to block_N.out.
/// `threads` as SimplifyOptions::threads (the output does not depend on it).
Status simplify_block(const std::string& work, const OutOfCorePlan& plan, uint32_t block,
                      unsigned threads);

struct MergeResult {
  TriangleMesh mesh;
  uint64_t stitched_triangles = 0;  // before the final pass
  SimplifyStats stats;              // of the final pass
};

/// The merge stage: every block_N.out stitched and simplified to the final
/// target.
Result<MergeResult> merge_blocks(const std::string& work, const OutOfCorePlan& plan,
                                 unsigned threads, const StageProgress& progress);

/// Removes the work files of the stages (block files and the plan) from
/// `work`, and the folder itself when that leaves it empty.
void remove_work_files(const std::string& work);

}  // namespace lodbake
