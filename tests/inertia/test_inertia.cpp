// Inertia from parts, rotations of tensors, principal axes and the stability report
// (generator/inertia.hpp) against the chapter's worked examples 5.1–5.6, textbook formulas and a
// direct numerical integration.
#include "inertia/inertia.hpp"
#include "support.hpp"

#include <rotation.hpp> // the runtime's rotation utilities

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include <cmath>

using namespace rotgen;
using namespace rotgen::test;
using GiNaC::ex;
using GiNaC::numeric;

namespace {

const double pi = 3.141592653589793;

bool vanishes(const ex& e) {
    return GiNaC::normal(e.expand()).is_zero();
}

// Algebraic numbers are compared to 50 digits (GiNaC does not rewrite sqrt(2)*sqrt(3) as
// sqrt(6), so two exact forms of one number need not cancel symbolically).
bool same_number(const ex& a, const ex& b) {
    const long saved = GiNaC::Digits;
    GiNaC::Digits = 60;
    const ex d = GiNaC::evalf(a - b);
    GiNaC::Digits = saved;
    return GiNaC::is_a<numeric>(d) &&
           GiNaC::abs(GiNaC::ex_to<numeric>(d)) < numeric(1, 1) / GiNaC::pow(numeric(10), 50);
}

double value(const ex& e, const GiNaC::exmap& at = {}) {
    const ex v = GiNaC::evalf(e.subs(at));
    REQUIRE(GiNaC::is_a<numeric>(v));
    return GiNaC::ex_to<numeric>(v).to_double();
}

Eigen::Matrix3d numbers(const matrix3& m, const GiNaC::exmap& at = {}) {
    Eigen::Matrix3d r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r(i, j) = value(m[i][j], at);
    return r;
}

matrix3 from_rows(std::initializer_list<std::initializer_list<ex>> rows) {
    matrix3 m;
    int i = 0;
    for (const auto& row : rows) {
        int j = 0;
        for (const ex& x : row)
            m[i][j++] = x;
        ++i;
    }
    return m;
}

part make_box(const ex& m, const vector3& size, const vector3& at) {
    part p;
    p.kind = part_kind::box;
    p.mass = m;
    p.size = size;
    p.at = at;
    return p;
}

part make_point(const ex& m, const vector3& at) {
    part p;
    p.kind = part_kind::point;
    p.mass = m;
    p.at = at;
    return p;
}

part make_axial(part_kind kind, const ex& m, const ex& radius, const ex& length,
                const vector3& axis, const vector3& at = {0, 0, 0}) {
    part p;
    p.kind = kind;
    p.mass = m;
    p.radius = radius;
    p.length = length;
    p.axis = axis;
    p.at = at;
    return p;
}

// sin^2 -> 1 - cos^2 for the dumbbell's angle, so trigonometric identities cancel.
ex trig_canonical(const ex& e, const GiNaC::realsymbol& a) {
    return e.expand()
        .subs(GiNaC::pow(GiNaC::sin(a), 2) == 1 - GiNaC::pow(GiNaC::cos(a), 2),
              GiNaC::subs_options::algebraic)
        .expand();
}

} // namespace

TEST_CASE("inertia: Examples 5.1 and 5.2: the two products of elementary rotations, exact, differ",
          "[inertia][rotation]") {
    const ex deg30 = GiNaC::Pi / 6, deg45 = GiNaC::Pi / 4;
    const ex r2 = GiNaC::sqrt(ex(2)), r3 = GiNaC::sqrt(ex(3)), r6 = GiNaC::sqrt(ex(6));
    // (5.11), (5.12): the elementary matrices come out exact
    const matrix3 ax = rotation_x(deg30), az = rotation_z(deg45);
    CHECK(vanishes(ax[1][1] - r3 / 2));
    CHECK(vanishes(ax[2][1] + numeric(1, 2)));
    CHECK(vanishes(az[0][1] - r2 / 2));
    // (5.13): 30 degrees about x, then 45 degrees about z: B = Az Ax (5.10)
    const matrix3 b = multiply(az, ax);
    const matrix3 expected_b = from_rows(
        {{r2 / 2, r6 / 4, r2 / 4}, {-r2 / 2, r6 / 4, r2 / 4}, {0, -numeric(1, 2), r3 / 2}});
    // (5.14): the other order, B' = Ax Az
    const matrix3 b_prime = multiply(ax, az);
    const matrix3 expected_b_prime = from_rows(
        {{r2 / 2, r2 / 2, 0}, {-r6 / 4, r6 / 4, numeric(1, 2)}, {r2 / 4, -r2 / 4, r3 / 2}});
    bool differ = false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            INFO("entry " << i << j << ": " << b[i][j] << " and " << b_prime[i][j]);
            CHECK(same_number(b[i][j], expected_b[i][j]));
            CHECK(same_number(b_prime[i][j], expected_b_prime[i][j]));
            // each entry exact: its square is rational
            CHECK(GiNaC::is_a<numeric>(GiNaC::pow(b[i][j], 2).expand()));
            if (!same_number(b[i][j], b_prime[i][j])) differ = true;
        }
    CHECK(differ); // rotations do not commute
    // both orthogonal and proper, exactly: B Bᵀ = 1, and the runtime's double versions agree
    const matrix3 bbt = multiply(b, transpose(b));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(vanishes(bbt[i][j] - (i == j ? 1 : 0)));
    const Eigen::Matrix3d runtime_b = compose<double>(rot_z(pi / 4), rot_x(pi / 6));
    CHECK((runtime_b - numbers(b)).cwiseAbs().maxCoeff() < 1e-15);
    CHECK(is_proper_rotation<double>(runtime_b, 1e-14));
}

