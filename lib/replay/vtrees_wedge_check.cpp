#include "lib/replay/vtrees_wedge_check.h"

#include <new>

#include "lib/replay/replay_check.h"

namespace lodbake {

std::vector<std::string> check_vtrees_wedges(const VtreesClient& client,
                                             const VtreesFrontReference& reference,
                                             const PmWedges& wedges) {
  try {
    Result<std::vector<std::array<uint32_t, 3>>> corners = client.corner_wedges();
    if (!corners.is_ok()) return {corners.status().message()};
    std::vector<std::string> problems = corner_wedge_problems(corners.value(), wedges);
    std::vector<uint32_t> slots;
    const std::vector<Triangle> tris = client.triangles(&slots);
    size_t differ = 0, first = 0;
    for (size_t f = 0; f < tris.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t want = reference.wedge(slots[f], client.visible_node(tris[f][k]));
        if (want == kNoVertex || want != corners.value()[f][k]) {
          if (differ++ == 0) first = f;
        }
      }
    }
    if (differ != 0) {
      problems.push_back(std::to_string(differ) +
                         " corners with another wedge than the server's front gives (first in "
                         "triangle " +
                         std::to_string(first) + ")");
    }
    return problems;
  } catch (const std::bad_alloc&) {
    return {"out of memory checking the client's corner wedges"};
  }
}

}  // namespace lodbake
