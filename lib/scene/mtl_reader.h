// Wavefront material libraries (.mtl, Appendix B1 of the Advanced Visualizer
// manual) as plain data, for the OBJ scene reader. Parses from memory.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/support/status.h"
#include "lib/meshio/import_report.h"

namespace lodbake {

using MtlColour = std::array<float, 3>;

// The statements of one 'newmtl' lodbake maps onto glTF; absent ones stay empty.
struct MtlMaterial {
  std::string name;
  std::optional<MtlColour> kd;     // diffuse colour
  std::optional<MtlColour> ks;     // specular colour
  std::optional<MtlColour> ke;     // emissive colour
  std::optional<float> ns;         // specular exponent
  std::optional<float> dissolve;   // 'd' (1 opaque), or 1 - 'Tr'
  std::optional<float> metallic;   // 'Pm' (PBR extension of the format)
  std::optional<float> roughness;  // 'Pr'
  std::string diffuse_map;         // 'map_Kd' file name, options removed
  std::string normal_map;          // 'norm', 'map_Bump' or 'bump' file name
  std::string emissive_map;        // 'map_Ke'
};

/// Every 'newmtl' block of the MTL text at `data`, in file order. Lenient,
/// as the OBJ reader is not allowed to fail on a material: statements it
/// does not map, and statements it cannot read (a malformed number, a
/// statement before any 'newmtl'), are counted in one note per keyword in
/// `report` (not null). Fails only on binary data (a NUL byte) and when
/// memory runs out.
Result<std::vector<MtlMaterial>> parse_mtl(const uint8_t* data, size_t size, ImportReport* report);

}  // namespace lodbake
