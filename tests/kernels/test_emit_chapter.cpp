// Generated kernels against equations written out by hand from the chapter:
// the free asymmetric top against Euler's equations (5.87)-(5.89) through the map (5.30), and the
// heavy symmetric top against (5.73)-(5.79).
#include "units.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>

namespace {

using vec3 = std::array<double, 3>;

struct angles_and_rates {
    double phi, theta, psi, phid, thetad, psid;
};

angles_and_rates random_point(std::mt19937& rng) {
    std::uniform_real_distribution<double> angle(0, 6.283185307179586), polar(0.3, 2.84),
        rate(-2, 2);
    return {angle(rng), polar(rng), angle(rng), rate(rng), rate(rng), rate(rng)};
}

// (5.30)
vec3 omega_of(const angles_and_rates& s) {
    return {s.phid * std::sin(s.theta) * std::sin(s.psi) + s.thetad * std::cos(s.psi),
            s.phid * std::sin(s.theta) * std::cos(s.psi) - s.thetad * std::sin(s.psi),
            s.phid * std::cos(s.theta) + s.psid};
}

// d/dt of (5.30) given the accelerations.
vec3 omega_dot_of(const angles_and_rates& s, const vec3& qdd) {
    const double st = std::sin(s.theta), ct = std::cos(s.theta), sp = std::sin(s.psi),
                 cp = std::cos(s.psi);
    return {qdd[0] * st * sp + s.phid * (ct * s.thetad * sp + st * cp * s.psid) + qdd[1] * cp -
                s.thetad * sp * s.psid,
            qdd[0] * st * cp + s.phid * (ct * s.thetad * cp - st * sp * s.psid) - qdd[1] * sp -
                s.thetad * cp * s.psid,
            qdd[0] * ct - s.phid * st * s.thetad + qdd[2]};
}

// Euler's equations, force-free, principal axes (5.87)-(5.89).
vec3 euler(const vec3& I, const vec3& w) {
    return {(I[1] - I[2]) * w[1] * w[2] / I[0], (I[2] - I[0]) * w[2] * w[0] / I[1],
            (I[0] - I[1]) * w[0] * w[1] / I[2]};
}

// p = J^T I omega for principal moments.
vec3 momenta_of(const angles_and_rates& s, const vec3& I) {
    const vec3 w = omega_of(s);
    const double st = std::sin(s.theta), ct = std::cos(s.theta), sp = std::sin(s.psi),
                 cp = std::cos(s.psi);
    const vec3 l{I[0] * w[0], I[1] * w[1], I[2] * w[2]};
    return {st * sp * l[0] + st * cp * l[1] + ct * l[2], cp * l[0] - sp * l[1], l[2]};
}

// d p / dt along the motion (l_dot = I omega_dot from Euler's equations).
vec3 momenta_dot_of(const angles_and_rates& s, const vec3& I) {
    const vec3 w = omega_of(s), wd = euler(I, w);
    const double st = std::sin(s.theta), ct = std::cos(s.theta), sp = std::sin(s.psi),
                 cp = std::cos(s.psi);
    const vec3 l{I[0] * w[0], I[1] * w[1], I[2] * w[2]},
        ld{I[0] * wd[0], I[1] * wd[1], I[2] * wd[2]};
    const double d_stsp = ct * s.thetad * sp + st * cp * s.psid,
                 d_stcp = ct * s.thetad * cp - st * sp * s.psid;
    return {d_stsp * l[0] + st * sp * ld[0] + d_stcp * l[1] + st * cp * ld[1] -
                st * s.thetad * l[2] + ct * ld[2],
            -sp * s.psid * l[0] + cp * ld[0] - cp * s.psid * l[1] - sp * ld[1], ld[2]};
}

template <class P> void set_free_moments(P& p, const vec3& I) {
    p.I1 = I[0], p.I2 = I[1], p.I3 = I[2];
}

} // namespace

