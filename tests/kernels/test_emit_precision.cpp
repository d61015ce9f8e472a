// Nearly equal moments: the generated kernels keep their accuracy where a difference of two
// moments decides a rate. I1 = 3 and I2 = 3 (1 + 2^-45) are exact binary numbers, and I2 - I1 is
// exact in double (Sterbenz); a kernel that computes 1/I2 - 1/I1, a difference of two rounded
// reciprocals, keeps ~2 of its digits (relative error ~4e-3). (With I1 = 1 the reciprocal of
// 1 + 2^-45 happens to round to 1 - 2^-45 exactly, which hides the loss: hence I1 = 3.)
#include "kernels.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace rotgen_test;

namespace {

struct moments {
    long double I1, I2, I3;
};

const moments nearly_equal{3.0L, 3.0L * (1 + std::ldexp(1.0L, -45)), 1.0L};

using state6 = std::array<long double, 6>;

// States away from theta = 0, pi where no component of the rates is small by accident.
const std::vector<state6> euler_states{{{0.3L, 1.1L, 0.7L, 0.9L, -0.4L, 1.3L}},
                                       {{2.0L, 0.6L, 4.1L, -1.2L, 0.8L, 0.5L}},
                                       {{5.2L, 2.3L, 1.9L, 0.4L, 1.7L, -0.9L}}};

// Euler's equations (5.87)-(5.89), the differences of moments as they stand there.
std::array<long double, 3> euler_equations(const std::array<long double, 3>& w, const moments& I) {
    return {(I.I2 - I.I3) * w[1] * w[2] / I.I1, (I.I3 - I.I1) * w[2] * w[0] / I.I2,
            (I.I1 - I.I2) * w[0] * w[1] / I.I3};
}

// Hamilton's equations of the free top, written out: l = J^{-T} p (the body angular momentum),
// omega = I^{-1} l, q_dot = J^{-1} omega, p_dot_i = -omega . dl/dq_i, with J of (5.30).
//   l1 = sin(psi) s + cos(psi) p_theta, l2 = cos(psi) s - sin(psi) p_theta, l3 = p_psi,
//   s = (p_phi - cos(theta) p_psi) / sin(theta);
//   dl/dphi = 0; dl/dtheta = (sin(psi), cos(psi), 0) (p_psi - cos(theta) p_phi) / sin^2(theta);
//   dl/dpsi = (l2, -l1, 0), so p_psi_dot = l1 l2 (1/I2 - 1/I1) = l1 l2 (I1 - I2) / (I1 I2).
state6 hamilton_reference(const state6& y, const moments& I) {
    const long double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                      cp = std::cos(y[2]);
    const long double s = (y[3] - ct * y[5]) / st;
    const long double l1 = sp * s + cp * y[4], l2 = cp * s - sp * y[4], l3 = y[5];
    const long double w1 = l1 / I.I1, w2 = l2 / I.I2, w3 = l3 / I.I3;
    const long double phi_dot = (w1 * sp + w2 * cp) / st;
    return {phi_dot,
            w1 * cp - w2 * sp,
            w3 - phi_dot * ct,
            0,
            -(w1 * sp + w2 * cp) * (y[5] - ct * y[3]) / (st * st),
            l1 * l2 * (I.I1 - I.I2) / (I.I1 * I.I2)};
}

// The Lagrangian form by Euler's equations: omega = J q_dot (5.30), omega_dot from (5.87)-(5.89),
// q_ddot = J^{-1} (omega_dot - J_dot q_dot), J_dot q_dot = sum_j (d omega / d q_j) q_dot_j.
state6 lagrange_reference(const state6& y, const moments& I) {
    const long double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                      cp = std::cos(y[2]);
    const long double phi_dot = y[3], theta_dot = y[4], psi_dot = y[5];
    const std::array<long double, 3> w{phi_dot * st * sp + theta_dot * cp,
                                       phi_dot * st * cp - theta_dot * sp, phi_dot * ct + psi_dot};
    const std::array<long double, 3> wd = euler_equations(w, I);
    const long double a1 =
        wd[0] - (phi_dot * ct * sp * theta_dot + (phi_dot * st * cp - theta_dot * sp) * psi_dot);
    const long double a2 =
        wd[1] - (phi_dot * ct * cp * theta_dot - (phi_dot * st * sp + theta_dot * cp) * psi_dot);
    const long double a3 = wd[2] + phi_dot * st * theta_dot;
    const long double phi_ddot = (a1 * sp + a2 * cp) / st;
    return {phi_dot, theta_dot, psi_dot, phi_ddot, a1 * cp - a2 * sp, a3 - phi_ddot * ct};
}

void check_close(double value, long double exact, const std::string& what,
                 long double relative = 1e-13L) {
    INFO(what << ": generated " << value << ", exact " << static_cast<double>(exact));
    if (exact == 0)
        CHECK(value == 0);
    else
        CHECK(std::abs(value - exact) <= relative * std::abs(exact));
}

} // namespace

