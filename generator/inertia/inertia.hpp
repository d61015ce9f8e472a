// rotgen — inertia from geometry, principal axes, and the stability of steady rotation (§5.4–5.7).
//
// Everything here is exact (GiNaC) where it can be, and numeric (at the parameters' defaults)
// where it cannot. No YAML: spec/body_parts.cpp reads `body: {pivot, parts}` into `part`s and calls
// `combine_parts`.
//
// Conventions (the chapter's; runtime/rotation.hpp has the same ones in floating point):
//   * Rotation matrices are PASSIVE. Euler angles are z-x-z, A = Az(ψ) Ax(θ) Az(φ) (5.25), with
//     Az, Ax, Ay of (5.8, 5.9). A frame B obtained from a frame S by the Euler rotation (φ, θ, ψ)
//     has coordinates x_B = A x_S.
//   * Inertia tensors (5.39): I_ij = Σ m (r² δ_ij − x_i x_j), products of inertia with the minus
//     sign. Under x' = A x a tensor transforms as I' = A I Aᵀ (5.44), so I = Aᵀ I' A (5.51).
//   * A part's `rotation: [φ, θ, ψ]` gives the part's own axes (the box's edges a, b, c along its
//     x, y, z) relative to the body axes exactly as the Euler angles give the body axes relative to
//     space: x_part = A x_body. The part's tensor, diagonal in its own axes, is therefore
//     I_body = Aᵀ I_part A (5.44 read backwards). Example: rotation [pi/2, 0, 0] turns the box by
//     +90° about z, so its edge a lies along the body y axis and I_yy = m (b² + c²)/12.
//   * Principal axes are returned as the ROWS of a proper rotation matrix A (det A = +1), so that
//     A I Aᵀ = diag(I1, I2, I3) (5.69): row k is the k-th principal axis in body axes.
#pragma once

#include "support/error.hpp"

#include <ginac/ginac.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace rotgen {

using matrix3 = std::array<std::array<GiNaC::ex, 3>, 3>;
using vector3 = std::array<GiNaC::ex, 3>;

// ---- exact rotation matrices (5.8, 5.9, 5.25) and tensor algebra --------------------------------

matrix3 rotation_x(const GiNaC::ex& a); // Ax(a) (5.9)
matrix3 rotation_y(const GiNaC::ex& a); // Ay(a) (5.9)
matrix3 rotation_z(const GiNaC::ex& a); // Az(a) (5.8)
matrix3 euler_rotation(const GiNaC::ex& phi, const GiNaC::ex& theta,
                       const GiNaC::ex& psi);         // (5.25)
matrix3 multiply(const matrix3& a, const matrix3& b); // a b, entries expanded
matrix3 transpose(const matrix3& a);
matrix3 identity3();
// I' = A I Aᵀ (5.44): the tensor I in the axes x' = A x.
matrix3 transform_tensor(const matrix3& a, const matrix3& tensor);

// ---- parts and their tensors --------------------------------------------------------------------

enum class part_kind { point, box, rod, cylinder, sphere };
const char* part_kind_name(part_kind k);
const std::vector<std::string>& part_kind_names(); // "point", "box", "rod", "cylinder", "sphere"

struct part {
    part_kind kind = part_kind::point;
    GiNaC::ex mass;
    vector3 at;                      // its centre (of mass) in body axes
    vector3 size;                    // box: edges a, b, c along its own x, y, z
    std::optional<vector3> rotation; // box: z-x-z Euler angles of its own axes (see above)
    GiNaC::ex length = 0;            // rod, cylinder
    GiNaC::ex radius = 0;            // cylinder, sphere
    vector3 axis;                    // rod, cylinder: direction (any length but 0) in body axes
    bool hollow = false;             // sphere: a thin shell
    source_location where;           // for messages
};

// The tensor of a part about its own centre, in body axes:
//   point     0
//   box       Aᵀ diag(m(b²+c²), m(a²+c²), m(a²+b²))/12 A         (A from `rotation`, else 1)
//   rod       m l²/12 (1 − n nᵀ)                                  (thin; n = axis/|axis|)
//   cylinder  m(3r² + l²)/12 (1 − n nᵀ) + m r²/2 n nᵀ              (solid)
//   sphere    2/5 m r² 1 (solid), 2/3 m r² 1 (hollow)
// n nᵀ is written a aᵀ/(aᵀa), so an axis needs no square root.
matrix3 central_tensor(const part& p);