TEST_CASE("inertia: Example 5.3: a rotation about y has theta = vartheta, phi = pi/2, psi = -pi/2",
          "[inertia][rotation]") {
    // Exactly, for a symbolic angle: Az(-pi/2) Ax(t) Az(pi/2) = Ay(t) (5.25, 5.26).
    const GiNaC::realsymbol t("t");
    const matrix3 a = euler_rotation(GiNaC::Pi / 2, t, -GiNaC::Pi / 2);
    const matrix3 ay = rotation_y(t);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(vanishes(a[i][j] - ay[i][j]));
    // With the runtime's euler_from_matrix (psi in [0, 2 pi): -pi/2 is 3 pi/2).
    for (double vartheta : {0.2, 1.0, 2.0, 3.0}) {
        INFO("vartheta = " << vartheta);
        const euler_angles<double> e = euler_from_matrix<double>(rot_y(vartheta));
        CHECK(e.theta == Approx(vartheta).margin(1e-14));
        CHECK(e.phi == Approx(pi / 2).margin(1e-14));
        CHECK(e.psi == Approx(3 * pi / 2).margin(1e-14));
    }
}

TEST_CASE("inertia: Example 5.4: the dumbbell's tensor and its three kinetic energies",
          "[inertia]") {
    const GiNaC::realsymbol m1("m1"), m2("m2"), r1("r1"), r2("r2"), a("a"), w("w");
    const ex s = GiNaC::sin(a), c = GiNaC::cos(a);
    const body_inertia b =
        combine_parts({make_point(m1, {r1 * s, r1 * c, 0}), make_point(m2, {-r2 * s, -r2 * c, 0})},
                      vector3{0, 0, 0}, {});
    const ex k = m1 * r1 * r1 + m2 * r2 * r2;
    const matrix3 expected =
        from_rows({{k * c * c, -k * s * c, 0}, {-k * s * c, k * s * s, 0}, {0, 0, k}});
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            INFO(i << j << ": " << b.tensor[i][j]);
            CHECK(trig_canonical(b.tensor[i][j] - expected[i][j], a).is_zero());
        }
    const auto kinetic = [&](const vector3& omega) {
        ex t = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                t += omega[i] * b.tensor[i][j] * omega[j] / 2; // (5.38)
        return trig_canonical(t, a);
    };
    CHECK(trig_canonical(kinetic({0, w, 0}) - k * w * w * s * s / 2, a).is_zero()); // about y
    CHECK(trig_canonical(kinetic({0, 0, w}) - k * w * w / 2, a).is_zero());         // about z
    CHECK(kinetic({w * s, w * c, 0}).is_zero()); // about its own axis
    // A body on a line: a rotor (§5.5); rotation about the line is no rotation at all.
    const GiNaC::exmap at{{m1, 1}, {m2, 2}, {r1, 0.5}, {r2, 0.3}, {a, 0.4}};
    const inertia_report r = analyse_inertia(b.tensor, at);
    CHECK(r.kind == top_class::rotor);
    CHECK(r.stability[0].kind == stability_kind::none);
    CHECK(r.stability[1].stable);
    CHECK(r.stability[2].stable);
}

