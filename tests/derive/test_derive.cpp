// The derivation against the chapter: (5.30), (5.72)-(5.79), Euler's equations (5.87)-(5.89),
// and cross-checks between independent routes (Lagrange vs Hamilton, H vs T + V).
#include "support.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

using namespace rotgen;
using namespace rotgen::test;
using GiNaC::cos;
using GiNaC::ex;
using GiNaC::pow;
using GiNaC::sin;

namespace {

// Symbolic equality: the difference reduces to zero in the canonical form; for expressions with
// 1/sin(theta) also after clearing sin(theta)^2 and using sin^2 + cos^2 = 1 for theta.
bool same(const ex& a, const ex& b) {
    const auto& s = symbols();
    ex d = canonical(a - b);
    if (d.is_zero()) return true;
    d = GiNaC::normal(
        d.subs(pow(sin(s.q[1]), 2) == 1 - pow(cos(s.q[1]), 2), GiNaC::subs_options::algebraic));
    return d.is_zero();
}

// Solves M(q) q_ddot = f(q, q_dot, t) numerically at the point and adds q_ddot to it.
void add_accelerations(point& pt, const derivation& d, const model_spec& spec) {
    Eigen::Matrix3d M;
    Eigen::Vector3d f;
    for (int i = 0; i < 3; ++i) {
        f[i] = eval(d.forcing[i], pt.values, spec);
        for (int j = 0; j < 3; ++j)
            M(i, j) = eval(d.mass_matrix[i][j], pt.values, spec);
    }
    const Eigen::Vector3d qdd = M.lu().solve(f);
    for (int i = 0; i < 3; ++i)
        pt.values[symbols().qdd[i]] = qdd[i];
}

ex param(const model_spec& spec, const std::string& name) {
    return spec.parameter_names().at(name);
}

struct heavy_top_fixture {
    model_spec spec = load_model(model_path("heavy_top"));
    derivation d = derive(spec);
    const coordinate_symbols& s = symbols();
    ex I1 = param(spec, "I1"), I3 = param(spec, "I3"), M = param(spec, "M"), g = param(spec, "g"),
       h = param(spec, "h");
    ex th = s.q[1];
    ex phid = s.qd[0], thd = s.qd[1], psid = s.qd[2];
};

} // namespace

TEST_CASE("body angular velocity is (5.30)", "[derive]") {
    const model_spec spec = load_model(model_path("free_asymmetric_top"));
    const derivation d = derive(spec);
    const auto& s = symbols();
    const ex th = s.q[1], ps = s.q[2];
    CHECK(same(d.omega[0], s.qd[0] * sin(th) * sin(ps) + s.qd[1] * cos(ps)));
    CHECK(same(d.omega[1], s.qd[0] * sin(th) * cos(ps) - s.qd[1] * sin(ps)));
    CHECK(same(d.omega[2], s.qd[0] * cos(th) + s.qd[2]));
}

TEST_CASE_METHOD(heavy_top_fixture, "symmetric top T and L are (5.72) and (5.73)", "[derive]") {
    const ex T = I1 / 2 * (pow(thd, 2) + pow(phid, 2) * pow(sin(th), 2)) +
                 I3 / 2 * pow(phid * cos(th) + psid, 2);
    CHECK(same(d.kinetic, T));
    CHECK(same(d.potential, M * g * h * cos(th)));
    CHECK(same(d.lagrangian, T - M * g * h * cos(th)));
    CHECK_FALSE(same(d.lagrangian, T + M * g * h * cos(th))); // the check can fail
}

TEST_CASE_METHOD(heavy_top_fixture, "symmetric top momenta are (5.74)-(5.76)", "[derive]") {
    CHECK(same(d.momenta[0], I1 * phid * pow(sin(th), 2) + I3 * cos(th) * (phid * cos(th) + psid)));
    CHECK(same(d.momenta[1], I1 * thd));
    CHECK(same(d.momenta[2], I3 * (phid * cos(th) + psid)));
    CHECK(d.cyclic == std::vector<int>{0, 2}); // phi and psi cyclic: p_phi, p_psi conserved
}

