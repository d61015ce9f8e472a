// rotgen — benchmark: how long the symbolic stage takes, model file to derivation.
//
//   derive_bench [--repeats N] [--min-time SECONDS] [--format text|tsv] MODEL.yaml...
//
// One timed call is rotgen::load_model(path) followed by rotgen::derive(spec): the model file read
// and validated, then everything the generator derives (omega (5.30), T (5.38), V, L, p, M(q),
// f(q, q_dot, t), the Euler-Lagrange equations, H(q, p), Hamilton's equations, cyclic coordinates).
// A repeat loops the call until at least --min-time seconds have passed (0.2 s by default) and
// divides; the median, min and max are taken over --repeats repeats (9 by default, at least 7).
// One untimed call before the repeats warms the caches (the process-wide symbol table, the
// file system, GiNaC's static data), as a long-running generator would have them.
//
// Output, one line per model: text (default) for a person, tsv for bench/derive.sh:
//   model <TAB> median_s <TAB> min_s <TAB> max_s <TAB> calls_per_repeat <TAB> repeats
#include "derive/derive.hpp"
#include "spec/spec.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

namespace {

using clock_type = std::chrono::steady_clock;

struct timing {
    double median = 0, min = 0, max = 0; // seconds per call
    long calls_per_repeat = 0;
};

// Something of every result, so that no part of the derivation can be optimised away.
std::size_t fingerprint(const rotgen::derivation& d) {
    std::size_t n = d.lagrangian.nops() + d.hamiltonian.nops() + d.cyclic.size();
    for (int i = 0; i < 3; ++i) {
        n += d.momenta[i].nops() + d.forcing[i].nops() + d.euler_lagrange[i].nops() +
             d.hamilton_qdot[i].nops() + d.hamilton_pdot[i].nops();
        for (int j = 0; j < 3; ++j)
            n += d.mass_matrix[i][j].nops();
    }
    return n;
}

std::size_t sink = 0;

std::size_t load_and_derive(const std::string& path) {
    const rotgen::model_spec spec = rotgen::load_model(path);
    return fingerprint(rotgen::derive(spec));
}

timing measure(const std::string& path, int repeats, double min_time) {
    sink += load_and_derive(path); // warm-up, untimed
    std::vector<double> per_call;
    long calls_per_repeat = 0;
    for (int r = 0; r < repeats; ++r) {
        long calls = 0;
        const auto start = clock_type::now();
        double elapsed = 0;
        do {
            sink += load_and_derive(path);
            ++calls;
            elapsed = std::chrono::duration<double>(clock_type::now() - start).count();
        } while (elapsed < min_time);
        per_call.push_back(elapsed / static_cast<double>(calls));
        calls_per_repeat = std::max(calls_per_repeat, calls);
    }
    std::sort(per_call.begin(), per_call.end());
    timing t;
    const std::size_t n = per_call.size();
    t.median = n % 2 ? per_call[n / 2] : (per_call[n / 2 - 1] + per_call[n / 2]) / 2;
    t.min = per_call.front();
    t.max = per_call.back();
    t.calls_per_repeat = calls_per_repeat;
    return t;
}

std::string stem(const std::string& path) {
    std::string s = path.substr(path.find_last_of('/') + 1);
    return s.substr(0, s.find_last_of('.'));
}

int usage(const char* why) {
    std::fprintf(stderr,
                 "derive_bench: error: %s\n"
                 "usage: derive_bench [--repeats N (>= 7)] [--min-time SECONDS] "
                 "[--format text|tsv] MODEL.yaml...\n",
                 why);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    int repeats = 9;
    double min_time = 0.2;
    std::string format = "text";
    std::vector<std::string> models;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool has_value = i + 1 < argc;
        if (a == "--repeats" && has_value) {
            repeats = std::atoi(argv[++i]);
        } else if (a == "--min-time" && has_value) {
            min_time = std::atof(argv[++i]);
        } else if (a == "--format" && has_value) {
            format = argv[++i];
        } else if (!a.empty() && a[0] == '-') {
            return usage(("unknown or incomplete option '" + a + "'").c_str());
        } else {
            models.push_back(a);
        }
    }
    if (models.empty()) return usage("no model file given");
    if (repeats < 7) return usage("--repeats must be at least 7");
    if (!(min_time > 0)) return usage("--min-time must be positive");
    if (format != "text" && format != "tsv") return usage("--format must be text or tsv");

    try {
        if (format == "text")
            std::printf("load_model + derive, %d repeats of >= %.2f s each (per call)\n", repeats,
                        min_time);
        for (const std::string& path : models) {
            const timing t = measure(path, repeats, min_time);
            if (format == "tsv")
                std::printf("%s\t%.9g\t%.9g\t%.9g\t%ld\t%d\n", stem(path).c_str(), t.median, t.min,
                            t.max, t.calls_per_repeat, repeats);
            else
                std::printf(
                    "%-22s median %9.3f ms   min %9.3f ms   max %9.3f ms   (%ld calls/repeat)\n",
                    stem(path).c_str(), t.median * 1e3, t.min * 1e3, t.max * 1e3,
                    t.calls_per_repeat);
            std::fflush(stdout);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "derive_bench: error: %s\n", e.what());
        return 1;
    }
    return sink == 0 ? 1 : 0; // sink is never 0: every derivation has terms
}