TEST_CASE("inertia: Example 5.5: the cube about a corner, exactly (5.41-5.43)", "[inertia]") {
    const GiNaC::realsymbol M("M"), L("L");
    const body_inertia b =
        combine_parts({make_box(M, {L, L, L}, {L / 2, L / 2, L / 2})}, vector3{0, 0, 0}, {});
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(vanishes(b.tensor[i][j] - (i == j ? numeric(2, 3) : -numeric(1, 4)) * M * L * L));
    CHECK(vanishes(b.mass - M));
    for (int i = 0; i < 3; ++i)
        CHECK(vanishes(b.centre_of_mass[i] - L / 2));

    SECTION("the shipped model reads the same tensor from its parts") {
        const model_spec spec = load_model(model_path("cube_on_corner"));
        const ex Ms = spec.parameter_names().at("M"), Ls = spec.parameter_names().at("L");
        REQUIRE(spec.body);
        CHECK(!spec.inertia_diagonal);
        CHECK(vanishes(spec.inertia[0][0] - numeric(2, 3) * Ms * Ls * Ls));
        CHECK(vanishes(spec.inertia[0][1] + numeric(1, 4) * Ms * Ls * Ls));
        // gravity without mass and com: the parts' mass and centre of mass relative to the pivot
        const scratch_file explicit_gravity(
            "inertia_cube_explicit.yaml",
            "name: cube\nparameters: {M: 1.0, L: 0.2, g: 9.81}\n"
            "inertia: [[2/3*M*L^2, -1/4*M*L^2, -1/4*M*L^2], [-1/4*M*L^2, 2/3*M*L^2, -1/4*M*L^2], "
            "[-1/4*M*L^2, -1/4*M*L^2, 2/3*M*L^2]]\ngravity: {mass: M, g: g, com: [L/2, L/2, "
            "L/2]}\n");
        const model_spec e = load_model(explicit_gravity.path);
        GiNaC::exmap same;
        for (const char* n : {"M", "L", "g"})
            same[e.parameter_names().at(n)] = spec.parameter_names().at(n);
        CHECK(vanishes(spec.potential - e.potential.subs(same)));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                CHECK(vanishes(spec.inertia[i][j] - e.inertia[i][j].subs(same)));
    }
    SECTION("about its centre the cube is a spherical top") {
        const body_inertia c =
            combine_parts({make_box(M, {L, L, L}, {L / 2, L / 2, L / 2})}, std::nullopt, {});
        for (int i = 0; i < 3; ++i) {
            CHECK(vanishes(c.pivot[i] - L / 2));
            for (int j = 0; j < 3; ++j)
                CHECK(vanishes(c.tensor[i][j] - (i == j ? M * L * L / 6 : ex(0))));
        }
        CHECK(analyse_inertia(c.tensor, {{M, 1}, {L, 1}}).kind == top_class::spherical);
    }
}