TEST_CASE_METHOD(heavy_top_fixture, "symmetric top Hamiltonian is (5.79)", "[derive]") {
    const ex pphi = s.p[0], pth = s.p[1], ppsi = s.p[2];
    const ex H = pow(pth, 2) / (2 * I1) + pow(ppsi, 2) / (2 * I3) +
                 pow(pphi - ppsi * cos(th), 2) / (2 * I1 * pow(sin(th), 2)) + M * g * h * cos(th);
    CHECK(same(d.hamiltonian, H));
    CHECK_FALSE(same(d.hamiltonian, H + pow(pth, 2) / (2 * I1)));
}

TEST_CASE("mass matrix is J^T I J, built independently", "[derive]") {
    const std::string name = GENERATE("heavy_top", "free_asymmetric_top", "full_tensor_top");
    const model_spec spec = load_model(model_path(name));
    const derivation d = derive(spec);
    const auto& s = symbols();
    const ex st = sin(s.q[1]), ct = cos(s.q[1]), sp = sin(s.q[2]), cp = cos(s.q[2]);
    const ex J[3][3] = {{st * sp, cp, 0}, {st * cp, -sp, 0}, {ct, 0, 1}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            ex m = 0;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    m += J[a][i] * spec.inertia[a][b] * J[b][j];
            INFO(name << " M[" << i << "][" << j << "]");
            CHECK(same(d.mass_matrix[i][j], m));
        }
}

TEST_CASE("free top: the Euler-Lagrange equations are Euler's equations (5.87)-(5.89)",
          "[derive]") {
    const model_spec spec = load_model(model_path("free_asymmetric_top"));
    const derivation d = derive(spec);
    const auto& s = symbols();
    const double I[3] = {1.0, 2.0, 3.0}; // the model's defaults
    // omega_dot = d/dt (J q_dot), in q, q_dot, q_ddot
    vector3 omega_dot;
    for (int i = 0; i < 3; ++i)
        omega_dot[i] = time_derivative(d.omega[i]);
    std::mt19937 rng(5087);
    for (int k = 0; k < 50; ++k) {
        point pt(rng, 0.05);
        add_accelerations(pt, d, spec); // q_ddot from M q_ddot = f
        double w[3], wd[3];
        for (int i = 0; i < 3; ++i) {
            w[i] = eval(d.omega[i], pt.values, spec);
            wd[i] = eval(omega_dot[i], pt.values, spec);
        }
        const double scale = 1 + w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
        INFO("state " << k);
        CHECK(I[0] * wd[0] == Approx((I[1] - I[2]) * w[1] * w[2]).margin(1e-11 * scale)); // (5.87)
        CHECK(I[1] * wd[1] == Approx((I[2] - I[0]) * w[2] * w[0]).margin(1e-11 * scale)); // (5.88)
        CHECK(I[2] * wd[2] == Approx((I[0] - I[1]) * w[0] * w[1]).margin(1e-11 * scale)); // (5.89)
    }
}

