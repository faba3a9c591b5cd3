// The section tags this build of lodbake knows how to read. The reader uses
// the list to decide "unknown required section" (LBK-E022); inspect uses the
// descriptions; every writer takes a known section's required flag from here
// (docs/format.md section 4 has the same table). A tag is added here in the
// same change that adds its decoder under formats/sections/.
#pragma once

#include <string_view>
#include <vector>

namespace lodbake {

inline constexpr char kMetaTag[] = "META";  ///< JSON provenance (formats/sections/meta.h)
inline constexpr char kBaseTag[] = "BASE";  ///< base triangle mesh (formats/sections/base.h)
inline constexpr char kVsplTag[] = "VSPL";  ///< vertex-split records (formats/sections/vspl.h)
inline constexpr char kDageTag[] = "DAGE";  ///< DAG of vertex splits (formats/sections/dage.h)
inline constexpr char kVtreTag[] = "VTRE";  ///< vertex trees (formats/sections/vtre.h)
inline constexpr char kVhieTag[] = "VHIE";  ///< balanced vertex hierarchy (formats/sections/vhie.h)
inline constexpr char kRfinTag[] = "RFIN";  ///< per-split refinement data (formats/sections/rfin.h)
inline constexpr char kFanhTag[] = "FANH";  ///< fan-merge hierarchy (formats/sections/fanh.h)
inline constexpr char kStrpTag[] = "STRP";  ///< triangle strips (formats/sections/strp.h)
inline constexpr char kSetsTag[] = "SETS";  ///< SETS strip graph (formats/sections/sets.h)
inline constexpr char kScneTag[] = "SCNE";  ///< the asset's scene (formats/sections/scne.h)
inline constexpr char kWedgTag[] = "WEDG";  ///< a PM's wedges (formats/sections/wedg.h)

struct SectionKind {
  const char* tag;          ///< 4 printable ASCII characters
  const char* description;  ///< one line, for listings
  /// The required flag lodbake writes: set when a reader that skipped the
  /// section would take the file for something it is not.
  bool required;
};

/// Every known section kind, in a fixed order (the order inspect lists them).
const std::vector<SectionKind>& known_section_kinds();

/// True when `tag` is in known_section_kinds().
bool is_known_section(std::string_view tag);

/// The description of a known tag, or nullptr.
const char* section_description(std::string_view tag);

/// The required flag of a known tag (SectionKind::required); false for a
/// tag this build does not know (writers copy such sections' flags as found).
bool section_required(std::string_view tag);

}  // namespace lodbake
