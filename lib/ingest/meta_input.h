// META's record of a baked input, shared by the tools and lodbake-bake so
// that both write the same bytes: a file's base name, size and SHA-256, or,
// for a container, the input its own META names (containers of one input
// stay mergeable).
#pragma once

#include <string>

#include "formats/sections/meta.h"
#include "formats/support/file_io.h"
#include "lib/ingest/load_mesh.h"

namespace lodbake {

// `text` with every byte that is not part of valid UTF-8 replaced by U+FFFD,
// for strings that must be valid UTF-8 (META) but come from file names.
std::string to_valid_utf8(const std::string& text);

// A loaded mesh's record: its base name (so the same input baked from
// another folder gives the same bytes), size and SHA-256.
MetaInput meta_input(const std::string& path, const LoadedMesh& loaded);

// An asset's record (`bytes`: the file's content): a container's own record
// of its input, else the file's base name, SHA-256 and size.
MetaInput asset_meta_input(const std::string& path, const Bytes& bytes);

}  // namespace lodbake