TEST_CASE("H and E equal 1/2 w.I.w (5.30, 5.38) + V, and Hamilton agrees with Euler-Lagrange",
          "[derive]") {
    const std::string name =
        GENERATE("heavy_top", "free_asymmetric_top", "full_tensor_top", "damped_driven_top");
    const model_spec spec = load_model(model_path(name));
    const derivation d = derive(spec);
    const auto& s = symbols();
    vector3 p_dot_along_motion; // d/dt p(q, q_dot)
    for (int i = 0; i < 3; ++i)
        p_dot_along_motion[i] = time_derivative(d.momenta[i]);
    std::mt19937 rng(5079);
    for (int k = 0; k < 20; ++k) {
        point pt(rng);
        add_accelerations(pt, d, spec);
        // the point in phase space: p = p(q, q_dot)
        GiNaC::exmap phase = pt.values;
        for (int i = 0; i < 3; ++i)
            phase[s.p[i]] = eval(d.momenta[i], pt.values, spec);
        INFO(name << " state " << k);
        const double E = eval(d.energy, pt.values, spec);
        CHECK(eval(d.hamiltonian, phase, spec) == Approx(E).epsilon(1e-12).margin(1e-12));
        // The energy against T computed here in doubles, independently of the derivation: the
        // body rates (5.30) from the angles and rates, T = 1/2 sum_ij I_ij w_i w_j (5.38) with the
        // model's tensor; V is the model's potential as written (the input, not the derivation).
        const double ph = eval(s.qd[0], pt.values, spec), th = eval(s.qd[1], pt.values, spec),
                     ps = eval(s.qd[2], pt.values, spec), theta = eval(s.q[1], pt.values, spec),
                     psi = eval(s.q[2], pt.values, spec);
        const Eigen::Vector3d w(ph * std::sin(theta) * std::sin(psi) + th * std::cos(psi),
                                ph * std::sin(theta) * std::cos(psi) - th * std::sin(psi),
                                ph * std::cos(theta) + ps);
        Eigen::Matrix3d I;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                I(i, j) = eval(spec.inertia[i][j], pt.values, spec);
        const double T = 0.5 * w.dot(I * w), V = eval(spec.potential, pt.values, spec);
        CHECK(E == Approx(T + V).epsilon(1e-12).margin(1e-12));
        for (int i = 0; i < 3; ++i) {
            const double qd = eval(s.qd[i], pt.values, spec);
            CHECK(eval(d.hamilton_qdot[i], phase, spec) == Approx(qd).epsilon(1e-11).margin(1e-11));
            CHECK(
                eval(d.hamilton_pdot[i], phase, spec) ==
                Approx(eval(p_dot_along_motion[i], pt.values, spec)).epsilon(1e-10).margin(1e-10));
        }
    }
}

TEST_CASE("damping and torque enter as the generalised force Q = -c q_dot + J^T tau", "[derive]") {
    const model_spec spec = load_model(model_path("damped_driven_top"));
    const derivation d = derive(spec);
    const auto& s = symbols();
    const ex c = param(spec, "c"), A = param(spec, "A"), w = param(spec, "w");
    // tau = (0, 0, A sin(w t)); (J^T tau)_i = J[2][i] tau3 = (cos(theta), 0, 1) tau3
    const ex tau3 = A * sin(w * s.t);
    CHECK(same(d.generalized_force[0], -c * s.qd[0] + cos(s.q[1]) * tau3));
    CHECK(same(d.generalized_force[1], -c * s.qd[1]));
    CHECK(same(d.generalized_force[2], -c * s.qd[2] + tau3));
    CHECK(d.cyclic.empty()); // damping breaks the conservation of p_phi and p_psi
}

TEST_CASE("gravity shorthand gives M g (com . e_z), e_z the third column of A", "[derive]") {
    const model_spec spec = load_model(model_path("full_tensor_top"));
    const auto& s = symbols();
    const ex M = param(spec, "M"), g = param(spec, "g"), cx = param(spec, "cx"),
             cy = param(spec, "cy"), cz = param(spec, "cz");
    const ex th = s.q[1], ps = s.q[2];
    CHECK(same(spec.potential,
               M * g * (cx * sin(th) * sin(ps) + cy * sin(th) * cos(ps) + cz * cos(th))));
}

TEST_CASE("inspect output is byte-identical across processes", "[derive][cli]") {
    // GiNaC's term order depends on hash seeds that change between runs; rotgen's printers must
    // not. Run the executable several times and compare every format.
    for (const char* format : {"json", "text", "latex"}) {
        const std::string args =
            "inspect '" + model_path("full_tensor_top") + "' --format " + format;
        const run_result first = run_rotgen(args);
        REQUIRE(first.status == 0);
        REQUIRE(first.out.size() > 1000);
        for (int k = 0; k < 3; ++k)
            CHECK(run_rotgen(args).out == first.out);
    }
}
