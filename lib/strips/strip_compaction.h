// Shortening a strip's sequence after a contraction without changing what
// it describes: the SETS paper's removal of sub-sequences (Belmonte et al.
// 2006, section 3.2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lodbake {

/// Removes vertices from `sequence` (a strip in the TriangleStrips window
/// rule) while its non-degenerate triangles stay exactly the same, each with
/// its orientation: runs of two vertices whose removal only drops and
/// creates degenerate windows (even-length removals keep every later
/// window's parity), and everything after the last non-degenerate window.
/// A sequence without any non-degenerate window becomes empty. Linear time.
void compact_strip(std::vector<uint32_t>* sequence);

/// The same compaction, appending to `changed` (which it does not clear) a
/// superset of the ids whose successor runs it may change: every removed
/// id, and every id that is left before a removal. An id not appended has
/// the same successor at each of its occurrences (lib/strips/sets_build.cpp
/// re-records only the ids appended).
void compact_strip(std::vector<uint32_t>* sequence, std::vector<uint32_t>* changed);

/// The same on sequence[0, size), in place; returns the new size.
size_t compact_strip(uint32_t* sequence, size_t size, std::vector<uint32_t>* changed);

}  // namespace lodbake