TEST_CASE(
    "inertia: Example 5.6: the cube's principal moments and axes, and A I A^T is diagonal (5.69)",
    "[inertia]") {
    const GiNaC::realsymbol M("M"), L("L");
    const GiNaC::exmap defaults{{M, 1.0}, {L, 0.2}};
    const matrix3 tensor =
        combine_parts({make_box(M, {L, L, L}, {L / 2, L / 2, L / 2})}, vector3{0, 0, 0}, defaults)
            .tensor;
    const principal_axes p = find_principal_axes(tensor, defaults);
    REQUIRE(p.exact_axes);
    CHECK(vanishes(p.moments[0] - M * L * L / 6));
    CHECK(vanishes(p.moments[1] - numeric(11, 12) * M * L * L));
    CHECK(vanishes(p.moments[2] - numeric(11, 12) * M * L * L));
    const ex r3 = GiNaC::sqrt(ex(3));
    for (int j = 0; j < 3; ++j)
        CHECK(vanishes(p.axes[0][j] - r3 / 3)); // (1, 1, 1)/sqrt(3)
    // A I Aᵀ = diag(1/6, 11/12, 11/12) M L², exactly, with A proper
    const matrix3 d = transform_tensor(p.axes, tensor);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(vanishes(d[i][j] - (i == j ? p.moments[i] : ex(0))));
    CHECK(numbers(p.axes).determinant() == Approx(1).epsilon(1e-14));
    // The chapter's own A (5.68) gives M L²/12 diag(2, 11, 11) (5.69)
    const ex r2 = GiNaC::sqrt(ex(2)), r6 = GiNaC::sqrt(ex(6));
    const matrix3 chapter = from_rows(
        {{r2 / r6, r2 / r6, r2 / r6}, {-r3 / r6, r3 / r6, 0}, {-1 / r6, -1 / r6, 2 / r6}});
    const matrix3 dc = transform_tensor(chapter, tensor);
    const GiNaC::exmap unit{{M, 1}, {L, 1}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(same_number(dc[i][j].subs(unit), i != j   ? ex(0)
                                                   : i == 0 ? ex(numeric(2, 12))
                                                            : ex(numeric(11, 12))));
    // a symmetric top: stable about the diagonal at 9/11 of the spin, neutral across it
    const inertia_report r = analyse_inertia(tensor, defaults);
    CHECK(r.kind == top_class::symmetric);
    CHECK(r.stability[0].kind == stability_kind::stable);
    CHECK(vanishes(r.stability[0].rate - numeric(9, 11)));
    CHECK(r.stability[1].kind == stability_kind::neutral);
    CHECK(r.stability[2].kind == stability_kind::neutral);
}

TEST_CASE("inertia: parts against their textbook tensors", "[inertia]") {
    const GiNaC::realsymbol m("m"), a("a"), b("b"), c("c"), r("r"), l("l");
    const auto diag_is = [](const matrix3& t, const ex& x, const ex& y, const ex& z) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                INFO(i << j << ": " << t[i][j]);
                CHECK(vanishes(t[i][j] - (i != j ? ex(0) : i == 0 ? x : i == 1 ? y : z)));
            }
    };
    SECTION("box about its centre: m(b^2+c^2)/12, ...") {
        diag_is(central_tensor(make_box(m, {a, b, c}, {0, 0, 0})), m * (b * b + c * c) / 12,
                m * (a * a + c * c) / 12, m * (a * a + b * b) / 12);
    }
    SECTION("box turned by phi = pi/2 about z: its edge a lies along body y") {
        part p = make_box(m, {a, b, c}, {0, 0, 0});
        p.rotation = vector3{GiNaC::Pi / 2, 0, 0};
        diag_is(central_tensor(p), m * (a * a + c * c) / 12, m * (b * b + c * c) / 12,
                m * (a * a + b * b) / 12);
    }
    SECTION("rod: m l^2/12 across, 0 along; about an end m l^2/3") {
        diag_is(central_tensor(make_axial(part_kind::rod, m, 0, l, {0, 0, 2})), m * l * l / 12,
                m * l * l / 12, 0);
        const body_inertia end = combine_parts(
            {make_axial(part_kind::rod, m, 0, l, {0, 0, 1}, {0, 0, l / 2})}, vector3{0, 0, 0}, {});
        diag_is(end.tensor, m * l * l / 3, m * l * l / 3, 0);
    }
    SECTION("cylinder: m r^2/2 along, m(3r^2 + l^2)/12 across; a disc m r^2/4") {
        diag_is(central_tensor(make_axial(part_kind::cylinder, m, r, l, {0, 0, 1})),
                m * (3 * r * r + l * l) / 12, m * (3 * r * r + l * l) / 12, m * r * r / 2);
        diag_is(central_tensor(make_axial(part_kind::cylinder, m, r, 0, {1, 0, 0})), m * r * r / 2,
                m * r * r / 4, m * r * r / 4);
        // r = 0 is a thin rod
        const matrix3 thin = central_tensor(make_axial(part_kind::cylinder, m, 0, l, {1, 2, 2}));
        const matrix3 rod = central_tensor(make_axial(part_kind::rod, m, 0, l, {1, 2, 2}));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                CHECK(vanishes(thin[i][j] - rod[i][j]));
    }
    SECTION("sphere: 2/5 m r^2 solid, 2/3 m r^2 hollow") {
        part p = make_axial(part_kind::sphere, m, r, 0, {0, 0, 1});
        diag_is(central_tensor(p), numeric(2, 5) * m * r * r, numeric(2, 5) * m * r * r,
                numeric(2, 5) * m * r * r);
        p.hollow = true;
        diag_is(central_tensor(p), numeric(2, 3) * m * r * r, numeric(2, 3) * m * r * r,
                numeric(2, 3) * m * r * r);
    }
    SECTION("an oblique rod is the rod along z rotated (5.44); a thin box along a rotated x is "
            "that rod") {
        // n = (1, 1, 0)/sqrt(2): I = m l^2/12 (1 - n n^T)
        const matrix3 t = central_tensor(make_axial(part_kind::rod, m, 0, l, {1, 1, 0}));
        const ex k = m * l * l / 12;
        const matrix3 expected = from_rows({{k / 2, -k / 2, 0}, {-k / 2, k / 2, 0}, {0, 0, k}});
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                CHECK(vanishes(t[i][j] - expected[i][j]));
        // A box of edges (l, 0, 0) turned by Euler angles has its edge along the first row of A.
        const vector3 angles{numeric(3, 10), numeric(7, 10), numeric(11, 10)};
        part box = make_box(m, {l, 0, 0}, {0, 0, 0});
        box.rotation = angles;
        const matrix3 a_matrix = euler_rotation(angles[0], angles[1], angles[2]);
        const matrix3 rod = central_tensor(make_axial(part_kind::rod, m, 0, l, a_matrix[0]));
        const GiNaC::exmap at{{m, 1.3}, {l, 0.9}};
        CHECK((numbers(central_tensor(box), at) - numbers(rod, at)).cwiseAbs().maxCoeff() < 1e-14);
    }
}

