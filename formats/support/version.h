// The lodbake release version: written into every META section and printed
// by `--version`. Separate from the container format version (major/minor in
// formats/container/container_layout.h), which changes only with the bytes.
#pragma once

namespace lodbake {

inline constexpr char kLodbakeVersion[] = "0.1.0";

}  // namespace lodbake
