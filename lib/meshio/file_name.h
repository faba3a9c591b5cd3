// File-name helpers shared by import and export.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace lodbake {

// The extension after the last '.' of the last path component, lower-case;
// empty when there is none.
inline std::string lower_extension(const std::string& path) {
  size_t slash = path.find_last_of('/');
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace lodbake
