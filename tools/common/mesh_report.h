// How tools present the import, check and repair reports: aligned text for
// people, JSON objects for machines. Presentation only; the reports
// themselves come from lib/.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "lib/check/mesh_check.h"
#include "lib/meshio/import_report.h"
#include "lib/repair/mesh_repair.h"
#include "tools/common/cli.h"

namespace lodbake::cli {

nlohmann::json to_json(const MeshCheckReport& report);
nlohmann::json to_json(const ImportReport& report);
nlohmann::json to_json(const RepairReport& report);
nlohmann::json to_json(const Vec3f& v);

// "label         value" lines of the check report.
void print_check(std::ostream& out, const MeshCheckReport& report);

// The import notes and repair actions as "tool: FILE: ..." lines on stderr
// (nothing is dropped silently), unless --quiet.
void print_import_notes(const Tool& tool, const std::string& file, const ImportReport& report);
void print_repair_actions(const Tool& tool, const std::string& file, const RepairReport& report);

// `text` with every byte that is not part of valid UTF-8 replaced by U+FFFD,
// for strings that must be valid UTF-8 (META) but come from file names.
std::string to_valid_utf8(const std::string& text);

// A float printed as the shortest text that reads back to the same value.
std::string format_float(float value);

}  // namespace lodbake::cli
