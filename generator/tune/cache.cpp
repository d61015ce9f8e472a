// rotgen — `method: auto`: the cache of choices, and the resolution of a scene (tune.hpp).
#include "tune/tune.hpp"

#include "run/compile_cache.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/hash.hpp"
#include "support/memory_files.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace rotgen {

namespace {

namespace fs = std::filesystem;

// The tuning procedure's version: a change to what it measures or chooses makes new keys.
constexpr const char* procedure =
    "tune 4: sampled error against a Taylor reference, half-decade grid, atol = rtol, DOP853 fixed "
    "steps for one run, tolerances per unit step";

std::string text_of(const std::string& path) {
    std::string text;
    if (memory_file(path, text)) return text;
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The choice file: one `key value` per line.
std::string choice_file_text(const auto_choice& c) {
    std::ostringstream s;
    s.precision(17);
    s << "method " << c.method << "\nrtol " << c.rtol << "\natol " << c.atol << "\nstep " << c.step
      << "\nform " << to_string(c.form) << "\nerror " << c.error << "\nrun_seconds "
      << c.run_seconds << "\nfloor " << c.floor << "\ntune_seconds " << c.tune_seconds << "\n";
    return s.str();
}

bool read_choice(const fs::path& file, auto_choice& c) {
    std::ifstream in(file);
    std::string key, form;
    int seen = 0;
    while (in >> key) {
        if (key == "method")
            in >> c.method;
        else if (key == "rtol")
            in >> c.rtol;
        else if (key == "atol")
            in >> c.atol;
        else if (key == "step")
            in >> c.step;
        else if (key == "form")
            in >> form;
        else if (key == "error")
            in >> c.error;
        else if (key == "run_seconds")
            in >> c.run_seconds;
        else if (key == "floor")
            in >> c.floor;
        else if (key == "tune_seconds")
            in >> c.tune_seconds;
        else
            return false;
        ++seen;
    }
    for (const form_kind f : {form_kind::lagrangian, form_kind::hamiltonian, form_kind::reduced,
                              form_kind::body, form_kind::rotor})
        if (form == to_string(f)) c.form = f, ++seen;
    return seen == 10 && !c.method.empty() && (c.rtol > 0 || c.step > 0);
}

// Written whole under another name, then renamed: a reader never sees half a choice.
void write_choice(const fs::path& file, const auto_choice& c) {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    const fs::path tmp = file.string() + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(tmp);
        out << choice_file_text(c);
        if (!out) return; // a cache that cannot be written only costs a tuning next time
    }
    fs::rename(tmp, file, ec);
    if (ec) fs::remove(tmp, ec);
}

} // namespace

std::string auto_cache_key(const scene_spec& scene, auto_use use) {
    std::string all = text_of(scene.file) + '\0' + scene.model.source + '\0';
    all += short_number(scene.integrator.error, 17) + '\0' + compiler_identity() + '\0' + procedure;
    if (use != auto_use::single_run)
        all += std::string(1, '\0') + (use == auto_use::lanes ? "lanes" : "ensemble");
    return hex(fnv1a(all));
}

auto_choice resolve_auto(scene_spec& scene, std::ostream* log, auto_use use) {
    integrator_spec& ig = scene.integrator;
    if (ig.method != "auto") return {};
    const fs::path file =
        fs::path(usable_cache_directory()) / "tune" / (auto_cache_key(scene, use) + ".choice");
    auto_choice c;
    c.cached = read_choice(file, c);
    if (!c.cached) {
        c = tune_scene(scene, log, use);
        write_choice(file, c);
    }
    const double error = ig.error;
    ig = integrator_spec{};
    ig.method = c.method, ig.error = error;
    if (c.step > 0)
        ig.step = c.step;
    else
        ig.rtol = c.rtol, ig.atol = c.atol;
    if (!scene.form_given) scene.form = c.form;
    ig.auto_choice = choice_text(c) + " (tuned in " + short_number(c.tune_seconds, 2) + " s" +
                     (c.cached ? "; cached" : "") + ")";
    return c;
}

} // namespace rotgen