TEST_CASE("nearly equal moments: the Hamiltonian form of the free top stays accurate",
          "[emit][precision]") {
    // Before rotgen brought like terms to one fraction, p_psi_dot was -(1/I2 - 1/I1) l1 l2
    // (relative error 4e-3 here).
    const kernel k = find_kernel("free_asymmetric_top_hamiltonian")
                         .with_parameters({3.0, 3.0 * (1 + std::ldexp(1.0, -45)), 1.0});
    REQUIRE(k.parameter_names == std::vector<std::string>{"I1", "I2", "I3"});
    for (const state6& yl : euler_states) {
        const std::vector<double> y(yl.begin(), yl.end());
        std::vector<double> f(6);
        k.rhs(0.0, y.data(), f.data());
        const state6 exact = hamilton_reference(yl, nearly_equal);
        for (std::size_t i = 0; i < 6; ++i)
            check_close(f[i], exact[i], "d" + k.state_names[i] + "/dt");
    }
}

TEST_CASE("nearly equal moments: the Lagrangian and body forms of the free top stay accurate",
          "[emit][precision]") {
    const std::vector<double> I{3.0, 3.0 * (1 + std::ldexp(1.0, -45)), 1.0};
    SECTION("lagrangian") {
        const kernel k = find_kernel("free_asymmetric_top").with_parameters(I);
        for (const state6& yl : euler_states) {
            const std::vector<double> y(yl.begin(), yl.end());
            std::vector<double> f(6);
            k.rhs(0.0, y.data(), f.data());
            const state6 exact = lagrange_reference(yl, nearly_equal);
            for (std::size_t i = 0; i < 6; ++i)
                check_close(f[i], exact[i], "d" + k.state_names[i] + "/dt");
        }
    }
    SECTION("body") {
        const kernel k = find_kernel("free_asymmetric_top_body_omega").with_parameters(I);
        for (const std::array<long double, 3>& w :
             {std::array<long double, 3>{0.9L, -0.4L, 1.3L}, {-1.2L, 0.8L, 0.5L}}) {
            const std::vector<double> y(w.begin(), w.end());
            std::vector<double> f(3);
            k.rhs(0.0, y.data(), f.data());
            const std::array<long double, 3> exact = euler_equations(w, nearly_equal);
            for (std::size_t i = 0; i < 3; ++i)
                check_close(f[i], exact[i], "d" + k.state_names[i] + "/dt");
        }
    }
}

TEST_CASE("nearly equal moments: the free top's rates and Jacobians round like their long "
          "double evaluation, entry by entry",
          "[emit][precision]") {
    // The rounding error of a kernel is its double value minus its long double value (2^11 times
    // more precise, same operations). Relative to each entry, not to the largest: an entry that
    // is small because I1 ~ I2 must be as accurate as the others. Before like terms were
    // combined, the Lagrangian Jacobian computed such entries as (a + x) - (b + x) (relative
    // error up to 0.3 here) and the Hamiltonian and reduced forms used 1/I2 - 1/I1. At random
    // states an entry's own cancellations cost up to 7e-13 (measured over 200 states), hence
    // the bound 1e-11: far above that, far below the 4e-3 of the defect.
    for (const std::string unit :
         {"free_asymmetric_top", "free_asymmetric_top_hamiltonian", "free_asymmetric_top_reduced",
          "free_asymmetric_top_body", "free_asymmetric_top_body_omega"}) {
        const kernel& k0 = find_kernel(unit);
        std::vector<double> values;
        for (const std::string& name : k0.parameter_names)
            values.push_back(name == "I1"   ? 3.0
                             : name == "I2" ? 3.0 * (1 + std::ldexp(1.0, -45))
                             : name == "I3" ? 1.0
                                            : 0.7); // p_phi, the reduced form's
        const kernel k = k0.with_parameters(values);
        std::mt19937 rng(29);
        for (int trial = 0; trial < 5; ++trial) {
            const std::vector<double> y = random_state(k, rng);
            const std::vector<long double> yl(y.begin(), y.end());
            std::vector<double> f(k.n), J(k.n * k.n);
            std::vector<long double> fl(k.n), Jl(k.n * k.n);
            k.rhs(0.0, y.data(), f.data());
            k.rhs_long(0.0L, yl.data(), fl.data());
            k.jacobian(0.0, y.data(), J.data());
            k.jacobian_long(0.0L, yl.data(), Jl.data());
            for (std::size_t i = 0; i < k.n; ++i)
                check_close(f[i], fl[i], unit + " rhs " + std::to_string(i), 1e-11L);
            for (std::size_t i = 0; i < k.n * k.n; ++i)
                check_close(J[i], Jl[i], unit + " jacobian " + std::to_string(i), 1e-11L);
        }
    }
}
