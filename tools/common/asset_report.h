// What the builder tools say when they build over a whole asset
// (lib/scene/asset_build.h): the input record for META, the one warning
// about attributes, and the per-group report.
#pragma once

#include <string>

#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "lib/scene/asset_build.h"
#include "tools/common/cli.h"

namespace lodbake::cli {

// Until structures carry attributes, every build over an asset says so once.
inline constexpr char kPositionsOnly[] =
    "the structures hold positions only: the asset's attributes and materials stay in its SCNE "
    "section, not in the levels they refine to (attribute-aware structures: not yet)";

// META's input for an asset: a container's own record of its input (so all
// the containers of one asset merge), else the file's base name, SHA-256
// and size.
MetaInput asset_meta_input(const std::string& path, const Bytes& bytes);

// The report of a build over an asset, text or JSON; returns 0.
int print_asset_build(const Tool& tool, const char* schema, const std::string& input,
                      const std::string& output, const AssetBuild& built);

}  // namespace lodbake::cli
