// rotgen bench: parsing its command line.
#include "bench/options.hpp"

#include "support/error.hpp"

#include <cstdlib>
#include <filesystem>

namespace rotgen::bench {

namespace fs = std::filesystem;

const char* const bench_usage = "rotgen bench SCENE.yaml [-o DIR] [--quick] [--long-steps N]";

namespace {

user_error usage_error(const std::string& problem) {
    return user_error({"rotgen bench"}, problem);
}

} // namespace

// shared with simulate: to be replaced by the one option parser (support/ or cli/)
bench_options parse_arguments(const std::vector<std::string>& args) {
    bench_options o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-o" || a == "--long-steps") {
            if (i + 1 >= args.size()) throw usage_error(a + " needs a value");
            const std::string v = args[++i];
            if (a == "-o") {
                o.dir = v;
            } else {
                char* end = nullptr;
                const long n = std::strtol(v.c_str(), &end, 10);
                if (!end || *end || n < 0 || n > 100000000)
                    throw usage_error(
                        "--long-steps needs a whole number of steps in [0, 1e8], got '" + v + "'");
                o.long_steps = n;
            }
        } else if (a == "--quick") {
            o.quick = true;
        } else if (!a.empty() && a[0] == '-') {
            const std::string best = closest_name(a, {"-o", "--quick", "--long-steps"});
            throw usage_error("unknown option '" + a + "' for bench" +
                              (best.empty() ? "" : "; did you mean '" + best + "'?"));
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            throw usage_error("bench takes one scene file, got '" + o.scene + "' and '" + a + "'");
        }
    }
    if (o.scene.empty()) throw usage_error(std::string("bench needs a scene file: ") + bench_usage);
    if (o.long_steps < 0) o.long_steps = o.quick ? 10000 : 1000000;
    if (o.dir.empty()) o.dir = "bench-out/" + fs::path(o.scene).stem().string();
    return o;
}

} // namespace rotgen::bench
