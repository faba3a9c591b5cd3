// What --validate asks of the corner wedges of a streamed client's mesh:
// the checks of every asset mesh (corner_wedge_problems()), and that each
// corner has the wedge the server's whole hierarchy gives the same face at
// the same node (FrontWedges), so the packets' wedge data lose nothing.
#pragma once

#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "lib/hierarchy/front_wedges.h"
#include "lib/replay/stream_client.h"
#include "lib/replay/stream_server.h"

namespace lodbake {

/// One line per kind of problem with `client`'s corner wedges (its
/// corner_wedges() against `front`, the wedges of `db`'s complete
/// hierarchy), with the count and the first face; empty when there is none.
std::vector<std::string> check_stream_wedges(const StreamClient& client, const StreamHierarchy& db,
                                             const FrontWedges& front, const PmWedges& wedges);

}  // namespace lodbake
