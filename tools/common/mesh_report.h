// How tools present the import, check and repair reports: aligned text for
// people, JSON objects for machines. Presentation only; the reports
// themselves come from lib/.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

#include "formats/sections/meta.h"
#include "lib/check/mesh_check.h"
#include "lib/ingest/load_mesh.h"
// meta_input() and to_valid_utf8(), which the tools share with lodbake-bake.
#include "lib/ingest/meta_input.h"
#include "lib/meshio/import_report.h"
#include "lib/repair/mesh_repair.h"
#include "tools/common/cli.h"

namespace lodbake::cli {

nlohmann::json to_json(const MeshCheckReport& report);
nlohmann::json to_json(const ImportReport& report);
nlohmann::json to_json(const RepairReport& report);
// The "repairs" object of a tool's JSON report: to_json() of the repair
// that ran (all counts zero when none did), "mode" ("default", "repair" for
// --repair, "strict" for --strict) and "changed" (whether the mesh the tool
// used differs from the one read, unreferenced vertices aside).
nlohmann::json repairs_json(const LoadOptions& options, const LoadedMesh& loaded);
nlohmann::json to_json(const Vec3f& v);

// "label         value" lines of the check report.
void print_check(std::ostream& out, const MeshCheckReport& report);

// The import notes as one "tool: FILE: ...; ..." line on stderr (nothing
// is dropped silently), unless --quiet.
void print_import_notes(const Tool& tool, const std::string& file, const ImportReport& report);
// What a repair did, as one note: "repaired (...): A, B" for the default
// repair, "repair: A, B" (or "repair: nothing to repair") for --repair.
std::string repair_note(const RepairReport& report, bool by_default);

// Whether a tool's input is a lodbake container rather than a mesh: its
// magic bytes, or a `.lbk` name (so that a container whose header is broken
// gets the container reader's error, not "cannot tell the mesh format").
// `bytes` is the file's content when already read, else null.
bool is_container_input(const std::string& path, const Bytes* bytes = nullptr);

// Loads a tool's input mesh the way every baking tool does and prints
// either the one error line, or at most one note line (import notes, seam
// split, repair, unreferenced vertices dropped) and a warning per problem
// the policy lets through. --strict with --repair is a usage error. Returns
// 0, or the exit code after printing the error.
int load_input(const Tool& tool, const std::string& path, const LoadOptions& options,
               LoadedMesh* loaded);

// Checks a --quantize BITS value (1..30 bits, formats/support/quantization.h)
// when the option was given; the usage error's exit code otherwise.
std::optional<int> check_quantize_bits(const Tool& tool, int bits);

// A float printed as the shortest text that reads back to the same value.
std::string format_float(float value);

}  // namespace lodbake::cli
