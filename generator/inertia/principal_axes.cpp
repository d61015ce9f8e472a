// rotgen — inertia/: principal axes (§5.5): the eigenvalues and eigenvectors of a symmetric tensor
// (5.60–5.62), exact where GiNaC's factor() splits the characteristic cubic and the closed forms
// stay readable, numeric (Eigen, at the defaults) otherwise; and the classification of the top.
#include "inertia/inertia_detail.hpp"

#include "expr/numbers.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace rotgen {

using GiNaC::ex;
using GiNaC::numeric;
using namespace inertia_detail;

const char* top_class_name(top_class c) {
    switch (c) {
    case top_class::spherical:
        return "spherical";
    case top_class::symmetric:
        return "symmetric";
    case top_class::asymmetric:
        return "asymmetric";
    case top_class::rotor:
        return "rotor";
    }
    return "?";
}

top_class classify(const std::array<double, 3>& moments, double rel_tol) {
    std::array<double, 3> m = moments;
    std::sort(m.begin(), m.end());
    const double tol = rel_tol * std::max(std::abs(m[0]), std::abs(m[2]));
    const bool eq01 = m[1] - m[0] <= tol, eq12 = m[2] - m[1] <= tol;
    if (eq01 && eq12) return top_class::spherical;
    if (std::abs(m[0]) <= tol && eq12) return top_class::rotor; // I1 = 0, I2 = I3
    if (eq01 || eq12) return top_class::symmetric;
    return top_class::asymmetric;
}

namespace {

using eigen_result = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>;

// A row with its largest component positive.
std::array<double, 3> sign_normalised(const Eigen::Vector3d& v) {
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(v[i]) > std::abs(v[k]) * (1 + 1e-12)) k = i;
    const double s = v[k] < 0 ? -1 : 1;
    return {s * v[0], s * v[1], s * v[2]};
}

double det3(const std::array<std::array<double, 3>, 3>& a) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

principal_axes numeric_axes(const Eigen::Matrix3d& tn) {
    const eigen_result solver(tn);
    principal_axes r;
    for (int k = 0; k < 3; ++k) {
        r.moment_values[k] = solver.eigenvalues()[k];
        r.axis_values[k] = sign_normalised(solver.eigenvectors().col(k));
    }
    if (det3(r.axis_values) < 0)
        for (double& x : r.axis_values[2])
            x = -x;
    for (int k = 0; k < 3; ++k) {
        r.moments[k] = float_numeric(r.moment_values[k]);
        for (int j = 0; j < 3; ++j) // an eigenvector component may be subnormal
            r.axes[k][j] = float_numeric(r.axis_values[k][j]);
    }
    return r;
}

// Nodes in an expression tree: a measure of how readable a closed form still is.
std::size_t tree_size(const ex& e) {
    std::size_t n = 1;
    for (std::size_t i = 0; i < e.nops(); ++i)
        n += tree_size(e.op(i));
    return n;
}

// Limits on the closed forms: beyond them (quadratic factors with symbolic coefficients give
// axes of thousands of nodes) the numeric answer is the useful one.
constexpr std::size_t max_polynomial_terms =
    150; // factor() of larger characteristic polynomials takes seconds
constexpr std::size_t max_moment_size = 200;
constexpr std::size_t max_axes_size = 400; // all nine components together

// A root under a root (sqrt(5/2 - sqrt(5)/2)): unit axes in Q(√d) usually need one, and then
// the numbers say more than the closed form.
bool has_root(const ex& e) {
    if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<numeric>(e.op(1)) &&
        !GiNaC::ex_to<numeric>(e.op(1)).is_integer())
        return true;
    for (std::size_t i = 0; i < e.nops(); ++i)
        if (has_root(e.op(i))) return true;
    return false;
}

