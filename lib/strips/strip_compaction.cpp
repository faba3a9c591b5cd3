// Sub-sequence removal of the SETS model (Belmonte, Aguado, Sancho 2006,
// section 3.2): after vertex a is replaced by b in a strip, sub-sequences
// may go when (a) an even number of vertices is removed and (b) the rest
// describes no triangle that was not there.
//
// Choices where the paper is vague:
// - Condition (b) is read strictly: every window that disappears and every
//   window that the removal creates must be degenerate, so the set of
//   non-degenerate triangles (with orientation) is exactly kept.
// - Removals are pairs of neighbours, found greedily left to right; after a
//   removal the scan steps back three places, since only pairs whose
//   six-vertex neighbourhood spans the new junction can have become
//   removable. Longer even runs are removed as successive pairs. Linear
//   time: each removal costs at most three steps back.
// - The tail after the last non-degenerate window goes whatever its length:
//   no later window's parity depends on it (the paper's Figure 1 drops one
//   vertex at LoD 4 the same way).
#include "lib/strips/strip_compaction.h"

#include "formats/sections/strp.h"

namespace lodbake {
namespace {

bool degenerate(uint32_t a, uint32_t b, uint32_t c) {
  return !is_real_triangle(a, b, c);
}

// Without `changed`, the calls that note ids compile away.
template <bool kNote>
size_t compact(uint32_t* s, size_t size, std::vector<uint32_t>* changed) {
  // Tail: keep up to the last non-degenerate window.
  size_t n = size;
  while (n >= 3 && degenerate(s[n - 3], s[n - 2], s[n - 1]))
    --n;
  if (n < 3) {
    if (kNote) changed->insert(changed->end(), s, s + size);
    return 0;
  }
  if (kNote && n < size) changed->insert(changed->end(), s + (n - 1), s + size);
  // The sequence is s[0, w) followed by s[r, n); the pair considered is
  // (s[r], s[r + 1]).
  size_t w = 0, r = 0;
  while (r < n) {
    if (r + 1 < n) {
      const bool l1 = w >= 1, l2 = w >= 2, r2 = r + 2 < n, r3 = r + 3 < n;
      const uint32_t x = s[r], y = s[r + 1];
      const uint32_t p1 = l1 ? s[w - 1] : 0, p2 = l2 ? s[w - 2] : 0;
      const uint32_t q2 = r2 ? s[r + 2] : 0, q3 = r3 ? s[r + 3] : 0;
      const bool removable = (!l2 || degenerate(p2, p1, x)) && (!l1 || degenerate(p1, x, y)) &&
                             (!r2 || degenerate(x, y, q2)) && (!r3 || degenerate(y, q2, q3)) &&
                             (!(l2 && r2) || degenerate(p2, p1, q2)) &&
                             (!(l1 && r3) || degenerate(p1, q2, q3));
      if (removable) {
        if (kNote) {
          changed->push_back(x);
          changed->push_back(y);
          if (l1) changed->push_back(p1);
        }
        r += 2;
        for (int k = 0; k < 3 && w > 0; ++k)
          s[--r] = s[--w];
        continue;
      }
    }
    s[w++] = s[r++];
  }
  return w;
}

}  // namespace

void compact_strip(std::vector<uint32_t>* sequence) {
  sequence->resize(compact<false>(sequence->data(), sequence->size(), nullptr));
}

void compact_strip(std::vector<uint32_t>* sequence, std::vector<uint32_t>* changed) {
  sequence->resize(compact<true>(sequence->data(), sequence->size(), changed));
}

size_t compact_strip(uint32_t* sequence, size_t size, std::vector<uint32_t>* changed) {
  return compact<true>(sequence, size, changed);
}

}  // namespace lodbake