// The tensor of a point mass m at d (5.39): m (d² 1 − d dᵀ). Added to a part's central tensor
// it is the parallel-axis (Steiner) shift to a point at −d from the centre.
matrix3 point_mass_tensor(const GiNaC::ex& m, const vector3& d);

struct body_inertia {
    GiNaC::ex mass;         // Σ m_k
    vector3 centre_of_mass; // Σ m_k r_k / Σ m_k, body axes
    vector3 pivot;          // the point the tensor is taken about (default: the centre of mass)
    bool pivot_given = false;
    matrix3 tensor; // about the pivot, body axes
};

// Σ_k [ I_C,k + m_k (d_k² 1 − d_k d_kᵀ) ],  d_k = r_k − pivot  (parallel-axis theorem).
// Without a pivot, about the centre of mass c = S/M (S = Σ m_k r_k, M = Σ m_k):
//   I_c = I_O − M (c² 1 − c cᵀ) = I_O − (S² 1 − S Sᵀ)/M,
// I_O the tensor about the body origin, the division by M done exactly where it divides.
// `defaults` (parameter -> value) fix signs so that fractions print the same way in every run.
body_inertia combine_parts(const std::vector<part>& parts, const std::optional<vector3>& pivot,
                           const GiNaC::exmap& defaults);

// ---- principal axes (§5.5) ----------------------------------------------------------------------

enum class top_class { spherical, symmetric, asymmetric, rotor };
const char* top_class_name(top_class c); // "spherical", "symmetric", "asymmetric", "rotor"

struct principal_axes {
    bool exact_moments = false;            // the moments in closed form
    bool exact_axes = false;               // the axes in closed form too
    std::array<GiNaC::ex, 3> moments;      // I1, I2, I3
    matrix3 axes;                          // rows: unit principal axes in body axes; proper (5.69)
    std::array<double, 3> moment_values{}; // at the parameters' defaults
    std::array<std::array<double, 3>, 3> axis_values{};
};

// The eigenvalues and eigenvectors of a symmetric tensor, det(I − λ1) = 0 (5.60–5.62).
//   * diagonal tensor: the moments in body-axis order, A = 1;
//   * otherwise the moments ascending (by their values at the defaults). The moments are exact
//     when GiNaC's factor() splits the characteristic cubic into linear and quadratic factors
//     over the rationals in the parameters (Example 5.6: (6λ − ML²)(12λ − 11ML²)²; square roots
//     of integers in the tensor are first written as products of square roots of primes, so
//     that a box turned by π/6 still has a rational cubic). The axis of a simple moment λ is a
//     cross product of two rows of I − λ1, normalised; a double moment gets the plane
//     perpendicular to the simple axis (any orthonormal pair in it is principal, §5.5.1).
//   * numeric otherwise, and where the closed forms would be too large to read (a quadratic
//     factor with symbolic coefficients gives axes of thousands of nodes; see the limits in
//     principal_axes.cpp) or need a root under a root (the unit axes of [[2, 1], [1, 3]]): Eigen's
//     SelfAdjointEigenSolver on the tensor at the defaults. Moments may be exact while the axes
//     are numeric.
// Each axis has its largest component positive, except that the third may be flipped to make
// det A = +1.
principal_axes find_principal_axes(const matrix3& tensor, const GiNaC::exmap& defaults);
// The numeric branch alone, for a tensor of numbers (a run's inertia at its member's values): the
// moments ascending, the axes as above (the split methods' principal frame, run/split_run.cpp).
principal_axes numeric_principal_axes(const std::array<std::array<double, 3>, 3>& tensor);

// How many principal moments are exactly zero (0, 1, 2 or 3), decided exactly from the tensor's
// characteristic polynomial (c3 = det I = 0: one at least; c2 = Σ principal minors = 0 too: two;
// tr I = 0 too: all), the entries compared after sin² → 1 − cos² (rotor.cpp).
int exact_zero_moments(const matrix3& tensor);

