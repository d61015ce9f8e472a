// Rotation utilities: elementary rotations (5.8, 5.9), the Euler matrix (5.25), the chapter's
// worked examples 5.1–5.3, Euler angles ↔ matrix ↔ quaternion round trips including the
// singular θ = 0 and θ = π, and the orientation-error angle.
#include <catch2/catch.hpp>

#include "rotation.hpp"

#include <cmath>
#include <limits>

using namespace rotgen;

namespace {

template <class T> T max_abs_diff(const mat3<T>& a, const mat3<T>& b) {
    return (a - b).cwiseAbs().maxCoeff();
}

// Angular distance on the circle, in [0, π].
template <class T> T angle_diff(T a, T b) {
    using std::abs;
    using std::atan2;
    using std::cos;
    using std::sin;
    return abs(atan2(sin(a - b), cos(a - b)));
}

constexpr double pi = 3.14159265358979323846;

} // namespace

TEMPLATE_TEST_CASE("elementary rotations are proper orthogonal matrices", "[rotation]", float,
                   double, long double) {
    using T = TestType;
    const T tol = T(16) * std::numeric_limits<T>::epsilon();
    for (int i = -8; i <= 8; ++i) {
        const T a = T(i) * T(0.7);
        for (const mat3<T>& m : {rot_z(a), rot_x(a), rot_y(a)}) {
            CHECK(is_orthogonal(m, tol));
            CHECK(is_proper_rotation(m, tol));
            CHECK_FALSE(is_improper_rotation(m, tol));
            CHECK(max_abs_diff<T>(inverse(m) * m, mat3<T>::Identity()) <= tol);
        }
    }
    // (5.8): Az(a) = [[c, s, 0], [−s, c, 0], [0, 0, 1]] — the passive sign convention
    const mat3<T> az = rot_z(T(0.3));
    CHECK(az(0, 1) == Approx(std::sin(0.3)).epsilon(1e-6));
    CHECK(az(1, 0) == Approx(-std::sin(0.3)).epsilon(1e-6));
    const mat3<T> ax = rot_x(T(0.3));
    CHECK(ax(1, 2) == Approx(std::sin(0.3)).epsilon(1e-6));
    CHECK(ax(2, 1) == Approx(-std::sin(0.3)).epsilon(1e-6));

    mat3<T> reflection = mat3<T>::Identity();
    reflection(2, 2) = T(-1);
    CHECK(is_improper_rotation(reflection, tol));
    CHECK_FALSE(is_proper_rotation(reflection, tol));
    mat3<T> sheared = mat3<T>::Identity();
    sheared(0, 1) = T(1e-2);
    CHECK_FALSE(is_orthogonal(sheared, T(1e-3)));
}

TEST_CASE("Example 5.1 and 5.2: products of elementary rotations do not commute", "[rotation]") {
    const double d = pi / 180;
    const mat3<double> a = compose(rot_z(45 * d), rot_x(30 * d)); // 30° about x, then 45° about z
    mat3<double> expected;                                        // (5.13)
    const double r2 = std::sqrt(2.0), r3 = std::sqrt(3.0), r6 = std::sqrt(6.0);
    expected << r2 / 2, r6 / 4, r2 / 4, -r2 / 2, r6 / 4, r2 / 4, 0, -0.5, r3 / 2;
    CHECK(max_abs_diff(a, expected) < 1e-15);

    const mat3<double> b = compose(rot_x(30 * d), rot_z(45 * d)); // 45° about z, then 30° about x
    mat3<double> expected_b;                                      // Example 5.2, B' = Ax Az
    expected_b << r2 / 2, r2 / 2, 0, -r6 / 4, r6 / 4, 0.5, r2 / 4, -r2 / 4, r3 / 2;
    CHECK(max_abs_diff(b, expected_b) < 1e-15);
    CHECK(max_abs_diff(a, b) > 0.3);
}

TEST_CASE("Euler matrix (5.25) equals the product Az(psi) Ax(theta) Az(phi)", "[rotation]") {
    for (double phi : {0.0, 0.4, 2.0, 4.5})
        for (double theta : {0.0, 0.3, 1.5, 2.9, pi})
            for (double psi : {0.0, 1.1, 3.3, 6.0}) {
                const mat3<double> a = euler_matrix(phi, theta, psi);
                CHECK(max_abs_diff(a, mat3<double>(rot_z(psi) * rot_x(theta) * rot_z(phi))) <
                      1e-15);
                // third row (sinθ sinφ, −sinθ cosφ, cosθ)
                CHECK(a(2, 0) == Approx(std::sin(theta) * std::sin(phi)).margin(1e-15));
                CHECK(a(2, 1) == Approx(-std::sin(theta) * std::cos(phi)).margin(1e-15));
                CHECK(a(2, 2) == Approx(std::cos(theta)).margin(1e-15));
                CHECK(is_proper_rotation(a, 1e-14));
            }
}

TEST_CASE("Example 5.3: rotation by vartheta about y has theta = vartheta, phi = pi/2, psi = -pi/2",
          "[rotation]") {
    for (double vt : {0.2, 1.0, 2.5}) {
        const euler_angles<double> e = euler_from_matrix(rot_y(vt));
        CHECK(e.theta == Approx(vt).epsilon(1e-14));
        CHECK(e.phi == Approx(pi / 2).epsilon(1e-14));
        CHECK(e.psi == Approx(3 * pi / 2).epsilon(1e-14)); // −π/2 wrapped into [0, 2π)
        CHECK(max_abs_diff(euler_matrix(pi / 2, vt, -pi / 2), rot_y(vt)) < 1e-15);
    }
}

