// SHA-256 of input files, recorded in META so a build cache can tell which
// input a container was baked from. Backed by OpenSSL's libcrypto (Debian
// libssl-dev): a well-kept implementation instead of our own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace lodbake {

// Lower-case hexadecimal SHA-256 of the bytes.
std::string sha256_hex(const uint8_t* data, size_t size);

}  // namespace lodbake
