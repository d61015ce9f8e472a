// The twelve Euler-angle sequences of runtime/euler_sequence.hpp against independent truth: the
// matrix against the product of rotation.hpp's rot_x/rot_y/rot_z (5.8, 5.9) and, for z-x-z,
// euler_matrix (5.25); angles -> matrix -> angles round trips, on the singular set too; the
// quaternion against the matrix; and J (omega = J q_dot) against [omega]x = -A_dot A^T by finite
// differences of the matrix.
#include <catch2/catch.hpp>

#include "euler_sequence.hpp"

#include <cmath>
#include <random>

using namespace rotgen;

namespace {

const std::array<std::array<int, 3>, 12> all_sequences{{{2, 0, 2},
                                                        {2, 1, 2},
                                                        {0, 1, 0},
                                                        {0, 2, 0},
                                                        {1, 0, 1},
                                                        {1, 2, 1},
                                                        {2, 1, 0},
                                                        {2, 0, 1},
                                                        {1, 0, 2},
                                                        {1, 2, 0},
                                                        {0, 1, 2},
                                                        {0, 2, 1}}};

mat3<double> axis_rotation(int n, double a) {
    return n == 0 ? rot_x(a) : n == 1 ? rot_y(a) : rot_z(a);
}

// A random attitude's angles, the middle one in the sequence's range, away from the singular set
// by at least `margin`.
std::array<double, 3> random_angles(const euler_sequence& s, std::mt19937& rng, double margin) {
    const double pi = 3.14159265358979323846;
    std::uniform_real_distribution<double> outer(-pi, pi);
    std::uniform_real_distribution<double> middle(s.proper() ? margin : -pi / 2 + margin,
                                                  s.proper() ? pi - margin : pi / 2 - margin);
    return {outer(rng), middle(rng), outer(rng)};
}

} // namespace

TEST_CASE("sequence_matrix is A_c A_b A_a of the elementary rotations for all twelve sequences",
          "[rotation]") {
    std::mt19937 rng(7);
    double worst = 0;
    for (const auto& axes : all_sequences) {
        const euler_sequence s{axes};
        for (int k = 0; k < 20; ++k) {
            const auto q = random_angles(s, rng, 0.1);
            const mat3<double> want = axis_rotation(axes[2], q[2]) * axis_rotation(axes[1], q[1]) *
                                      axis_rotation(axes[0], q[0]);
            worst = std::max(worst, (sequence_matrix(s, q) - want).cwiseAbs().maxCoeff());
        }
    }
    CHECK(worst <= 1e-15); // observed 0 (the same products)
    // z-x-z is the chapter's (5.25)
    const std::array<double, 3> q{0.3, 1.1, -2.0};
    CHECK((sequence_matrix(euler_sequence{}, q) - euler_matrix(q[0], q[1], q[2]))
              .cwiseAbs()
              .maxCoeff() <= 1e-15);
}

TEST_CASE("angles of every sequence round-trip through the matrix and the quaternion",
          "[rotation]") {
    std::mt19937 rng(11);
    double angle_err = 0, quat_err = 0;
    for (const auto& axes : all_sequences) {
        const euler_sequence s{axes};
        for (int k = 0; k < 50; ++k) {
            const auto q = random_angles(s, rng, 1e-3);
            const mat3<double> A = sequence_matrix(s, q);
            const auto back = sequence_angles_from_matrix(s, A);
            angle_err = std::max(angle_err, (sequence_matrix(s, back) - A).cwiseAbs().maxCoeff());
            const auto via_q = sequence_angles_from_quaternion(s, sequence_quaternion(s, q));
            quat_err = std::max(quat_err, (sequence_matrix(s, via_q) - A).cwiseAbs().maxCoeff());
            // the quaternion's matrix is A (R(q) = A^T)
            quat_err = std::max(
                quat_err,
                (matrix_from_quaternion(sequence_quaternion(s, q)) - A).cwiseAbs().maxCoeff());
        }
    }
    CHECK(angle_err <= 1e-14); // observed 1.1e-15
    CHECK(quat_err <= 3e-13);  // observed 2.7e-14
}

TEST_CASE("angles on the singular set of every sequence reproduce the matrix", "[rotation]") {
    const double pi = 3.14159265358979323846;
    double worst = 0;
    for (const auto& axes : all_sequences) {
        const euler_sequence s{axes};
        for (double beta :
             s.proper() ? std::array<double, 2>{0, pi} : std::array<double, 2>{-pi / 2, pi / 2}) {
            const std::array<double, 3> q{0.7, beta, -0.4};
            const mat3<double> A = sequence_matrix(s, q);
            const auto back = sequence_angles_from_matrix(s, A);
            CHECK(back[2] == 0); // the whole turn goes into the first angle
            worst = std::max(worst, (sequence_matrix(s, back) - A).cwiseAbs().maxCoeff());
        }
    }
    CHECK(worst <= 1e-15); // observed 1.1e-16
}

TEST_CASE("sequence J gives omega of -A_dot A^T for every sequence", "[rotation]") {
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> rate(-2, 2);
    double worst = 0;
    for (const auto& axes : all_sequences) {
        const euler_sequence s{axes};
        for (int k = 0; k < 10; ++k) {
            const auto q = random_angles(s, rng, 0.2);
            const Eigen::Vector3d qd(rate(rng), rate(rng), rate(rng));
            const double h = 1e-6;
            std::array<double, 3> qp = q, qm = q;
            for (int i = 0; i < 3; ++i)
                qp[i] += h * qd[i], qm[i] -= h * qd[i];
            const mat3<double> A = sequence_matrix(s, q);
            const mat3<double> W = -(sequence_matrix(s, qp) - sequence_matrix(s, qm)) / (2 * h) *
                                   A.transpose(); // [omega]x in body axes
            const Eigen::Vector3d w(W(2, 1), W(0, 2), W(1, 0));
            worst = std::max(worst, (sequence_omega_jacobian(s, q) * qd - w).cwiseAbs().maxCoeff());
        }
    }
    CHECK(worst <= 3e-9); // observed 3.2e-10 (the central difference's h^2)
}
