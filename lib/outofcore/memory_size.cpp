#include "lib/outofcore/memory_size.h"

#include <cctype>

namespace lodbake {

Result<uint64_t> parse_memory_size(const std::string& text) {
  const Status bad = invalid_input(
      "a memory size is a whole number with K, M, G or T, like 512M or 2G, not '" + text + "'");
  size_t i = 0;
  uint64_t value = 0;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
    if (value > (uint64_t{1} << 50)) return bad;
    value = value * 10 + static_cast<uint64_t>(text[i] - '0');
    ++i;
  }
  if (i == 0) return bad;
  std::string suffix = text.substr(i);
  for (char& c : suffix)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  int shift = 0;
  if (!suffix.empty()) {
    const std::string units = "KMGT";
    const size_t unit = units.find(suffix[0]);
    if (unit == std::string::npos) {
      if (suffix != "B") return bad;
    } else {
      shift = 10 * static_cast<int>(unit + 1);
      const std::string rest = suffix.substr(1);
      if (!rest.empty() && rest != "B" && rest != "IB") return bad;
    }
  }
  if (value == 0) return invalid_input("a memory size must be above 0, not '" + text + "'");
  if (value > ((uint64_t{1} << 50) >> shift))
    return invalid_input("the memory size '" + text + "' is above 1P");
  return value << shift;
}

}  // namespace lodbake