TEST_CASE("inertia: rotation leaves the trace and the principal moments unchanged", "[inertia]") {
    const GiNaC::realsymbol m("m"), a("a"), b("b"), c("c");
    const matrix3 own = central_tensor(make_box(m, {a, b, c}, {0, 0, 0}));
    SECTION("exactly, at angles with exact sines and cosines") {
        part p = make_box(m, {a, b, c}, {0, 0, 0});
        p.rotation = vector3{GiNaC::Pi / 6, GiNaC::Pi / 4, GiNaC::Pi / 3};
        const matrix3 t = central_tensor(p);
        CHECK(vanishes(t[0][0] + t[1][1] + t[2][2] - (own[0][0] + own[1][1] + own[2][2])));
        // the characteristic polynomial det(I - x 1) is invariant: all its coefficients (with
        // sqrt(6) written as sqrt(2) sqrt(3) so that equal numbers cancel)
        const GiNaC::realsymbol x("x");
        const auto charpoly = [&](const matrix3& m3) {
            GiNaC::matrix mm(3, 3);
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    mm(i, j) = m3[i][j] - (i == j ? ex(x) : ex(0));
            return mm.determinant().expand();
        };
        CHECK(vanishes(canonical_radicals(charpoly(t) - charpoly(own))));
        // with numbers for the sizes the moments come out exact again (the axes, rows of the
        // rotation with nested radicals, numeric)
        const GiNaC::exmap at{{m, 12}, {a, 1}, {b, 2}, {c, 3}};
        matrix3 tn;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                tn[i][j] = t[i][j].subs(at);
        const principal_axes pa = find_principal_axes(tn, {});
        CHECK(pa.exact_moments);
        for (int k = 0; k < 3; ++k)
            CHECK(vanishes(pa.moments[k] - std::array<int, 3>{5, 10, 13}[k]));
        Eigen::Matrix3d axes;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                axes(i, j) = pa.axis_values[i][j];
        const Eigen::Matrix3d d = axes * numbers(tn) * axes.transpose();
        CHECK((d - Eigen::Vector3d(5, 10, 13).asDiagonal().toDenseMatrix()).cwiseAbs().maxCoeff() <
              1e-13);
    }
    SECTION("numerically, at arbitrary angles (the principal axes are then numeric)") {
        const GiNaC::exmap at{{m, 2.5}, {a, 0.3}, {b, 1.7}, {c, 0.9}};
        const Eigen::Vector3d expected =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(numbers(own, at)).eigenvalues();
        for (const auto& angles :
             {std::array<double, 3>{0.3, 0.7, 1.1}, {2.0, 2.9, -0.4}, {5.5, 0.01, 3.0}}) {
            part p = make_box(m, {a, b, c}, {0, 0, 0});
            p.rotation = vector3{angles[0], angles[1], angles[2]};
            const matrix3 t = central_tensor(p);
            const Eigen::Matrix3d tn = numbers(t, at);
            CHECK(tn.trace() == Approx(expected.sum()).epsilon(1e-14));
            const principal_axes pa = find_principal_axes(t, at);
            CHECK(!pa.exact_moments);
            Eigen::Matrix3d axes;
            for (int i = 0; i < 3; ++i) {
                CHECK(pa.moment_values[i] == Approx(expected[i]).epsilon(1e-13));
                for (int j = 0; j < 3; ++j)
                    axes(i, j) = pa.axis_values[i][j];
            }
            CHECK(is_proper_rotation<double>(axes, 1e-13));
            const Eigen::Matrix3d d = axes * tn * axes.transpose();
            CHECK((d - Eigen::Matrix3d(expected.asDiagonal())).cwiseAbs().maxCoeff() < 1e-13);
            // the box's own axes are the rows of its Euler matrix: the runtime's (5.25)
            const Eigen::Matrix3d a_rt = euler_matrix(angles[0], angles[1], angles[2]);
            const Eigen::Matrix3d own_n = numbers(own, at);
            CHECK((a_rt.transpose() * own_n * a_rt - tn).cwiseAbs().maxCoeff() < 1e-14);
        }
    }
}