TEST_CASE("free asymmetric top: every form follows Euler's equations (5.87)-(5.89)",
          "[emit][chapter]") {
    namespace lag = rotgen::models::free_asymmetric_top;
    namespace sol = rotgen::models::free_asymmetric_top_solve;
    namespace ham = rotgen::models::free_asymmetric_top_hamiltonian;
    namespace red = rotgen::models::free_asymmetric_top_reduced;
    namespace bod = rotgen::models::free_asymmetric_top_body;
    namespace bom = rotgen::models::free_asymmetric_top_body_omega;
    std::mt19937 rng(5);
    for (const vec3 I : {vec3{1.0, 2.0, 3.0}, vec3{1.7, 1.1, 2.3}}) {
        lag::params<double> pl;
        sol::params<double> ps;
        ham::params<double> ph;
        red::params<double> pr;
        bod::params<double> pb;
        bom::params<double> po;
        set_free_moments(pl, I), set_free_moments(ps, I), set_free_moments(ph, I),
            set_free_moments(pr, I), set_free_moments(pb, I), set_free_moments(po, I);
        for (int trial = 0; trial < 20; ++trial) {
            const angles_and_rates s = random_point(rng);
            const vec3 w = omega_of(s), wd = euler(I, w);
            // Lagrangian, both strategies: q_ddot, mapped to omega_dot by d/dt (5.30).
            const double yl[6] = {s.phi, s.theta, s.psi, s.phid, s.thetad, s.psid};
            double f[6];
            for (int strategy = 0; strategy < 2; ++strategy) {
                if (strategy == 0)
                    lag::rhs(0.0, yl, f, pl);
                else
                    sol::rhs(0.0, yl, f, ps);
                const vec3 got = omega_dot_of(s, {f[3], f[4], f[5]});
                for (int i = 0; i < 3; ++i)
                    CHECK(got[i] == Approx(wd[i]).epsilon(1e-11).margin(1e-11));
                for (int i = 0; i < 3; ++i)
                    CHECK(f[i] == yl[3 + i]);
            }
            double wl[3];
            lag::omega(yl, wl, pl);
            for (int i = 0; i < 3; ++i)
                CHECK(wl[i] == Approx(w[i]).epsilon(1e-13).margin(1e-13));
            // Hamiltonian: q_dot back, p_dot = d/dt (J^T I omega).
            const vec3 p = momenta_of(s, I), pd = momenta_dot_of(s, I);
            const double yh[6] = {s.phi, s.theta, s.psi, p[0], p[1], p[2]};
            ham::rhs(0.0, yh, f, ph);
            for (int i = 0; i < 3; ++i)
                CHECK(f[i] == Approx(yl[3 + i]).epsilon(1e-12).margin(1e-12));
            for (int i = 0; i < 3; ++i)
                CHECK(f[3 + i] == Approx(pd[i]).epsilon(1e-11).margin(1e-11));
            // Reduced (phi ignored, p_phi a parameter): y = (theta, psi, p_theta, p_psi).
            pr.p_phi = p[0];
            const double yr[4] = {s.theta, s.psi, p[1], p[2]};
            double fr[4], rates[1];
            red::rhs(0.0, yr, fr, pr);
            red::ignored_rates(yr, rates, pr);
            CHECK(fr[0] == Approx(s.thetad).epsilon(1e-12).margin(1e-12));
            CHECK(fr[1] == Approx(s.psid).epsilon(1e-12).margin(1e-12));
            CHECK(fr[2] == Approx(pd[1]).epsilon(1e-11).margin(1e-11));
            CHECK(fr[3] == Approx(pd[2]).epsilon(1e-11).margin(1e-11));
            CHECK(rates[0] == Approx(s.phid).epsilon(1e-12).margin(1e-12));
            // Body forms: omega_dot is Euler's equations, whatever the orientation.
            double fb[7];
            const double yo[3] = {w[0], w[1], w[2]};
            bom::rhs(0.0, yo, fb, po);
            for (int i = 0; i < 3; ++i)
                CHECK(fb[i] == Approx(wd[i]).epsilon(1e-13).margin(1e-13));
            const double yb[7] = {0.3, -0.5, 0.7, 0.1, w[0], w[1], w[2]};
            bod::rhs(0.0, yb, fb, pb);
            for (int i = 0; i < 3; ++i)
                CHECK(fb[4 + i] == Approx(wd[i]).epsilon(1e-13).margin(1e-13));
            // Energy: 1/2 sum I_i omega_i^2 in every form.
            const double T = (I[0] * w[0] * w[0] + I[1] * w[1] * w[1] + I[2] * w[2] * w[2]) / 2;
            CHECK(lag::energy(yl, pl) == Approx(T).epsilon(1e-13));
            CHECK(ham::energy(yh, ph) == Approx(T).epsilon(1e-12));
            CHECK(red::energy(yr, pr) == Approx(T).epsilon(1e-12));
            CHECK(bom::energy(yo, po) == Approx(T).epsilon(1e-13));
        }
    }
}

