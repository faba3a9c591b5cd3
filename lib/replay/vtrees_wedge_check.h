// What --validate asks of the corner wedges of a vertex-tree client's
// triangles: the checks of every asset mesh (corner_wedge_problems()), and
// that each corner has the wedge the whole hierarchy's FrontWedges gives
// the same face slot at the same node, so the records' wedge data lose
// nothing.
#pragma once

#include <string>
#include <vector>

#include "formats/mesh/pm_wedges.h"
#include "lib/replay/vtrees_client.h"
#include "lib/replay/vtrees_wedges.h"

namespace lodbake {

/// One line per kind of problem with `client`'s corner wedges, with the
/// count and the first triangle; empty when there is none.
std::vector<std::string> check_vtrees_wedges(const VtreesClient& client,
                                             const VtreesFrontReference& reference,
                                             const PmWedges& wedges);

}  // namespace lodbake
