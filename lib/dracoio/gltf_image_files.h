// Internal to lib/dracoio: how a written .gltf names the image files beside
// it, and the URI text for a file name. A name taken from the input is kept
// when it stays inside the output folder; anything else is named by the
// writer, so no scene can make a writer put a file outside its folder.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/scene/scene.h"

namespace lodbake {
namespace dracoio {

// The image's media type: `declared` when given, else recognized from the
// first bytes (PNG, JPEG, WebP, KTX2), else empty.
std::string image_mime_type(const std::string& declared, const std::vector<uint8_t>& bytes);

// "png", "jpg", "webp", "ktx2" for those media types, else "bin".
std::string image_extension(const std::string& mime_type);

// `uri` (percent-decoded, as SceneImage::uri holds it) as a relative path
// inside the output folder: "." and empty segments removed; empty when it
// cannot be one (absolute, a scheme or drive letter, a backslash, a ".."
// segment, a control character).
std::string safe_relative_name(const std::string& uri);

// `name` percent-encoded for a glTF URI: every byte but the unreserved ones
// (RFC 3986: letters, digits, "-._~") and "/" as %XX.
std::string percent_encode(const std::string& name);

// The file name each image is written under beside a .gltf named
// `gltf_name` with its buffer `bin_name` (an empty name for a missing image,
// which is not written). Input names are kept when safe; others become
// "image_<i>.<ext>"; a name already taken by another file (compared without
// case, for case-insensitive file systems) gets "_<i>" before its extension,
// except that images with the same name and the same bytes share one file.
std::vector<std::string> image_file_names(const std::vector<SceneImage>& images,
                                          const std::string& gltf_name,
                                          const std::string& bin_name);

}  // namespace dracoio
}  // namespace lodbake
