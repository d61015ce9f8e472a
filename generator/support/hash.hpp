// rotgen — stable hashing for cache keys, header stamps and the CSV provenance line.
#pragma once

#include <cstdint>
#include <string>

namespace rotgen {

// FNV-1a, 64 bit: the same value in every run and on every machine.
std::uint64_t fnv1a(const std::string& data, std::uint64_t seed = 14695981039346656037ull);
// 16 lower-case hex digits.
std::string hex(std::uint64_t value);
// SHA-256 (FIPS 180-4) of `data`: 64 lower-case hex digits, as `sha256sum` prints them.
std::string sha256_hex(const std::string& data);

} // namespace rotgen
