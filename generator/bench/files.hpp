// rotgen bench: reading and writing whole files.
#pragma once

#include <filesystem>
#include <string>

namespace rotgen::bench {

// The bytes of a file; throws std::runtime_error if it cannot be read.
std::string read_file(const std::filesystem::path& p);

// support/atomic_file.hpp's write_file_atomically (never a partial file; user_error naming the
// path).
void write_file(const std::filesystem::path& path, const std::string& text);

} // namespace rotgen::bench