// What makes numeric principal moments (in any order) unphysical, "" when nothing does (relative
// tolerance 1e-12): "a principal moment is negative (m1, m2, m3)", or "principal moments (...)
// break the triangle inequality (each at most the sum of the other two): a + b < c".
std::string negative_moment_problem(const std::array<double, 3>& moments);
std::string triangle_problem(const std::array<double, 3>& moments);
// For a tensor with exactly one zero moment (with the triangle inequality: a linear rotor,
// Example 5.4) the two equal moments across the line, I2 = I3 = tr I / 2, exactly; else nullopt.
std::optional<GiNaC::ex> exact_rotor_moment(const matrix3& tensor);
// For a rotor's tensor and a point c (body axes, relative to the point the tensor is taken
// about): its distance d = |c| along the line, exactly, when c lies on the line (I c = 0
// identically); nullopt when it does not.
std::optional<GiNaC::ex> rotor_arm(const matrix3& tensor, const vector3& c);

// Spherical I1 = I2 = I3; rotor: one moment 0, the other two equal; symmetric: two equal;
// asymmetric: all different. Equal means within `rel_tol` of the largest moment.
top_class classify(const std::array<double, 3>& moments, double rel_tol = 1e-12);

// ---- stability of steady, force-free rotation (§5.7, 5.90–5.100) --------------------------------

enum class stability_kind {
    stable,   // Ω² > 0: small deviations oscillate at Ω (5.94); or they stay constant (rate 0)
    unstable, // Ω² < 0: they grow like exp(|Ω| t) (5.100)
    neutral,  // Ω² = 0 with two equal moments: no oscillation, no exponential growth, but the
              // deviation turns the spin axis within the plane of the equal moments at a rate
              // proportional to the deviation (it grows linearly in the body frame)
    none      // the line of a rotor: rotation about it moves no mass (T = 0, Example 5.4)
};
const char* stability_kind_name(stability_kind k);

struct axis_stability {
    int axis = 0; // 1, 2, 3: the principal axis (row of principal_axes::axes)
    stability_kind kind = stability_kind::stable;
    bool stable = false;   // deviations stay small (kind stable)
    GiNaC::ex rate;        // |Ω| per unit spin: frequency if stable, growth rate if unstable
    double rate_value = 0; // at the defaults
};

// Spin ω about principal axis i, the others j, k. Linearising Euler's equations (5.87–5.89)
// about ω e_i gives for the small components δ_j'' = −s_i ω² δ_j with
//   s_i = (I_i − I_j)(I_i − I_k) / (I_j I_k),
// which is (5.94) for i = 1 and i = 3 of the chapter's ordering I1 > I2 > I3 and −(5.100) for
// i = 2, and holds for any ordering. s_i > 0: stable, Ω = √s_i; s_i < 0: unstable, growth √−s_i;
// s_i = 0: neutral (two equal moments), or stable with rate 0 for a spherical top (ω constant)
// and for the axes perpendicular to a rotor's line.
std::array<axis_stability, 3> stability_report(const principal_axes& principal,
                                               const GiNaC::exmap& defaults);

// Everything `rotgen inspect --inertia` shows.
struct inertia_report {
    matrix3 tensor;
    principal_axes principal;
    top_class kind = top_class::asymmetric;
    std::array<axis_stability, 3> stability;
};
inertia_report analyse_inertia(const matrix3& tensor, const GiNaC::exmap& defaults);

// ---- helpers shared with the parser -------------------------------------------------------------

// Square roots of rationals written over square roots of primes with the square factors taken
// out (sqrt(6) -> sqrt(2) sqrt(3), sqrt(12) -> 2 sqrt(3), 6^(-1/2) -> sqrt(2) sqrt(3)/6), then
// expanded, so that equal algebraic numbers cancel (GiNaC keeps sqrt(2) sqrt(3) and sqrt(6) apart).
GiNaC::ex canonical_radicals(const GiNaC::ex& e);

// The value of e at the defaults (a real double), or nullopt if it is not a finite real number.
std::optional<double> value_at(const GiNaC::ex& e, const GiNaC::exmap& defaults);

// A rational function in a reproducible form: reduced (normal()), the denominator expanded with
// integer content 1 and positive at the defaults, and the numerator's terms distributed over it
// (GiNaC's normal() chooses signs by hash order, and a sum that is a factor of a product may be
// held with either sign; a sum of monomials over one denominator prints the same way every run).
GiNaC::ex canonical_fraction(const GiNaC::ex& e, const GiNaC::exmap& defaults);

} // namespace rotgen
