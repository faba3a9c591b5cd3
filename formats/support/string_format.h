// printf-style formatting into a std::string, for one-line error messages
// (C++17 has no std::format).
#pragma once

#include <cstdarg>
#include <cstdio>
#include <string>

namespace lodbake {

/// vsnprintf into a std::string of the exact length needed.
__attribute__((format(printf, 1, 2))) inline std::string string_printf(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list copy;
  va_copy(copy, args);
  const int length = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  std::string out;
  if (length > 0) {
    out.resize(static_cast<size_t>(length) + 1);
    std::vsnprintf(&out[0], out.size(), format, args);
    out.resize(static_cast<size_t>(length));
  }
  va_end(args);
  return out;
}

}  // namespace lodbake
