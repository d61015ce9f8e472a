// The recordable quantities built from each form (generator/run/records.cpp, kernels.cpp):
// q0..q3, L1..L3, Lx..Lz, T and V, checked against truth computed here independently: A of
// (5.25) from the recorded angles, I omega from the model's moments, the heavy top's V and its
// conserved p_phi = Lz, and the constancy of a free top's angular momentum in space.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>

using namespace rotgen::test;

namespace {

using mat = std::array<std::array<double, 3>, 3>;

// A = Az(psi) Ax(theta) Az(phi) (5.25), written out: body <- space.
mat rotation_525(double phi, double theta, double psi) {
    const double cf = std::cos(phi), sf = std::sin(phi), ct = std::cos(theta), st = std::sin(theta),
                 cp = std::cos(psi), sp = std::sin(psi);
    return {{{cp * cf - ct * sf * sp, cp * sf + ct * cf * sp, sp * st},
             {-sp * cf - ct * sf * cp, -sp * sf + ct * cf * cp, cp * st},
             {st * sf, -st * cf, ct}}};
}

// R(q), the active rotation body -> space of the unit quaternion (w, x, y, z).
mat rotation_of(double w, double x, double y, double z) {
    return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
             {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
             {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

const std::string all = "[phi, theta, psi, q0, q1, q2, q3, omega1, omega2, omega3, L1, L2, L3, "
                        "Lx, Ly, Lz, T, V, energy]";

csv_table run_scene(const std::string& name, const std::string& text, std::string* out = nullptr) {
    const scratch_file scene(name + ".yaml", text);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/" + name + ".csv";
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    if (out) *out = r.out;
    csv_table t = read_csv(csv);
    std::remove(csv.c_str());
    return t;
}

// Every sample: |q| = 1, q0 >= 0, R(q) = A^T (A of 5.25 from the recorded angles, so the
// quaternion and the angles are one attitude), L_i = I_i omega_i, L_space = A^T L, |L_space| =
// |L|, T = 1/2 sum I_i omega_i^2, T + V = energy. Returns the largest deviation.
double check_samples(const csv_table& t, const std::array<double, 3>& I) {
    double worst = 0;
    const auto dev = [&](double a, double b) { worst = std::max(worst, std::abs(a - b)); };
    for (const auto& r : t.rows) {
        const auto v = [&](const char* n) { return r[t.column(n)]; };
        const double q[4] = {v("q0"), v("q1"), v("q2"), v("q3")};
        CHECK(q[0] >= 0);
        dev(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1);
        const mat A = rotation_525(v("phi"), v("theta"), v("psi"));
        const mat R = rotation_of(q[0], q[1], q[2], q[3]);
        const double w[3] = {v("omega1"), v("omega2"), v("omega3")};
        const double L[3] = {v("L1"), v("L2"), v("L3")}, Ls[3] = {v("Lx"), v("Ly"), v("Lz")};
        double T = 0, n2 = 0, ns2 = 0;
        for (int i = 0; i < 3; ++i) {
            dev(L[i], I[i] * w[i]);
            T += I[i] * w[i] * w[i] / 2;
            double s = 0;
            for (int j = 0; j < 3; ++j) {
                dev(R[i][j], A[j][i]);
                s += A[j][i] * L[j];
            }
            dev(Ls[i], s);
            n2 += L[i] * L[i], ns2 += Ls[i] * Ls[i];
        }
        dev(std::sqrt(ns2), std::sqrt(n2));
        dev(v("T"), T);
        dev(v("T") + v("V"), v("energy"));
    }
    return worst;
}

double largest_change(const csv_table& t, const char* name) {
    const auto v = t.values(name);
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return std::max(*hi - v.front(), v.front() - *lo);
}

// A scene of a shipped model in `form` from `initial`, with dop853 at rtol 1e-12.
std::string scene(const std::string& model, const std::string& form, const std::string& initial,
                  const std::string& rest) {
    return "model: " + model_path(model) + "\nform: " + form + "\ninitial: {" + initial +
           "}\nintegrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n" + rest;
}

} // namespace

TEST_CASE("a free top's quaternion, L and energies in every form agree with (5.25) and I omega",
          "[run][records]") {
    const std::string form = GENERATE(as<std::string>{}, "lagrangian", "hamiltonian", "body");
    INFO(form);
    const csv_table t = run_scene(
        "records_free_" + form,
        scene("free_asymmetric_top", form,
              "phi: 0.3, theta: 1.1, psi: 2.5, omega1: 0.4, omega2: 1, omega3: 0.3",
              "time: {end: 20, samples: 201}\nswitch_chart: false\nrecord: " + all + "\n"));
    REQUIRE(t.rows.size() == 201);
    // measured 1.0e-15 (lagrangian), 8.9e-16 (hamiltonian), 1.8e-15 (body)
    CHECK(check_samples(t, {1, 2, 3}) < 1e-14);
    // the angular momentum in space is constant: measured 5.6e-16 .. 1.2e-11
    for (const char* n : {"Lx", "Ly", "Lz"})
        CHECK(largest_change(t, n) < 1e-10);
    CHECK(largest_change(t, "V") == 0);
}

TEST_CASE("q, L and the energies stay right across chart switches (a top tumbling through "
          "theta ~ 0)",
          "[run][records]") {
    std::string summary;
    const csv_table t = run_scene(
        "records_tumble",
        "model: " + model_path("free_asymmetric_top") +
            "\nform: lagrangian\ninitial: {phi: 0, theta: 0.5, psi: 0, omega1: 0.05, omega2: 0.5, "
            "omega3: 1}\ntime: {end: 100, samples: 2001}\nintegrator: {method: dop853, rtol: "
            "1e-10, atol: 1e-12}\nrecord: " +
            all + "\n",
        &summary);
    CHECK(summary.find("switched to the body form") != std::string::npos);
    // measured 1.4e-15, also in the samples the body form integrated (angles from q)
    CHECK(check_samples(t, {1, 2, 3}) < 1e-14);
    // L in space through the changes of chart: measured 8.5e-11 .. 4.3e-10
    for (const char* n : {"Lx", "Ly", "Lz"})
        CHECK(largest_change(t, n) < 3e-9);
}

TEST_CASE("the heavy top's V is M g h cos theta, T + V = energy and Lz = p_phi, in every form",
          "[run][records]") {
    const std::string form =
        GENERATE(as<std::string>{}, "lagrangian", "hamiltonian", "reduced", "body");
    INFO(form);
    const bool reduced = form == "reduced";
    const csv_table t = run_scene(
        "records_heavy_" + form,
        scene("heavy_top", form,
              "phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30",
              "time: {end: 2, samples: 101}\nrecord: " +
                  std::string(reduced ? "[theta, T, V, energy, phi_dot, theta_dot, psi_dot]"
                                      : "[theta, T, V, energy, Lz, p_phi, phi_dot, "
                                        "theta_dot, psi_dot]") +
                  "\n"));
    double worst = 0, worst_t = 0;
    for (const auto& r : t.rows) {
        const auto v = [&](const char* n) { return r[t.column(n)]; };
        worst = std::max(worst, std::abs(v("V") - 1.0 * 9.81 * 0.1 * std::cos(v("theta"))));
        worst = std::max(worst, std::abs(v("T") + v("V") - v("energy")) / v("energy"));
        if (!reduced) worst = std::max(worst, std::abs(v("Lz") - v("p_phi")) / v("p_phi"));
        // T from the rates (5.73), I1 = 1, I3 = 0.5: not from the form's own T or energy
        const double st = std::sin(v("theta")), ct = std::cos(v("theta"));
        const double spin = v("psi_dot") + v("phi_dot") * ct;
        const double T =
            0.5 * (v("theta_dot") * v("theta_dot") + v("phi_dot") * v("phi_dot") * st * st) +
            0.5 * 0.5 * spin * spin;
        worst_t = std::max(worst_t, std::abs(v("T") - T) / T);
    }
    CHECK(worst_t < 3e-15); // observed 0 (Euler-angle forms, body), 2.5e-16 (reduced)
    // the energy is conserved, whatever defines it: observed 1.3e-16 .. 5.0e-16 relative
    CHECK(largest_change(t, "energy") < 5e-15 * t.values("energy")[0]);
    // measured 1.1e-16 (Euler-angle and reduced forms), 4.0e-16 (body)
    CHECK(worst < 3e-15);
    // Lz = p_phi is conserved: measured 0 .. 2.7e-13 (body)
    if (!reduced) CHECK(largest_change(t, "Lz") < 2e-12);
}
