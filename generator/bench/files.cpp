// rotgen bench: reading and writing whole files.
#include "bench/files.hpp"

#include "support/error.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rotgen::bench {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + p.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// shared with simulate: to be replaced by support/'s atomic file writer
void write_file(const fs::path& path, const std::string& text) {
    const fs::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw user_error({path.string()}, std::string("cannot write: ") + std::strerror(errno));
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw user_error({path.string()}, "cannot write: " + ec.message());
}

} // namespace rotgen::bench
