#include "lib/replay/stream_wedge_check.h"

#include <new>

#include "lib/replay/replay_check.h"

namespace lodbake {

std::vector<std::string> check_stream_wedges(const StreamClient& client, const StreamHierarchy& db,
                                             const FrontWedges& front, const PmWedges& wedges) {
  try {
    Result<std::vector<std::array<uint32_t, 3>>> corners = client.corner_wedges();
    if (!corners.is_ok()) return {corners.status().message()};
    std::vector<std::string> problems = corner_wedge_problems(corners.value(), wedges);
    const std::vector<Triangle> faces = client.refiner().triangles();
    const std::vector<uint32_t> origins = client.refiner().face_origins();
    const auto base = static_cast<uint32_t>(db.h->base.triangles.size());
    size_t differ = 0, first = 0;
    for (size_t f = 0; f < faces.size(); ++f) {
      const WedgeFace face = client.face_of(origins[f]);
      uint32_t origin = face.tree;
      if (face.heap != 0) {
        const uint32_t s = db.node_of({face.tree, face.heap});
        origin = s == kNoNode ? kNoVertex : base + 2 * s + face.side;
      }
      for (int k = 0; k < 3; ++k) {
        const uint32_t node = db.node_of(client.id_of(faces[f][k]));
        const uint32_t want = node == kNoNode ? kNoVertex : front.wedge(origin, node);
        if (want != corners.value()[f][k]) {
          if (differ++ == 0) first = f;
        }
      }
    }
    if (differ != 0) {
      problems.push_back(std::to_string(differ) +
                         " corners with another wedge than the server's front gives (first in "
                         "face " +
                         std::to_string(first) + ")");
    }
    return problems;
  } catch (const std::bad_alloc&) {
    return {"out of memory checking the client's corner wedges"};
  }
}

}  // namespace lodbake