namespace {

struct heavy_top_values {
    double I1 = 1.3, I3 = 0.45, M = 0.8, g = 9.81, h = 0.12;
};

template <class P> void set_heavy(P& p, const heavy_top_values& v) {
    p.I1 = v.I1, p.I3 = v.I3, p.M = v.M, p.g = v.g, p.h = v.h;
}

} // namespace

TEST_CASE("heavy symmetric top: generated forms follow (5.73)-(5.79)", "[emit][chapter]") {
    namespace lag = rotgen::models::heavy_top;
    namespace sol = rotgen::models::heavy_top_solve;
    namespace ham = rotgen::models::heavy_top_hamiltonian;
    namespace red = rotgen::models::heavy_top_reduced;
    const heavy_top_values v;
    lag::params<double> pl;
    sol::params<double> ps;
    ham::params<double> ph;
    red::params<double> pr;
    set_heavy(pl, v), set_heavy(ps, v), set_heavy(ph, v), set_heavy(pr, v);
    const double Mgh = v.M * v.g * v.h;
    std::mt19937 rng(9);
    for (int trial = 0; trial < 30; ++trial) {
        const angles_and_rates s = random_point(rng);
        const double st = std::sin(s.theta), ct = std::cos(s.theta);
        const double w3 = s.phid * ct + s.psid;
        // (5.74)-(5.76)
        const double p_phi = v.I1 * s.phid * st * st + v.I3 * ct * w3, p_theta = v.I1 * s.thetad,
                     p_psi = v.I3 * w3;
        // Euler-Lagrange equations of (5.73), with p_phi and p_psi conserved.
        const double thetadd =
            (v.I1 * s.phid * s.phid * st * ct - v.I3 * w3 * s.phid * st + Mgh * st) / v.I1;
        const double phidd =
            (v.I3 * st * s.thetad * w3 - 2 * v.I1 * s.phid * st * ct * s.thetad) / (v.I1 * st * st);
        const double psidd = -(phidd * ct - s.phid * st * s.thetad);
        const double yl[6] = {s.phi, s.theta, s.psi, s.phid, s.thetad, s.psid};
        double f[6];
        for (int strategy = 0; strategy < 2; ++strategy) {
            if (strategy == 0)
                lag::rhs(0.0, yl, f, pl);
            else
                sol::rhs(0.0, yl, f, ps);
            CHECK(f[3] == Approx(phidd).epsilon(1e-11).margin(1e-11));
            CHECK(f[4] == Approx(thetadd).epsilon(1e-11).margin(1e-11));
            CHECK(f[5] == Approx(psidd).epsilon(1e-11).margin(1e-11));
        }
        double p[3];
        lag::momenta(yl, p, pl);
        CHECK(p[0] == Approx(p_phi).epsilon(1e-13).margin(1e-13));
        CHECK(p[1] == Approx(p_theta).epsilon(1e-13).margin(1e-13));
        CHECK(p[2] == Approx(p_psi).epsilon(1e-13).margin(1e-13));
        // (5.79) and Hamilton's equations written out from it.
        const double u = p_phi - p_psi * ct;
        const double H = p_theta * p_theta / (2 * v.I1) + p_psi * p_psi / (2 * v.I3) +
                         u * u / (2 * v.I1 * st * st) + Mgh * ct;
        // The generated energy against E = T + V with T and V read off (5.73) (in the rates), and
        // against H (5.79) (in the momenta (5.74)-(5.76)).
        const double T =
            v.I1 * (s.thetad * s.thetad + s.phid * s.phid * st * st) / 2 + v.I3 * w3 * w3 / 2;
        CHECK(lag::energy(yl, pl) == Approx(T + Mgh * ct).epsilon(1e-12));
        CHECK(lag::energy(yl, pl) == Approx(H).epsilon(1e-12));
        const double phid = u / (v.I1 * st * st), psid = p_psi / v.I3 - ct * u / (v.I1 * st * st);
        const double pthetad =
            -u * p_psi / (v.I1 * st) + u * u * ct / (v.I1 * st * st * st) + Mgh * st;
        const double yh[6] = {s.phi, s.theta, s.psi, p_phi, p_theta, p_psi};
        ham::rhs(0.0, yh, f, ph);
        CHECK(f[0] == Approx(phid).epsilon(1e-12).margin(1e-12));
        CHECK(f[1] == Approx(p_theta / v.I1).epsilon(1e-12).margin(1e-12));
        CHECK(f[2] == Approx(psid).epsilon(1e-12).margin(1e-12));
        CHECK(f[3] == Approx(0).margin(1e-12));
        CHECK(f[4] == Approx(pthetad).epsilon(1e-11).margin(1e-11));
        CHECK(f[5] == Approx(0).margin(1e-12));
        CHECK(ham::energy(yh, ph) == Approx(H).epsilon(1e-12));
        // The reduced form: y = (theta, p_theta), p_phi and p_psi parameters.
        pr.p_phi = p_phi, pr.p_psi = p_psi;
        const double yr[2] = {s.theta, p_theta};
        double fr[2], rates[2];
        red::rhs(0.0, yr, fr, pr);
        red::ignored_rates(yr, rates, pr);
        CHECK(fr[0] == Approx(p_theta / v.I1).epsilon(1e-12).margin(1e-12));
        CHECK(fr[1] == Approx(pthetad).epsilon(1e-11).margin(1e-11));
        CHECK(rates[0] == Approx(phid).epsilon(1e-12).margin(1e-12));
        CHECK(rates[1] == Approx(psid).epsilon(1e-12).margin(1e-12));
        CHECK(red::energy(yr, pr) == Approx(H).epsilon(1e-12));
    }
    SECTION("a point worked by hand") {
        // theta = pi/3, phi_dot = 2, theta_dot = 0.5, psi_dot = 1, with I1 = 1.3, I3 = 0.45,
        // M g h = 0.8 * 9.81 * 0.12 = 0.94176; cos theta = 1/2, sin^2 theta = 3/4:
        //   omega3 = phi_dot cos theta + psi_dot = 2;
        //   (5.74) p_phi = 1.3 * 2 * 3/4 + 0.45 * 1/2 * 2 = 2.4, (5.75) p_theta = 1.3 * 0.5 = 0.65,
        //   (5.76) p_psi = 0.45 * 2 = 0.9;
        //   (5.79) H = 0.65^2 / 2.6 + 0.9^2 / 0.9 + (2.4 - 0.45)^2 / (2.6 * 3/4) + 0.94176 / 2
        //            = 0.1625 + 0.9 + 1.95 + 0.47088 = 3.48338.
        const double third_pi = 3.141592653589793 / 3;
        const double yl[6] = {0.1, third_pi, 0.2, 2, 0.5, 1};
        double p[3];
        lag::momenta(yl, p, pl);
        CHECK(p[0] == Approx(2.4).epsilon(1e-14));
        CHECK(p[1] == Approx(0.65).epsilon(1e-14));
        CHECK(p[2] == Approx(0.9).epsilon(1e-14));
        CHECK(lag::energy(yl, pl) == Approx(3.48338).epsilon(1e-14));
        const double yh[6] = {0.1, third_pi, 0.2, 2.4, 0.65, 0.9};
        CHECK(ham::energy(yh, ph) == Approx(3.48338).epsilon(1e-14));
    }
}
