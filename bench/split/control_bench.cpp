// The split methods under error control (steppers/split_doubling.hpp) on the goal grid of issue 25
// §1 (bench/split/control.sh writes bench/results/split_control.md from this program's lines).
//
// Heavy top, M g h = 0.981, centre of mass on the body z axis, bodies I = (1, 1, 0.5) and
// (1, 1.2, 0.5), tilted θ0 ∈ {0.3, 1.2}, released with φ̇ = θ̇ = 0 and ψ̇ = spin ∈ {10, 1e2, 1e3,
// 1e4} (ω = (0, 0, spin)), t = 0..10. Error: max |Δq_i| of q0..q3 at t = 10 against DOP853 at
// rtol = atol = 1e-13. Each split method at rtol = atol ∈ {1e-4, 1e-6, 1e-8} (and 1e-10 for split4
// and split6) against DOP853 at the same rtol = atol, both calibrated as `rotgen simulate`
// calibrates them (calibrated.hpp; the reference is not). One line per run:
//   body theta0 spin method rtol error dop853_error steps rhs_evals bound pass
// bound = max(10 rtol, 2 · DOP853's error); pass: error <= bound.
//   control_bench floor      the reference's own error at spin 1e4 (floor_check)
//   control_bench unbounded  split2 at spin 1000, rtol 1e-4 without the bound on a step's turning
#include "calibrated.hpp"
#include "integrate/integrate.hpp"
#include "rotation.hpp"
#include "steppers/dop853.hpp"
#include "steppers/split_doubling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

using namespace rotgen;

namespace {

constexpr double t_end = 10, mgh = 0.981;
using state = Eigen::Matrix<double, 7, 1>;

auto heavy_body(const std::array<double, 3>& in) {
    return make_split_system<double>(in, gravity_torque<double>{{0.0, 0.0, mgh}});
}

state start(double theta, double spin) {
    const Eigen::Quaterniond q = quaternion_from_euler(0.0, theta, 0.0);
    state y;
    y << q.w(), q.x(), q.y(), q.z(), 0, 0, spin;
    return y;
}

double q_error(const state& a, const state& b) {
    return (a.head<4>() - b.head<4>()).cwiseAbs().maxCoeff();
}

template <class M>
state run(const std::array<double, 3>& in, double theta, double spin, M m,
          step_stats* stats = nullptr) {
    auto sys = heavy_body(in);
    state y = start(theta, spin);
    m.max_steps = 100000000;
    const auto r = integrate(sys, m, 0.0, y, t_end);
    if (r.code != status::ok) y.setConstant(NAN);
    if (stats) *stats = r.stats;
    return y;
}

template <int P>
void cell(const std::array<double, 3>& in, const char* body, double theta, double spin,
          const state& ref, double rtol) {
    const double dop = q_error(run(in, theta, spin, calibrated(dop853<double>(rtol, rtol))), ref);
    step_stats st;
    const auto m = calibrated(split_controlled<double, P>(rtol, rtol));
    const double e = q_error(run(in, theta, spin, m, &st), ref);
    const double bound = std::max(10 * rtol, 2 * dop);
    std::printf("%s %.1f %g split%d %g %.2e %.2e %zu %zu %.2e %s\n", body, theta, spin, P, rtol, e,
                dop, st.steps, st.rhs_evals, bound, e <= bound ? "yes" : "NO");
    std::fflush(stdout);
}

// The floor of the error column at spin 1e4: split4 and split6 at rtol = atol = 1e-12 against each
// other and against DOP853 at 1e-13 and 3e-14 (symmetric body, theta0 = 0.3).
void floor_check() {
    const std::array<double, 3> in = {1, 1, 0.5};
    const state s4 = run(in, 0.3, 1e4, split_controlled<double, 4>(1e-12, 1e-12));
    const state s6 = run(in, 0.3, 1e4, split_controlled<double, 6>(1e-12, 1e-12));
    const state d13 = run(in, 0.3, 1e4, dop853<double>(1e-13, 1e-13));
    const state d14 = run(in, 0.3, 1e4, dop853<double>(3e-14, 3e-14));
    std::printf("split4 - split6 %.2e, split4 - DOP853(1e-13) %.2e, DOP853(1e-13) - DOP853(3e-14) "
                "%.2e\n",
                q_error(s4, s6), q_error(s4, d13), q_error(d13, d14));
}

// The runs of split2 at spin 1000 and rtol 1e-4 without the bound on a step's turning
// (max_turns = 0): the cells that missed the bound before it (split_doubling.hpp).
void unbounded() {
    const std::array<std::array<double, 3>, 2> bodies = {{{1, 1, 0.5}, {1, 1.2, 0.5}}};
    const char* names[] = {"symmetric", "asymmetric"};
    for (int b = 0; b < 2; ++b)
        for (double theta : {0.3, 1.2}) {
            const state ref = run(bodies[b], theta, 1e3, dop853<double>(1e-13, 1e-13));
            auto m = calibrated(split_controlled<double, 2>(1e-4, 1e-4));
            m.max_turns = 0;
            step_stats st;
            const double e = q_error(run(bodies[b], theta, 1e3, m, &st), ref);
            std::printf("%s %.1f 1000 split2 1e-4 without the bound: error %.3g (%.3g rtol) in %zu "
                        "steps\n",
                        names[b], theta, e, e / 1e-4, st.steps);
        }
}

} // namespace

int main(int argc, char** argv) {
    if (argc > 1 && std::string(argv[1]) == "floor") return floor_check(), 0;
    if (argc > 1 && std::string(argv[1]) == "unbounded") return unbounded(), 0;
    const std::array<std::array<double, 3>, 2> bodies = {{{1, 1, 0.5}, {1, 1.2, 0.5}}};
    const char* names[] = {"symmetric", "asymmetric"};
    for (int b = 0; b < 2; ++b)
        for (double theta : {0.3, 1.2})
            for (double spin : {10.0, 1e2, 1e3, 1e4}) {
                const state ref = run(bodies[b], theta, spin, dop853<double>(1e-13, 1e-13));
                for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
                    if (rtol > 1e-9) cell<2>(bodies[b], names[b], theta, spin, ref, rtol);
                    cell<4>(bodies[b], names[b], theta, spin, ref, rtol);
                    cell<6>(bodies[b], names[b], theta, spin, ref, rtol);
                }
            }
}