TEST_CASE("inertia: a shifted, rotated box against direct integration over a grid", "[inertia]") {
    // I_ij = ∫ ρ (r² δ_ij − x_i x_j) d³x (5.39) about a pivot, by the midpoint rule on an
    // N x N x N grid over the box. The grid's first moments vanish and its second moments are
    // a²(1 − 1/N²)/12 (and likewise b, c) instead of a²/12, so the rule's error is the tensor of
    // E = m diag(a², b², c²)/(12 N²) taken with a minus sign: every entry is within
    // m (a² + b² + c²)/(6 N²) of the exact one, and adding the correction leaves only rounding.
    const double m = 2.0, a = 0.3, b = 0.5, c = 0.8;
    const std::array<double, 3> angles{0.4, 1.0, -0.7}, at{0.5, -0.2, 0.9}, pivot{0.1, 0.2, -0.3};
    part p = make_box(numeric(m), {numeric(a), numeric(b), numeric(c)}, {at[0], at[1], at[2]});
    p.rotation = vector3{angles[0], angles[1], angles[2]};
    const matrix3 exact = combine_parts({p}, vector3{pivot[0], pivot[1], pivot[2]}, {}).tensor;
    const Eigen::Matrix3d expected = numbers(exact);

    const int n = 40;
    const Eigen::Matrix3d a_rt = euler_matrix(angles[0], angles[1], angles[2]); // x_box = A x_body
    const Eigen::Vector3d centre(at[0], at[1], at[2]), o(pivot[0], pivot[1], pivot[2]);
    Eigen::Matrix3d grid = Eigen::Matrix3d::Zero();
    const double dm = m / (double(n) * n * n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const Eigen::Vector3d xi((i + 0.5) / n - 0.5, (j + 0.5) / n - 0.5,
                                         (k + 0.5) / n - 0.5);
                const Eigen::Vector3d box(xi[0] * a, xi[1] * b, xi[2] * c);
                const Eigen::Vector3d d = centre + a_rt.transpose() * box - o;
                grid += dm * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
            }
    const double bound = m * (a * a + b * b + c * c) / (6.0 * n * n);
    CHECK((grid - expected).cwiseAbs().maxCoeff() < bound);
    CHECK((grid - expected).cwiseAbs().maxCoeff() > bound / 100); // the bound is not vacuous
    const Eigen::Matrix3d e =
        m / (12.0 * n * n) * Eigen::Vector3d(a * a, b * b, c * c).asDiagonal();
    const Eigen::Matrix3d correction =
        a_rt.transpose() * (e.trace() * Eigen::Matrix3d::Identity() - e) * a_rt;
    CHECK((grid + correction - expected).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE(
    "inertia: the centre of mass is the default pivot, and Steiner's theorem links the pivots",
    "[inertia]") {
    const GiNaC::realsymbol m1("m1"), m2("m2"), x1("x1"), x2("x2"), r("r");
    const GiNaC::exmap defaults{{m1, 1.0}, {m2, 3.0}, {x1, 0.5}, {x2, -0.2}, {r, 0.1}};
    part sphere = make_axial(part_kind::sphere, m2, r, 0, {0, 0, 1}, {x2, 0, 0});
    const std::vector<part> parts{make_point(m1, {x1, 0, 0}), sphere};
    const body_inertia about_com = combine_parts(parts, std::nullopt, defaults);
    const ex com_x = (m1 * x1 + m2 * x2) / (m1 + m2);
    CHECK(vanishes(about_com.centre_of_mass[0] - com_x));
    CHECK(about_com.centre_of_mass[1].is_zero());
    CHECK(!about_com.pivot_given);
    // I_yy about the centre of mass: the reduced mass times the distance squared, plus the sphere
    CHECK(vanishes(about_com.tensor[1][1] -
                   (m1 * m2 / (m1 + m2) * GiNaC::pow(x1 - x2, 2) + numeric(2, 5) * m2 * r * r)));
    // about the origin = about the centre of mass + M (d² 1 − d dᵀ), d the centre of mass
    const body_inertia about_origin = combine_parts(parts, vector3{0, 0, 0}, defaults);
    const matrix3 shift = point_mass_tensor(m1 + m2, about_com.centre_of_mass);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(vanishes(about_origin.tensor[i][j] - about_com.tensor[i][j] - shift[i][j]));
    // a single part's mass divides exactly: no fraction is left
    const body_inertia one =
        combine_parts({make_box(m1, {x1, x1, r}, {x2, r, 0})}, std::nullopt, defaults);
    CHECK(vanishes(one.centre_of_mass[0] - x2));
    CHECK(vanishes(one.tensor[0][0] - m1 * (x1 * x1 + r * r) / 12));
}

TEST_CASE("inertia: principal axes: exact from a quadratic factor, numeric without closed form",
          "[inertia]") {
    SECTION("[[3, 1, 0], [1, 3, 0], [0, 0, 1]]: three simple moments 1, 2, 4 with exact axes") {
        const matrix3 t = from_rows({{3, 1, 0}, {1, 3, 0}, {0, 0, 1}});
        const principal_axes p = find_principal_axes(t, {});
        REQUIRE(p.exact_axes);
        for (int k = 0; k < 3; ++k)
            CHECK(vanishes(p.moments[k] - std::array<int, 3>{1, 2, 4}[k]));
        const ex h = GiNaC::sqrt(ex(2)) / 2;
        const matrix3 expected =
            from_rows({{0, 0, 1}, {h, -h, 0}, {h, h, 0}}); // largest component > 0, det +1
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                CHECK(vanishes(p.axes[i][j] - expected[i][j]));
        const matrix3 d = transform_tensor(p.axes, t);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                CHECK(vanishes(d[i][j] - (i == j ? p.moments[i] : ex(0))));
    }
    SECTION(
        "[[2, 1, 0], [1, 3, 0], [0, 0, 5]]: moments (5 -+ sqrt 5)/2 and 5 exact, axes numeric") {
        // the unit axes would need a root under a root, sqrt(5/2 - sqrt(5)/2)
        const matrix3 t = from_rows({{2, 1, 0}, {1, 3, 0}, {0, 0, 5}});
        const principal_axes p = find_principal_axes(t, {});
        REQUIRE(p.exact_moments);
        CHECK(!p.exact_axes);
        const ex r5 = GiNaC::sqrt(ex(5));
        CHECK(vanishes(p.moments[0] - (5 - r5) / 2));
        CHECK(vanishes(p.moments[1] - (5 + r5) / 2));
        CHECK(vanishes(p.moments[2] - 5));
        Eigen::Matrix3d a;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                a(i, j) = p.axis_values[i][j];
        const Eigen::Matrix3d d = a * numbers(t) * a.transpose();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                CHECK(d(i, j) == Approx(i == j ? p.moment_values[i] : 0).margin(1e-14));
        CHECK(a.determinant() == Approx(1).epsilon(1e-14));
    }
    SECTION("an irreducible cubic: numeric, ascending, proper, diagonalising") {
        const matrix3 t = from_rows({{2, numeric(3, 10), numeric(1, 5)},
                                     {numeric(3, 10), numeric(5, 2), -numeric(1, 10)},
                                     {numeric(1, 5), -numeric(1, 10), numeric(3, 2)}});
        const principal_axes p = find_principal_axes(t, {});
        CHECK(!p.exact_moments);
        CHECK(p.moment_values[0] < p.moment_values[1]);
        CHECK(p.moment_values[1] < p.moment_values[2]);
        Eigen::Matrix3d a;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                a(i, j) = p.axis_values[i][j];
        CHECK(is_proper_rotation<double>(a, 1e-14));
        const Eigen::Matrix3d d = a * numbers(t) * a.transpose();
        for (int i = 0; i < 3; ++i)
            CHECK(d(i, i) == Approx(p.moment_values[i]).epsilon(1e-14));
        CHECK(std::abs(d(0, 1)) + std::abs(d(0, 2)) + std::abs(d(1, 2)) < 1e-14);
    }
    SECTION("a diagonal tensor keeps the body axes and their order") {
        const GiNaC::realsymbol i1("I1"), i3("I3");
        const principal_axes p = find_principal_axes(
            from_rows({{i1, 0, 0}, {0, i1, 0}, {0, 0, i3}}), {{i1, 1.0}, {i3, 0.5}});
        CHECK(p.exact_axes);
        CHECK(vanishes(p.moments[0] - i1));
        CHECK(vanishes(p.moments[2] - i3));
        CHECK(vanishes(p.axes[2][2] - 1));
    }
}

TEST_CASE("inertia: classification of section 5.5", "[inertia]") {
    CHECK(classify({1, 1, 1}) == top_class::spherical);
    CHECK(classify({2, 2, 1}) == top_class::symmetric);
    CHECK(classify({1, 3, 3}) == top_class::symmetric);
    CHECK(classify({1, 2, 3}) == top_class::asymmetric);
    CHECK(classify({0, 2, 2}) == top_class::rotor);
    CHECK(classify({1, 1 + 1e-14, 3}) == top_class::symmetric); // equal to rounding
    CHECK(classify({1, 1 + 1e-9, 3}) == top_class::asymmetric);
}

TEST_CASE("inertia: stability report: (5.94) and (5.100) for any ordering of the moments",
          "[inertia][stability]") {
    // Spin about principal axis i: s_i = (I_i − I_j)(I_i − I_k)/(I_j I_k); the chapter, with
    // I1 > I2 > I3, has Omega1² = (I1−I3)(I1−I2)/(I2 I3), Omega3² = (I1−I3)(I2−I3)/(I1 I2), and
    // growth Omega2² = (I1−I2)(I2−I3)/(I1 I3).
    const auto report = [](double x, double y, double z) {
        return analyse_inertia(
                   from_rows({{numeric(x), 0, 0}, {0, numeric(y), 0}, {0, 0, numeric(z)}}), {})
            .stability;
    };
    const double big = 3, mid = 2, small = 1;
    const double omega_big = std::sqrt((big - small) * (big - mid) / (mid * small));
    const double omega_small = std::sqrt((big - small) * (mid - small) / (big * mid));
    const double growth_mid = std::sqrt((big - mid) * (mid - small) / (big * small));
    for (const auto& order : {std::array<double, 3>{3, 2, 1}, {1, 2, 3}, {2, 3, 1}, {1, 3, 2}}) {
        INFO(order[0] << " " << order[1] << " " << order[2]);
        const auto s = report(order[0], order[1], order[2]);
        for (int i = 0; i < 3; ++i) {
            CHECK(s[i].axis == i + 1);
            if (order[i] == mid) {
                CHECK(s[i].kind == stability_kind::unstable);
                CHECK(!s[i].stable);
                CHECK(s[i].rate_value == Approx(growth_mid).epsilon(1e-15));
            } else {
                CHECK(s[i].kind == stability_kind::stable);
                CHECK(s[i].rate_value ==
                      Approx(order[i] == big ? omega_big : omega_small).epsilon(1e-15));
            }
            CHECK(value(s[i].rate) == Approx(s[i].rate_value).epsilon(1e-15)); // exact form agrees
        }
    }
    SECTION("degenerate moments") {
        const auto sym =
            report(2, 2, 1); // symmetric: stable about the symmetry axis at |I1 − I3|/I1
        CHECK(sym[0].kind == stability_kind::neutral);
        CHECK(sym[1].kind == stability_kind::neutral);
        CHECK(sym[2].kind == stability_kind::stable);
        CHECK(vanishes(sym[2].rate - numeric(1, 2)));
        for (const auto& s : report(1, 1, 1)) { // spherical: omega is constant
            CHECK(s.kind == stability_kind::stable);
            CHECK(s.rate_value == 0);
        }
        const auto rotor = report(0, 1, 1);
        CHECK(rotor[0].kind == stability_kind::none);
        CHECK(rotor[1].kind == stability_kind::stable);
    }
    SECTION("symbolic moments give the formulas themselves") {
        const GiNaC::realsymbol a("a"), c("c");
        const auto s =
            analyse_inertia(from_rows({{a, 0, 0}, {0, a, 0}, {0, 0, c}}), {{a, 2.0}, {c, 1.0}})
                .stability;
        CHECK(vanishes(s[2].rate - (a - c) / a)); // |I1 − I3|/I1, signed positive at the defaults
    }
}

TEST_CASE("inertia: a model's body: all kinds of parts read from YAML with expressions",
          "[inertia][spec]") {
    const scratch_file file(
        "inertia_all_parts.yaml",
        "name: parts\n"
        "parameters: {m: 2, l: 0.5, r: 0.1}\n"
        "body:\n"
        "  pivot: [0, 0, -l]\n"
        "  parts:\n"
        "    - point: {mass: m/4, at: [l, 0, 0]}\n"
        "    - box: {mass: m, size: [l, 2*l, 3*l], at: [0, 0, 0], rotation: [pi/2, 0, 0]}\n"
        "    - rod: {mass: 1, length: l, at: [0, 0, l/2], axis: [0, 0, 1]}\n"
        "    - cylinder: {mass: 0.5, radius: r, length: 0.2, at: [0, 0, l], axis: [0, 0, 3]}\n"
        "    - sphere: {mass: 0.3, radius: r, at: [0, 0, -l/2], hollow: true}\n"
        "gravity: {g: 9.81}\n");
    const model_spec spec = load_model(file.path);
    REQUIRE(spec.body);
    REQUIRE(spec.parts.size() == 5);
    const double m = 2, l = 0.5, r = 0.1;
    // by hand: each part's central tensor plus its mass times the distance to the pivot (0,0,-l)
    const double mp = m / 4;
    double ixx = mp * l * l, iyy = mp * 2 * l * l,
           izz = mp * l * l; // point at d = (l, 0, l) from the pivot
    ixx += m * (l * l + 9 * l * l) / 12 + m * l * l;
    iyy += m * (4 * l * l + 9 * l * l) / 12 + m * l * l; // box turned: a along y
    izz += m * (l * l + 4 * l * l) / 12;
    ixx += l * l / 12 + 1.0 * std::pow(1.5 * l, 2);
    iyy += l * l / 12 + std::pow(1.5 * l, 2); // rod
    ixx += 0.5 * (3 * r * r + 0.04) / 12 + 0.5 * 4 * l * l;
    iyy += 0.5 * (3 * r * r + 0.04) / 12 + 0.5 * 4 * l * l;
    izz += 0.5 * r * r / 2; // cylinder
    const double shell = 0.3 * 2 * r * r / 3;
    ixx += shell + 0.3 * l * l / 4;
    iyy += shell + 0.3 * l * l / 4;
    izz += shell; // sphere
    const Eigen::Matrix3d t = numbers(spec.inertia, spec.parameter_defaults());
    CHECK(t(0, 0) == Approx(ixx).epsilon(1e-14));
    CHECK(t(1, 1) == Approx(iyy).epsilon(1e-14));
    CHECK(t(2, 2) == Approx(izz).epsilon(1e-14));
    CHECK(t(0, 2) == Approx(-mp * l * l).epsilon(1e-14)); // only the point is off the z axis
    CHECK(t(0, 1) == 0);
    CHECK(t(1, 2) == 0);
    // gravity: the total mass at the centre of mass, relative to the pivot
    const double mass = mp + m + 1 + 0.5 + 0.3;
    CHECK(value(spec.gravity->mass, spec.parameter_defaults()) == Approx(mass));
    const double com_z = (mp * 0 + m * 0 + 1 * l / 2 + 0.5 * l + 0.3 * (-l / 2)) / mass + l;
    CHECK(value(spec.gravity->com[2], spec.parameter_defaults()) == Approx(com_z).epsilon(1e-14));
    CHECK(value(spec.gravity->com[0], spec.parameter_defaults()) ==
          Approx(mp * l / mass).epsilon(1e-14));
}
