// rotgen bench: the driver's source, and compiling it.
#include "bench/driver.hpp"

#include "support/template.hpp"

#include "bench/files.hpp"
#include "run/compile_cache.hpp"
#include "support/error.hpp"
#include "support/hash.hpp"
#include "support/process.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <iostream>

namespace rotgen::bench {

namespace {

namespace fs = std::filesystem;

// Every variant's header (and unlowered rhs), labelled.
std::string emit_kernels(std::vector<variant>& variants, const model_spec& spec,
                         const bench_options& opt) {
    std::string kernels;
    for (auto& v : variants) {
        // v.f is the form emit_header would build: the body form keeps its quaternion exactly
        // when `rotation` is among the outputs (variants.cpp)
        const kernel_request request{v.outputs, v.specialised, {}};
        v.header = emit_header(spec, lower_form(spec, v.f, request),
                               {"rotgen bench " + opt.scene, v.unit});
        kernels += "// ==== " + v.label + " ====\n" + v.header.text + "\n" + v.naive + "\n";
    }
    return kernels;
}

std::string eigen_flags() {
    int status = 0;
    std::string f = run_capture("pkg-config --cflags eigen3", &status);
    if (status != 0 || f.find("-I") == std::string::npos) f = "-I/usr/include/eigen3";
    while (!f.empty() && (f.back() == '\n' || f.back() == ' '))
        f.pop_back();
    return f;
}

// The headers the driver includes, in path order, subfolders too (runtime/steppers/, ...): part of
// the cache key, so an edit to any of them compiles the driver anew.
std::string harness_text(const bench_sources& src) {
    std::string text;
    for (const auto& d : {src.harness, src.runtime}) {
        std::vector<fs::path> headers;
        for (const auto& e : fs::recursive_directory_iterator(d))
            if (e.path().extension() == ".hpp") headers.push_back(e.path());
        std::sort(headers.begin(), headers.end());
        for (const auto& h : headers)
            text += read_file(h);
    }
    return text;
}

// With GCC, an inlining limit high enough that every integrator — Odeint's header-only steppers
// as much as rotgen's — is inlined into its loop as it would be in a program that uses it once:
// at GCC's default, one translation unit holding many configurations outlines Odeint's
// Fehlberg 7(8) step (13.8 against 9.0 us for 119 fixed steps of the free top, 39 against
// 28 us adaptive), which measured the inliner's budget, not the integrator. Every method is
// compiled for this machine's vector instructions (host_vector_flags), as heyoka's JIT compiles
// for its host.
std::string driver_flags(const std::string& compiler_id) {
    std::string flags = "-std=c++17 -O3 -fno-math-errno -DNDEBUG " + host_vector_flags();
    const bool gcc = compiler_id.find("clang") == std::string::npos &&
                     compiler_id.find("Free Software Foundation") != std::string::npos;
    if (gcc) flags += " --param max-inline-insns-single=2000";
    return flags;
}

// cache/driver.cpp written and compiled to cache/driver (through a temporary: never a partial
// executable): `command` SOURCE -o EXE `libs`.
void compile_into(const compiled_driver& c, const std::string& source, const std::string& command,
                  const std::string& libs, std::size_t variant_count) {
    const fs::path cpp = c.cache / "driver.cpp";
    write_file(cpp, source);
    const fs::path tmp = c.exe.string() + ".tmp" + std::to_string(::getpid());
    std::cout << "rotgen bench: compiling the driver (" << variant_count
              << " variants; once per scene, cached in " << c.cache.string() << ") ..."
              << std::flush;
    int status = 0;
    const std::string log = run_capture(command + " " + shell_quote(cpp.string()) + " -o " +
                                            shell_quote(tmp.string()) + " " + libs,
                                        &status);
    std::error_code ec;
    if (status != 0) {
        fs::remove(tmp, ec);
        throw std::runtime_error("compiling the work-precision driver failed (" + cpp.string() +
                                 "):\n" + log.substr(0, 4000));
    }
    fs::rename(tmp, c.exe, ec);
    if (ec) throw std::runtime_error("cannot install " + c.exe.string() + ": " + ec.message());
    std::cout << " done\n";
}

} // namespace

std::string driver_source(std::vector<variant>& variants, const scene_spec& scene,
                          const model_spec& spec, const derivation& d, const kinematics& k0,
                          const bench_options& opt, const bench_sources& src) {
    const std::string kernels = emit_kernels(variants, spec, opt);
    std::string structs, list;
    for (std::size_t i = 0; i < variants.size(); ++i) {
        structs += variant_struct(variants[i], i, scene, k0, d) + "\n";
        list += (i ? ", " : "") + std::string("variant_") + std::to_string(i);
    }
    const std::map<std::string, std::string> fills{
        {"title", "work-precision driver for " + opt.scene},
        {"command", "rotgen bench " + opt.scene + (opt.quick ? " --quick" : "")},
        {"kernels", kernels},
        {"variants", structs},
        {"variant_list", list}};
    return fill_placeholders(read_file(src.harness / "driver.cpp.in"), fills, "driver.cpp.in",
                             placeholders::known_only);
}

// The driver is an executable with SUNDIALS, not a shared object: its own compile step, over the
// one cache directory and compiler identity of run/compile_cache.hpp.
fs::path bench_cache_root() {
    const fs::path root = fs::path(usable_cache_directory()) / "bench";
    std::error_code ec;
    fs::create_directories(root, ec);
    if (ec) throw user_error({root.string()}, "cannot create the cache directory: " + ec.message());
    return root;
}

compiled_driver compile_driver(const std::string& source, const bench_sources& src,
                               const std::string& scene_name, std::size_t variant_count) {
    const auto t_compile = std::chrono::steady_clock::now();
    const std::string include = "-I" + shell_quote(src.harness.string()) + " -I" +
                                shell_quote(src.runtime.string()) + " " + eigen_flags();
    const std::string libs = "-lsundials_cvode -lsundials_nvecserial -lsundials_sunmatrixdense "
                             "-lsundials_sunlinsoldense -lsundials_sunnonlinsolfixedpoint";
    const std::string harness = harness_text(src);
    const std::string compiler_id = compiler_identity();
    compiled_driver c;
    c.flags = driver_flags(compiler_id);
    const std::string key = hex(fnv1a(source + '\0' + harness + '\0' + compiler_id + '\0' +
                                      c.flags + '\0' + libs + '\0' + ROTGEN_VERSION));
    c.cache = bench_cache_root() / (scene_name + "-" + key);
    std::error_code ec;
    fs::create_directories(c.cache, ec);
    if (ec)
        throw user_error({c.cache.string()}, "cannot create the cache directory: " + ec.message());
    c.exe = c.cache / "driver";
    c.cached = fs::exists(c.exe, ec);
    if (!c.cached) {
        const std::string command = shell_quote(compiler()) + " " + c.flags + " " + include;
        compile_into(c, source, command, libs, variant_count);
    }
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_compile).count();
    return c;
}

} // namespace rotgen::bench