TEMPLATE_TEST_CASE("Euler angles -> matrix -> Euler angles round trip, including theta = 0 and pi",
                   "[rotation]", float, double, long double) {
    using T = TestType;
    const T eps = std::numeric_limits<T>::epsilon();
    const T tpi = T(EIGEN_PI);
    for (T phi : {T(0), T(0.3), T(2.2), T(5.9)})
        for (T psi : {T(0), T(0.8), T(3.5), T(6.1)}) {
            // regular points: the angles come back
            for (T theta : {T(1e-3), T(0.5), T(1.5), T(2.7), tpi - T(1e-3)}) {
                const euler_angles<T> e = euler_from_matrix(euler_matrix(phi, theta, psi));
                CHECK(std::abs(e.theta - theta) <= T(16) * eps);
                // φ and ψ are determined to rounding/sinθ individually, their sum/difference to
                // rounding
                CHECK(angle_diff(e.phi, phi) <= T(64) * eps / std::sin(theta));
                CHECK(angle_diff(e.psi, psi) <= T(64) * eps / std::sin(theta));
                CHECK(e.phi >= T(0));
                CHECK(e.phi < T(2) * tpi);
                CHECK(e.psi >= T(0));
                CHECK(e.psi < T(2) * tpi);
                CHECK(max_abs_diff(euler_matrix(e), euler_matrix(phi, theta, psi)) <= T(16) * eps);
            }
            // θ = 0: A = Az(φ + ψ); the defined answer is ψ = 0, φ = φ + ψ (mod 2π)
            {
                const euler_angles<T> e = euler_from_matrix(euler_matrix(phi, T(0), psi));
                CHECK(e.theta == T(0));
                CHECK(e.psi == T(0));
                CHECK(angle_diff(e.phi, phi + psi) <= T(8) * eps);
            }
            // θ = π: A = Az(ψ − φ) Ax(π) = Ax(π) Az(φ − ψ); ψ = 0, φ = φ − ψ (mod 2π)
            {
                const mat3<T> a = euler_matrix(phi, tpi, psi);
                const euler_angles<T> e = euler_from_matrix(a);
                CHECK(e.theta == Approx(tpi).epsilon(T(4) * eps));
                CHECK(e.psi == T(0));
                CHECK(angle_diff(e.phi, phi - psi) <= T(8) * eps);
                CHECK(max_abs_diff(euler_matrix(e), a) <= T(16) * eps);
            }
        }
    // close to the singularity the matrix is still reproduced to rounding
    for (T theta : {T(1e-9), tpi - T(1e-9)}) {
        const mat3<T> a = euler_matrix(T(1.0), theta, T(2.0));
        CHECK(max_abs_diff(euler_matrix(euler_from_matrix(a)), a) <= T(16) * eps);
    }
}

TEMPLATE_TEST_CASE("quaternion <-> matrix round trip and agreement with Euler angles", "[rotation]",
                   float, double, long double) {
    using T = TestType;
    const T eps = std::numeric_limits<T>::epsilon();
    for (T phi : {T(0), T(0.7), T(3.0), T(5.5)})
        for (T theta : {T(0), T(0.4), T(1.6), T(3.0), T(EIGEN_PI)})
            for (T psi : {T(0), T(1.2), T(3.14), T(4.9)}) {
                const mat3<T> a = euler_matrix(phi, theta, psi);
                const Eigen::Quaternion<T> q = quaternion_from_matrix(a);
                CHECK(q.w() >= T(0));
                CHECK(std::abs(q.norm() - T(1)) <= T(4) * eps);
                CHECK(max_abs_diff(matrix_from_quaternion(q), a) <= T(16) * eps);
                // independent route: q_z(φ) ⊗ q_x(θ) ⊗ q_z(ψ) is the same rotation
                const Eigen::Quaternion<T> qe = quaternion_from_euler(phi, theta, psi);
                CHECK(std::abs(std::abs(qe.dot(q)) - T(1)) <= T(16) * eps);
                // convention: A is the transpose of Eigen's active rotation matrix of q
                CHECK(max_abs_diff(mat3<T>(q.toRotationMatrix().transpose()), a) <= T(16) * eps);
                CHECK(max_abs_diff(euler_matrix(euler_from_quaternion(q)), a) <= T(32) * eps);
            }
    // a rotation by α about n: q = (cos α/2, n sin α/2) carries body axes to space axes, so the
    // passive matrix maps the space vector n to itself and rotates the others by −α
    const T alpha = T(0.9);
    const Eigen::Quaternion<T> qz(std::cos(alpha / 2), T(0), T(0), std::sin(alpha / 2));
    CHECK(max_abs_diff(matrix_from_quaternion(qz), rot_z(alpha)) <= T(8) * eps);
}

TEMPLATE_TEST_CASE("rotation angle and orientation error", "[rotation]", float, double,
                   long double) {
    using T = TestType;
    const T eps = std::numeric_limits<T>::epsilon();
    for (T a : {T(0), T(1e-7), T(0.5), T(2.0), T(EIGEN_PI) - T(1e-4)}) {
        CHECK(rotation_angle<T>(rot_z(a)) == Approx(a).epsilon(T(16) * eps).margin(T(4) * eps));
        CHECK(rotation_angle<T>(rot_x(-a)) == Approx(a).epsilon(T(16) * eps).margin(T(4) * eps));
    }
    const mat3<T> a = euler_matrix(T(0.3), T(1.1), T(2.0));
    CHECK(orientation_error<T>(a, a) <= T(4) * eps);
    // a small extra rotation is measured to rounding (absolute error ~eps), not to sqrt(eps) as
    // acos of the trace would: δ = 1e4·eps is found within 1 % (100·eps)
    const T delta = T(1e4) * eps;
    const mat3<T> b = compose<T>(rot_y(delta), a);
    CHECK(orientation_error<T>(b, a) == Approx(delta).epsilon(T(1e-2)));
}