bool has_nested_root(const ex& e) {
    if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<numeric>(e.op(1)) &&
        !GiNaC::ex_to<numeric>(e.op(1)).is_integer())
        return has_root(e.op(0));
    for (std::size_t i = 0; i < e.nops(); ++i)
        if (has_nested_root(e.op(i))) return true;
    return false;
}

struct root {
    ex value;
    double number = 0;
};

// det(T − λ1), expanded, over a common denominator: its numerator (the same roots), or nullopt
// when it is not a cubic in λ, has too many terms to factor quickly, or cannot be factored.
std::optional<ex> factored_characteristic(const matrix3& t, const GiNaC::realsymbol& lambda) {
    matrix3 m = t;
    for (int i = 0; i < 3; ++i)
        m[i][i] = m[i][i] - lambda;
    ex p = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
            m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
            m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
               .expand();
    try {
        p = p.numer_denom().op(0).expand(); // the numerator has the same roots
        if (p.degree(lambda) != 3 ||
            (GiNaC::is_a<GiNaC::add>(p) && p.nops() > max_polynomial_terms))
            return std::nullopt;
        return GiNaC::factor(p);
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

// The factors of a product with their multiplicities: f^k -> (f, k).
std::vector<std::pair<ex, int>> factors_of(const ex& factored) {
    std::vector<std::pair<ex, int>> factors;
    if (GiNaC::is_a<GiNaC::mul>(factored)) {
        for (std::size_t i = 0; i < factored.nops(); ++i)
            factors.push_back({factored.op(i), 1});
    } else {
        factors.push_back({factored, 1});
    }
    for (auto& f : factors)
        if (GiNaC::is_a<GiNaC::power>(f.first) && GiNaC::is_a<numeric>(f.first.op(1)) &&
            GiNaC::ex_to<numeric>(f.first.op(1)).is_pos_integer()) {
            f.second = GiNaC::ex_to<numeric>(f.first.op(1)).to_int();
            f.first = f.first.op(0);
        }
    return factors;
}

// The roots of a linear or quadratic factor f(λ), exactly; nullopt for a cubic.
std::optional<std::vector<ex>> roots_of_factor(const ex& f, const GiNaC::realsymbol& lambda,
                                               const GiNaC::exmap& defaults) {
    const int degree = f.degree(lambda);
    std::vector<ex> found;
    if (degree == 1) {
        // a λ + b = 0
        found.push_back(canonical_fraction(-f.coeff(lambda, 0) / f.coeff(lambda, 1), defaults));
    } else if (degree == 2) {
        // a λ² + b λ + c = 0:  λ = −b/(2a) ± √((b² − 4ac)/(4a²))
        const ex a = f.coeff(lambda, 2), b = f.coeff(lambda, 1), c = f.coeff(lambda, 0);
        const ex centre = canonical_fraction(-b / (2 * a), defaults);
        const ex half_width =
            exact_sqrt(canonical_fraction((b * b - 4 * a * c) / (4 * a * a), defaults));
        found.push_back((centre - half_width).expand());
        found.push_back((centre + half_width).expand());
    } else {
        return std::nullopt; // an irreducible cubic: casus irreducibilis, go numeric
    }
    return found;
}

// The roots of det(T − λ1) = 0 from GiNaC's factorisation, or nullopt if a factor is an
// irreducible cubic (or the polynomial is not one factor() can split).
std::optional<std::vector<root>> exact_roots(const matrix3& t, const GiNaC::exmap& defaults) {
    const GiNaC::realsymbol lambda("lambda");
    const auto factored = factored_characteristic(t, lambda);
    if (!factored) return std::nullopt;
    std::vector<root> roots;
    for (const auto& [factor_ex, multiplicity] : factors_of(*factored)) {
        const ex f = factor_ex.expand();
        if (!f.has(lambda)) continue;
        const auto found = roots_of_factor(f, lambda, defaults);
        if (!found) return std::nullopt;
        for (int k = 0; k < multiplicity; ++k)
            for (const ex& r : *found) {
                const auto v = value_at(r, defaults);
                if (!v) return std::nullopt;
                roots.push_back({r, *v});
            }
    }
    if (roots.size() != 3) return std::nullopt;
    std::stable_sort(roots.begin(), roots.end(),
                     [](const root& a, const root& b) { return a.number < b.number; });
    return roots;
}

// The square roots (of numbers) in e.
void collect_roots(const ex& e, GiNaC::exset& roots) {
    if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<numeric>(e.op(0)) && e.op(1) == numeric(1, 2)) {
        roots.insert(e);
        return;
    }
    for (std::size_t i = 0; i < e.nops(); ++i)
        collect_roots(e.op(i), roots);
}

// A number in Q(√d) written as a + b√d: the denominator rationalised with its conjugate,
// (p + q√d)(p − q√d) = p² − q² d. Anything else (symbols, several roots) is returned as it is.
ex rationalised(const ex& e) {
    if (!GiNaC::is_a<numeric>(GiNaC::evalf(e))) return e; // not a number
    const ex c = canonical_radicals(e);
    GiNaC::exset roots;
    collect_roots(c, roots);
    if (roots.size() != 1) return e;
    const ex root = *roots.begin();
    const ex d = root.op(0);
    const GiNaC::realsymbol x("x");
    const ex square = GiNaC::pow(x, 2) - d;
    try {
        const ex nd = c.subs(root == x).normal().numer_denom();
        const ex den = GiNaC::rem(nd.op(1).expand(), square, x);
        const ex conj = den.subs(x == -x);
        const ex num = GiNaC::rem((nd.op(0) * conj).expand(), square, x);
        const ex norm = GiNaC::rem((den * conj).expand(), square, x);
        if (!GiNaC::is_a<numeric>(norm) || norm.is_zero()) return e;
        return (num / norm).expand().subs(x == root);
    } catch (const std::exception&) {
        return e;
    }
}

// A direction as an exact vector, scaled so that its largest component (at the defaults) is 1.
std::optional<vector3> scaled_direction(const vector3& v, const GiNaC::exmap& defaults) {
    int k = -1;
    double best = 0;
    for (int i = 0; i < 3; ++i) {
        const auto x = value_at(v[i], defaults);
        if (!x) return std::nullopt;
        if (std::abs(*x) > best * (1 + 1e-12)) best = std::abs(*x), k = i;
    }
    if (k < 0) return std::nullopt;
    vector3 w;
    for (int i = 0; i < 3; ++i)
        w[i] = i == k ? ex(1) : rationalised(canonical_fraction(v[i] / v[k], defaults));
    return w;
}

// w / |w|; for a rational |w|² the square root is taken exactly (1/√3 -> √3/3).
vector3 normalised(const vector3& w, const GiNaC::exmap& defaults) {
    const ex norm2 = rationalised(canonical_fraction(dot(w, w), defaults));
    ex inverse_norm;
    if (GiNaC::is_a<numeric>(norm2) && GiNaC::ex_to<numeric>(norm2).is_rational())
        inverse_norm = exact_sqrt(GiNaC::ex_to<numeric>(norm2).inverse());
    else
        inverse_norm = GiNaC::pow(norm2, numeric(-1, 2));
    vector3 u;
    for (int i = 0; i < 3; ++i)
        u[i] = (w[i] * inverse_norm).expand();
    return u;
}

// The eigenvector of a simple eigenvalue λ: the rows of T − λ1 span the plane perpendicular to
// it, so the cross product of two independent rows points along it; take the largest of the
// three (at the defaults).
std::optional<vector3> simple_direction(const matrix3& t, const ex& lambda, double scale2,
                                        const GiNaC::exmap& defaults) {
    matrix3 m = t;
    for (int i = 0; i < 3; ++i)
        m[i][i] = (m[i][i] - lambda).expand();
    const std::array<vector3, 3> rows{m[0], m[1], m[2]};
    std::optional<vector3> best;
    double best_norm = 0;
    for (const auto& [i, j] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
        const vector3 c = cross(rows[i], rows[j]);
        const auto n = value_at(dot(c, c), defaults);
        if (!n) return std::nullopt;
        if (*n > best_norm * (1 + 1e-12)) best_norm = *n, best = c;
    }
    if (!best || best_norm <= 1e-20 * scale2 * scale2) return std::nullopt;
    return scaled_direction(*best, defaults);
}

// equal[k]: root k equals root k+1 exactly; nullopt when exactly different roots coincide at the
// defaults (the axes would be 0/0 there: numeric then) or all three are equal (a multiple of 1 is
// diagonal: handled before).
std::optional<std::array<bool, 2>> equal_roots(const std::vector<root>& roots, double scale,
                                               const GiNaC::exmap& defaults) {
    std::array<bool, 2> equal{};
    for (int k = 0; k < 2; ++k) {
        equal[k] = canonical_fraction(roots[k].value - roots[k + 1].value, defaults).is_zero();
        if (!equal[k] && std::abs(roots[k].number - roots[k + 1].number) <= 1e-9 * scale)
            return std::nullopt;
    }
    if (equal[0] && equal[1]) return std::nullopt;
    return equal;
}

// A double moment: u the simple axis (of root s); v the body axis e_k least aligned with u, minus
// its component along u; w = u × v. Rows (u, v, w) cyclically from u's place: det = +1.
std::optional<std::array<vector3, 3>> double_moment_directions(const matrix3& t,
                                                               const std::vector<root>& roots,
                                                               int s, double scale,
                                                               const GiNaC::exmap& defaults) {
    const auto u = simple_direction(t, roots[s].value, scale * scale, defaults);
    if (!u) return std::nullopt;
    int k = 0;
    double smallest = 2;
    for (int i = 0; i < 3; ++i) {
        const double x = std::abs(*value_at((*u)[i], defaults));
        if (x < smallest * (1 - 1e-12)) smallest = x, k = i;
    }
    const ex uu = dot(*u, *u);
    vector3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = rationalised(
            canonical_fraction((i == k ? ex(1) : ex(0)) - (*u)[k] * (*u)[i] / uu, defaults));
    const auto vs = scaled_direction(v, defaults);
    if (!vs) return std::nullopt;
    vector3 w = cross(*u, *vs);
    for (auto& x : w)
        x = canonical_fraction(x, defaults);
    std::array<vector3, 3> dirs;
    dirs[s] = *u;
    dirs[(s + 1) % 3] = *vs;
    dirs[(s + 2) % 3] = w;
    return dirs;
}

// The (unnormalised) principal directions of the exact moments, or nullopt.
std::optional<std::array<vector3, 3>> exact_directions(const matrix3& t,
                                                       const std::vector<root>& roots, double scale,
                                                       const GiNaC::exmap& defaults) {
    const auto equal = equal_roots(roots, scale, defaults);
    if (!equal) return std::nullopt;
    if ((*equal)[0] || (*equal)[1])
        return double_moment_directions(t, roots, (*equal)[0] ? 2 : 0, scale, defaults);
    std::array<vector3, 3> dirs;
    for (int k = 0; k < 3; ++k) {
        const auto d = simple_direction(t, roots[k].value, scale * scale, defaults);
        if (!d) return std::nullopt;
        dirs[k] = *d;
    }
    return dirs;
}

// Check at the defaults: A orthonormal and A T Aᵀ = diag(moments).
bool diagonalises(const principal_axes& r, const Eigen::Matrix3d& tn, double scale) {
    Eigen::Matrix3d a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            a(i, j) = r.axis_values[i][j];
    const Eigen::Matrix3d d = a * tn * a.transpose();
    if ((a * a.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9)
        return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(d(i, j) - (i == j ? r.moment_values[i] : 0.0)) > 1e-9 * scale)
                return false;
    return true;
}

// The axes in closed form for the exact moments `roots` (ascending), or nullopt.
std::optional<principal_axes> exact_axes(const matrix3& t, const Eigen::Matrix3d& tn,
                                         const std::vector<root>& roots, double scale,
                                         const GiNaC::exmap& defaults) {
    const auto dirs = exact_directions(t, roots, scale, defaults);
    if (!dirs) return std::nullopt;
    principal_axes r;
    r.exact_moments = r.exact_axes = true;
    std::size_t axes_size = 0;
    for (int k = 0; k < 3; ++k) {
        r.moments[k] = roots[k].value;
        r.moment_values[k] = roots[k].number;
        const vector3 u = normalised((*dirs)[k], defaults);
        for (int j = 0; j < 3; ++j) {
            axes_size += tree_size(u[j]);
            if (axes_size > max_axes_size || has_nested_root(u[j])) return std::nullopt;
            r.axes[k][j] = u[j];
            const auto x = value_at(u[j], defaults);
            if (!x) return std::nullopt;
            r.axis_values[k][j] = *x;
        }
    }
    if (det3(r.axis_values) < 0)
        for (int j = 0; j < 3; ++j) {
            r.axes[2][j] = (-r.axes[2][j]).expand();
            r.axis_values[2][j] = -r.axis_values[2][j];
        }
    if (!diagonalises(r, tn, scale)) return std::nullopt;
    return r;
}

} // namespace

