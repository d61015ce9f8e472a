// rotgen bench: reading and writing whole files.
#pragma once

#include <filesystem>
#include <string>

namespace rotgen::bench {

// The bytes of a file; throws std::runtime_error if it cannot be read.
std::string read_file(const std::filesystem::path& p);

// Written to a temporary beside the target, then renamed: never a partial file. Throws
// user_error naming the path.
// shared with simulate: to be replaced by support/'s atomic file writer
void write_file(const std::filesystem::path& path, const std::string& text);

} // namespace rotgen::bench
