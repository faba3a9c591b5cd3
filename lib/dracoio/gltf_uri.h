// Internal to lib/dracoio: glTF URIs (RFC 3986 references, as glTF 2.0's
// "URIs" section uses them) turned into file names.
#pragma once

#include <string>

#include "formats/support/status.h"

namespace lodbake {
namespace dracoio {

// `uri` with every %XX escape decoded. A malformed escape or a decoded NUL
// byte is invalid input.
Result<std::string> percent_decode(const std::string& uri);

}  // namespace dracoio
}  // namespace lodbake
