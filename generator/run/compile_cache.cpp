#include "run/compile_cache.hpp"

#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/hash.hpp"
#include "support/process.hpp"

#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rotgen {

namespace {

const char* const flags = "-std=c++17 -O3 -fno-math-errno -fPIC -shared -Wall -Wextra";

void make_directories(const std::string& path) {
    for (std::size_t i = 1; i <= path.size(); ++i)
        if (i == path.size() || path[i] == '/') ::mkdir(path.substr(0, i).c_str(), 0755);
}

} // namespace

const std::string& compiler_identity() {
    static const std::string id = [] {
        int status = 0;
        const std::string v = run_capture("'" + compiler() + "' --version", &status);
        if (status != 0)
            throw std::runtime_error("no working C++ compiler ('" + compiler() + "'): " + v);
        return v;
    }();
    return id;
}

std::string usable_cache_directory() {
    const std::string dir = cache_directory();
    make_directories(dir);
    struct stat st {};
    std::string problem;
    if (::stat(dir.c_str(), &st) != 0)
        problem = std::strerror(errno);
    else if (!S_ISDIR(st.st_mode))
        problem = "it is not a folder";
    else if (::access(dir.c_str(), W_OK | X_OK) != 0)
        problem = std::strerror(errno);
    if (!problem.empty())
        throw user_error({dir}, "cannot use this folder as the kernel cache: " + problem +
                                    "; set ROTGEN_CACHE_DIR to a folder you can write");
    return dir;
}

std::string host_vector_flags(std::string* target, bool fused) {
    const std::string contract = fused ? "-ffp-contract=fast" : "-ffp-contract=off";
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
        if (target) *target = "avx2+fma";
        return "-mavx2 -mfma " + contract;
    }
#endif
    if (target) *target = "sse2";
    return contract;
}

std::string host_lane_vector_flags(std::string* target, bool wide) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    if (wide && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("fma")) {
        if (target) *target = "avx512+fma";
        return "-mavx512f -mavx512dq -mavx512vl -mavx512bw -mavx2 -mfma -ffp-contract=fast";
    }
#endif
    return host_vector_flags(target, true);
}

std::string host_exact_vector_flags() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    if (__builtin_cpu_supports("avx2")) return "-mavx2";
#endif
    return "";
}

std::string cache_directory() {
    if (const char* d = std::getenv("ROTGEN_CACHE_DIR"); d && *d) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::string(d) + "/rotgen";
    if (const char* d = std::getenv("HOME"); d && *d) return std::string(d) + "/.cache/rotgen";
    return "/tmp/rotgen-cache";
}

loaded_library::loaded_library(loaded_library&& other) noexcept
    : m_handle(other.m_handle), m_path(std::move(other.m_path)), m_cached(other.m_cached) {
    other.m_handle = nullptr;
}

loaded_library& loaded_library::operator=(loaded_library&& other) noexcept {
    if (this != &other) {
        if (m_handle) ::dlclose(m_handle);
        m_handle = other.m_handle;
        m_path = std::move(other.m_path);
        m_cached = other.m_cached;
        other.m_handle = nullptr;
    }
    return *this;
}

loaded_library::~loaded_library() {
    if (m_handle) ::dlclose(m_handle);
}

void* loaded_library::symbol(const std::string& name) const {
    void* p = ::dlsym(m_handle, name.c_str());
    if (!p) throw std::runtime_error("compiled model " + m_path + " has no symbol " + name);
    return p;
}

std::string without_comment_lines(const std::string& source) {
    std::string code;
    code.reserve(source.size());
    for (std::size_t at = 0; at < source.size();) {
        std::size_t end = source.find('\n', at);
        end = end == std::string::npos ? source.size() : end + 1;
        const std::size_t first = source.find_first_not_of(" \t", at);
        if (first >= end || source.compare(first, 2, "//") != 0) code.append(source, at, end - at);
        at = end;
    }
    return code;
}

loaded_library compile_and_load(const std::string& source, const std::string& name,
                                const std::string& extra_flags) {
    const std::string all_flags = extra_flags.empty() ? flags : flags + (" " + extra_flags);
    const std::string key = hex(fnv1a(without_comment_lines(source) + '\0' + compiler_identity() +
                                      '\0' + all_flags + '\0' + ROTGEN_VERSION));
    const std::string dir = usable_cache_directory();
    const std::string base = dir + "/" + name + "-" + key;
    loaded_library lib;
    lib.m_path = base + ".so";
    lib.m_cached = ::access(lib.m_path.c_str(), R_OK) == 0;
    if (!lib.m_cached) {
        const std::string src = base + ".cpp";
        const std::string tmp_src = src + ".tmp" + std::to_string(::getpid());
        register_temporary(tmp_src);
        {
            std::ofstream out(tmp_src, std::ios::binary);
            out << source;
            if (!out) throw std::runtime_error("cannot write " + tmp_src);
        }
        std::rename(tmp_src.c_str(), src.c_str());
        forget_temporary(tmp_src);
        const std::string tmp_so = base + ".so.tmp" + std::to_string(::getpid());
        register_temporary(tmp_so);
        int status = 0;
        const std::string log = run_capture(
            "'" + compiler() + "' " + all_flags + " '" + src + "' -o '" + tmp_so + "'", &status);
        if (status != 0) {
            std::remove(tmp_so.c_str());
            forget_temporary(tmp_so);
            throw std::runtime_error("compiling the generated model failed (" + src + "):\n" + log);
        }
        std::rename(tmp_so.c_str(), lib.m_path.c_str()); // atomic: no half-written library
        forget_temporary(tmp_so);
    }
    lib.m_handle = ::dlopen(lib.m_path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib.m_handle)
        throw std::runtime_error(std::string("cannot load ") + lib.m_path + ": " + ::dlerror());
    return lib;
}

} // namespace rotgen
