// rotgen sweep --lanes: the time of one member's right-hand side, scalar kernel against batch
// kernel, from the compiled libraries in the kernel cache (bench/sweep.sh builds and runs this):
//
//   rhs_time SCALAR.so LANES.so N_STATE N_PARAMETERS
//
// prints "scalar_ns lanes4_ns lanes8_ns": nanoseconds per member and call, the best of 5 rounds,
// the scalar and batch calls interleaved within each round. The states differ from call to call
// (theta moves) so that nothing is hoisted out of the loop. The kernels read the prepared values
// (the parameters, all 1 here, then the constants made from them: rotgen_prepare), by lane for the
// batch kernel.
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using kernel = void (*)(const double*, double, const double*, double*);
using lane_kernel = void (*)(const double*, double, const double*, double*, unsigned long);
using prepare_fn = void (*)(const double*, double*);

// room for the prepared values of any shipped model (its parameters and constants)
constexpr int prepared_room = 256;

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ns per member of `calls` member evaluations in batches of w lanes
double lanes_ns(lane_kernel g, const std::vector<double>& prepared, unsigned long w, int n,
                int calls, double& sink) {
    std::vector<double> y(n * w), p(prepared_room * w), d(n * w);
    for (int j = 0; j < prepared_room; ++j)
        for (unsigned long l = 0; l < w; ++l)
            p[j * w + l] = prepared[j];
    for (unsigned long l = 0; l < w; ++l)
        for (int c = 0; c < n; ++c)
            y[c * w + l] = 0.3 + 0.1 * c + 0.01 * double(l);
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < calls / int(w); ++i) {
        y[w] = 0.5 + 1e-9 * i;
        g(p.data(), 0.0, y.data(), d.data(), w);
        sink += d[3 * w];
    }
    return seconds_since(t0) / calls * 1e9;
}

double scalar_ns(kernel f, const std::vector<double>& p, int n, int calls, double& sink) {
    std::vector<double> y(n), d(n);
    for (int c = 0; c < n; ++c)
        y[c] = 0.3 + 0.1 * c;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < calls; ++i) {
        y[1] = 0.5 + 1e-9 * i;
        f(p.data(), 0.0, y.data(), d.data());
        sink += d[3];
    }
    return seconds_since(t0) / calls * 1e9;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: rhs_time SCALAR.so LANES.so N_STATE N_PARAMETERS\n");
        return 2;
    }
    void* hs = dlopen(argv[1], RTLD_NOW);
    void* hl = dlopen(argv[2], RTLD_NOW);
    if (!hs || !hl) {
        std::fprintf(stderr, "rhs_time: %s\n", dlerror());
        return 1;
    }
    const auto f = reinterpret_cast<kernel>(dlsym(hs, "rotgen_rhs"));
    const auto g = reinterpret_cast<lane_kernel>(dlsym(hl, "rotgen_rhs_lanes"));
    const auto prepare = reinterpret_cast<prepare_fn>(dlsym(hs, "rotgen_prepare"));
    const int n = std::atoi(argv[3]), np = std::atoi(argv[4]), calls = 2000000;
    const std::vector<double> parameters(np, 1.0);
    std::vector<double> prepared(prepared_room, 0.0);
    prepare(parameters.data(), prepared.data());
    double best[3] = {1e9, 1e9, 1e9}, sink = 0;
    for (int round = 0; round < 5; ++round) {
        best[0] = std::min(best[0], scalar_ns(f, prepared, n, calls, sink));
        best[1] = std::min(best[1], lanes_ns(g, prepared, 4, n, calls, sink));
        best[2] = std::min(best[2], lanes_ns(g, prepared, 8, n, calls, sink));
    }
    std::printf("%.1f %.1f %.1f\n", best[0], best[1], best[2]);
    return sink == 0.123 ? 1 : 0; // keeps the results alive
}