principal_axes numeric_principal_axes(const std::array<std::array<double, 3>, 3>& tensor) {
    Eigen::Matrix3d tn;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            tn(i, j) = tensor[i][j];
    return numeric_axes(tn);
}

principal_axes find_principal_axes(const matrix3& tensor, const GiNaC::exmap& defaults) {
    Eigen::Matrix3d tn;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            tn(i, j) = value_or_throw(tensor[i][j], defaults);
    bool diagonal_tensor = true;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (i != j && !tensor[i][j].expand().is_zero()) diagonal_tensor = false;
    if (diagonal_tensor) {
        principal_axes r;
        r.exact_moments = r.exact_axes = true;
        for (int k = 0; k < 3; ++k) {
            r.moments[k] = tensor[k][k];
            r.moment_values[k] = tn(k, k);
            for (int j = 0; j < 3; ++j) {
                r.axes[k][j] = k == j ? 1 : 0;
                r.axis_values[k][j] = k == j ? 1 : 0;
            }
        }
        return r;
    }
    principal_axes fallback = numeric_axes(tn);
    if (const auto across = exact_rotor_moment(tensor)) {
        // a linear rotor (rotor.cpp): moments (0, I, I) exactly, ascending like the fallback's;
        // the axes numeric (the line is the eigenvector of the zero moment)
        fallback.exact_moments = true;
        fallback.moments = {ex(0), *across, *across};
        const double v = value_or_throw(*across, defaults);
        fallback.moment_values = {0.0, v, v};
        return fallback;
    }
    matrix3 t;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            t[i][j] = canonical_radicals(tensor[i][j]);
    const auto roots = exact_roots(t, defaults);
    if (!roots) return fallback;
    const double scale =
        std::max(std::abs(fallback.moment_values[0]), std::abs(fallback.moment_values[2])) + 1e-300;
    for (int k = 0; k < 3; ++k)
        if (std::abs((*roots)[k].number - fallback.moment_values[k]) > 1e-9 * scale ||
            tree_size((*roots)[k].value) > max_moment_size)
            return fallback;
    if (auto exact = exact_axes(t, tn, *roots, scale, defaults)) return *exact;
    // exact moments, numeric axes
    fallback.exact_moments = true;
    for (int k = 0; k < 3; ++k) {
        fallback.moments[k] = (*roots)[k].value;
        fallback.moment_values[k] = (*roots)[k].number;
    }
    return fallback;
}

} // namespace rotgen
