// The exact free asymmetric top (runtime/exact_free_top.hpp) in long double, for
// bench/extremes/moments.sh and long_runs.sh. The moments and omega(0) are read as doubles (what
// `rotgen simulate` reads from a scene) and then widened, so the reference solves exactly the
// problem the double-precision run was given.
//
//   free_top_error I1 I2 I3 W1 W2 W3 CSV
//       max over the CSV's rows of max_i |omega_i - exact_i| (columns t, omega1, omega2, omega3
//       in that order, as `record: [omega1, omega2, omega3]` writes them); the same against a
//       long-double run of the checked-in body-form kernels
//       (generated/free_asymmetric_top_body.hpp, dop853 at rtol 3e-18, a check on the exact
//       solution's own rounding); and the largest |omega3(t) - omega3(0)| of the exact solution
//       over the same times (the part of the motion that exists only because the moments differ).
//   free_top_error --floor I1 I2 I3 W1 W2 W3 T N
//       the data-rounding floor: the largest change of the exact omega over N + 1 times in [0, T]
//       when one of the six inputs (I1, I2, I3, W1, W2, W3) moves by its rounding to double,
//       u |x| with u = 2^-53. No double-precision computation of this problem can promise less.
#include "free_asymmetric_top_body.hpp"
#include <exact_free_top.hpp>
#include <rotgen.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using real = long double;

static std::array<real, 3> read3(char** a) {
    return {real(std::strtod(a[0], nullptr)), real(std::strtod(a[1], nullptr)),
            real(std::strtod(a[2], nullptr))};
}

// --floor: the largest change of the exact omega over n + 1 times in [0, T] when one of I, w
// moves by u |x|, u = 2^-53.
static real data_floor(const std::array<real, 3>& I, const std::array<real, 3>& w, real T, int n) {
    const rotgen::free_top_exact<real> exact(I, w);
    const real u = std::ldexp(real(1), -53);
    real worst = 0;
    for (int k = 0; k < 6; ++k) {
        std::array<real, 3> Ik = I, wk = w;
        (k < 3 ? Ik[k] : wk[k - 3]) *= 1 + u;
        const rotgen::free_top_exact<real> moved(Ik, wk);
        for (int i = 0; i <= n; ++i) {
            const real t = T * i / n;
            const auto a = exact(t), b = moved(t);
            for (int j = 0; j < 3; ++j)
                worst = std::max(worst, std::abs(a[j] - b[j]));
        }
    }
    return worst;
}

// The CSV's rows after its provenance line and header: t, omega1, omega2, omega3; false if it
// cannot be read.
static bool read_rows(const char* path, std::vector<std::array<real, 4>>& rows) {
    std::ifstream in(path);
    std::string line;
    do // the provenance line ("# rotgen ..."), then the header
        if (!std::getline(in, line)) return false;
    while (!line.empty() && line[0] == '#');
    while (std::getline(in, line)) {
        std::istringstream row(line);
        std::string cell;
        std::array<real, 4> v{};
        for (int j = 0; j < 4 && std::getline(row, cell, ','); ++j)
            v[j] = std::strtold(cell.c_str(), nullptr);
        rows.push_back(v);
    }
    return true;
}

// The rows against the exact solution and against a long-double run of the body-form kernels
// (dop853 at rtol 3e-18) sampled at the CSV's times; prints "exact run swing".
static int compare_with_exact(const std::array<real, 3>& I, const std::array<real, 3>& w,
                              const std::vector<std::array<real, 4>>& rows) {
    const rotgen::free_top_exact<real> exact(I, w);
    namespace model = rotgen::models::free_asymmetric_top_body;
    auto sys = ROTGEN_GENERATED_SYSTEM(model, real);
    sys.params.I1 = I[0], sys.params.I2 = I[1], sys.params.I3 = I[2];
    rotgen::state_vector<real, decltype(sys)> y;
    y << w[0], w[1], w[2];
    std::vector<real> times;
    for (const auto& r : rows)
        times.push_back(r[0]);
    rotgen::dop853<real> method(real(3e-18), real(1e-20));
    method.max_steps = 100000000;
    real worst = 0, worst_run = 0, swing = 0;
    const real w30 = exact(0)[2];
    std::size_t k = 0;
    const auto result =
        rotgen::integrate(sys, method, real(0), y, times, [&](real t, const auto& s) {
            const auto e = exact(t);
            for (int j = 0; j < 3; ++j) {
                worst = std::max(worst, std::abs(rows[k][j + 1] - e[j]));
                worst_run = std::max(worst_run, std::abs(rows[k][j + 1] - s[j]));
            }
            swing = std::max(swing, std::abs(e[2] - w30));
            ++k;
        });
    if (!result.ok() || k != rows.size()) {
        std::fprintf(stderr, "free_top_error: the long-double run failed: %s\n",
                     result.message.c_str());
        return 1;
    }
    std::printf("%.2Le %.2Le %.2Le\n", worst, worst_run, swing);
    return 0;
}

int main(int argc, char** argv) {
    if (argc == 10 && std::strcmp(argv[1], "--floor") == 0) {
        std::printf("%.2Le\n", data_floor(read3(argv + 2), read3(argv + 5),
                                          std::strtold(argv[8], nullptr), std::atoi(argv[9])));
        return 0;
    }
    if (argc != 8) {
        std::fprintf(stderr, "usage: free_top_error I1 I2 I3 W1 W2 W3 CSV\n"
                             "       free_top_error --floor I1 I2 I3 W1 W2 W3 T N\n");
        return 2;
    }
    std::vector<std::array<real, 4>> rows;
    if (!read_rows(argv[7], rows)) {
        std::fprintf(stderr, "free_top_error: cannot read %s\n", argv[7]);
        return 1;
    }
    return compare_with_exact(read3(argv + 1), read3(argv + 4), rows);
}
