// J(q) of every Euler sequence (expr/angles.hpp, derive/derive.cpp), derived from the product of
// the elementary rotations: for z-x-z it is the chapter's (5.30) symbolically; for all twelve,
// det J is one term (sin or cos of the middle angle: the singular set), J^{-1} J = 1 at random
// angles, and J gives the omega of [omega]x = -A_dot A^T. The model's angle names reach the
// parser and the printers.
#include "support.hpp"

#include "expr/angles.hpp"
#include "inspect/inspect.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace rotgen;
using namespace rotgen::test;
using GiNaC::ex;

namespace {

model_spec read(const std::string& name, const std::string& text) {
    const scratch_file f(name + ".yaml", text);
    return load_model(f.path);
}

double value(const ex& e, const GiNaC::exmap& at) {
    return GiNaC::ex_to<GiNaC::numeric>(e.subs(at).evalf()).to_double();
}

} // namespace

TEST_CASE("the derived J of zxz is the chapter's (5.30)", "[derive]") {
    const model_spec spec = read("seq_zxz", "name: t\ninertia: [1, 2, 3]\n");
    const derivation d = derive(spec);
    const auto& s = symbols();
    const ex st = GiNaC::sin(s.q[1]), ct = GiNaC::cos(s.q[1]);
    const ex sp = GiNaC::sin(s.q[2]), cp = GiNaC::cos(s.q[2]);
    const ex want[3][3] = {{st * sp, cp, 0}, {st * cp, -sp, 0}, {ct, 0, 1}};
    const ex inv[3][3] = {{sp / st, cp / st, 0}, {cp, -sp, 0}, {-sp * ct / st, -cp * ct / st, 1}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            CHECK((d.omega_jacobian[i][j] - want[i][j]).expand().is_zero());
            CHECK((d.inverse_omega_jacobian[i][j] - inv[i][j]).expand().is_zero());
        }
}

TEST_CASE("J of all twelve sequences: det J is sin or cos of the middle angle, J^-1 J = 1",
          "[derive]") {
    const auto& s = symbols();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> angle(0.2, 1.3);
    double worst = 0;
    for (const char* seq :
         {"zxz", "zyz", "xyx", "xzx", "yxy", "yzy", "zyx", "zxy", "yxz", "yzx", "xyz", "xzy"}) {
        const model_spec spec =
            read("seq_all", std::string("name: t\nangles: ") + seq + "\ninertia: [1, 2, 3]\n");
        const derivation d = derive(spec);
        const bool proper = seq[0] == seq[2];
        ex det = 0;
        for (int k = 0; k < 3; ++k) {
            const int a = (k + 1) % 3, b = (k + 2) % 3;
            det += d.omega_jacobian[0][k] * (d.omega_jacobian[1][a] * d.omega_jacobian[2][b] -
                                             d.omega_jacobian[1][b] * d.omega_jacobian[2][a]);
        }
        GiNaC::exmap at;
        for (int i = 0; i < 3; ++i)
            at[s.q[i]] = angle(rng);
        const double beta = value(s.q[1], at);
        // |det J| = |sin beta| (proper Euler) or |cos beta| (Tait-Bryan)
        CHECK(std::abs(std::abs(value(det, at)) -
                       (proper ? std::abs(std::sin(beta)) : std::abs(std::cos(beta)))) <= 1e-14);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                ex prod = 0;
                for (int k = 0; k < 3; ++k)
                    prod += d.inverse_omega_jacobian[i][k] * d.omega_jacobian[k][j];
                worst = std::max(worst, std::abs(value(prod, at) - (i == j ? 1 : 0)));
            }
    }
    CHECK(worst <= 1e-18); // observed 7.5e-20 (17 digits)
}

TEST_CASE("a model's angle names are parsed and printed, the chapter's refused", "[derive]") {
    const model_spec spec = read("seq_names", "name: sat\nangles: {sequence: zyx, names: [yaw, "
                                              "pitch, roll]}\ninertia: [1.2, 1, 0.4]\n"
                                              "potential: cos(pitch)*sin(roll)\n");
    const std::string text = inspect(spec, derive(spec), output_format::text);
    CHECK(text.find("yaw, pitch, roll (z-y-x Tait-Bryan angles") != std::string::npos);
    CHECK(text.find("pitch_dot") != std::string::npos);
    CHECK(text.find("p_roll") != std::string::npos);
    CHECK(text.find("theta") == std::string::npos);
    CHECK_THROWS_WITH(read("seq_bad", "name: sat\nangles: zyx\ninertia: [1.2, 1, 0.4]\n"
                                      "potential: cos(theta)\n"),
                      Catch::Contains("unknown symbol 'theta'"));
    CHECK_THROWS_WITH(read("seq_bad", "name: sat\nangles: zzx\ninertia: [1, 1, 1]\n"),
                      Catch::Contains("unknown Euler sequence 'zzx'"));
    CHECK_THROWS_WITH(read("seq_bad", "name: sat\nangles: {sequence: xyz, names: [a, a, b]}\n"
                                      "inertia: [1, 1, 1]\n"),
                      Catch::Contains("given twice"));
    CHECK_THROWS_WITH(read("seq_bad", "name: sat\nangles: {sequence: xyz, names: [sin, b, c]}\n"
                                      "inertia: [1, 1, 1]\n"),
                      Catch::Contains("cannot name an angle"));
    CHECK_THROWS_WITH(read("seq_bad", "name: sat\nangles: {sequence: xyz, names: [u, v, w]}\n"
                                      "parameters: {v_dot: 1}\ninertia: [1, 1, 1]\n"),
                      Catch::Contains("cannot be a parameter name"));
}

// The convention is the model's, not the process's: a model read after another (or derived while
// another is read, on another thread) leaves the first one's names and sequence as they were.
TEST_CASE("two models keep their own conventions whichever was read last", "[derive]") {
    const model_spec sat = read("seq_two_sat", "name: sat\nangles: zyx\ninertia: [1.2, 1, 0.4]\n"
                                               "potential: cos(pitch)*sin(roll)\n");
    const model_spec top = read("seq_two_top", "name: top\ninertia: [1, 1, 0.5]\n"
                                               "potential: cos(theta)\n");
    const derivation d_sat = derive(sat), d_top = derive(top);
    CHECK(sat.angles.sequence() == "zyx");
    CHECK(d_sat.angles.names == std::array<std::string, 3>{"yaw", "pitch", "roll"});
    CHECK(d_top.angles.sequence() == "zxz");
    const std::string text = inspect(sat, d_sat, output_format::text);
    CHECK(text.find("yaw, pitch, roll (z-y-x Tait-Bryan angles") != std::string::npos);
    CHECK(text.find("theta") == std::string::npos);
    // the z-y-x J, not z-x-z's: its (3, 1) entry is -sin(pitch) (z-x-z: cos(theta))
    const auto& s = symbols();
    CHECK((d_sat.omega_jacobian[0][0] + GiNaC::sin(s.q[1])).expand().is_zero());
    CHECK((d_top.omega_jacobian[2][0] - GiNaC::cos(s.q[1])).expand().is_zero());
    CHECK(inspect(top, d_top, output_format::text).find("phi, theta, psi") != std::string::npos);
}
