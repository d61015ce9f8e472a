#include "inertia/inertia.hpp"

#include "expr/numbers.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rotgen {

using GiNaC::ex;
using GiNaC::numeric;

// ---- helpers ------------------------------------------------------------------------------------

std::optional<double> value_at(const ex& e, const GiNaC::exmap& defaults) {
    try {
        const ex v = GiNaC::evalf(e.subs(defaults));
        if (!GiNaC::is_a<numeric>(v) || !GiNaC::ex_to<numeric>(v).is_real()) return std::nullopt;
        const double x = GiNaC::ex_to<numeric>(v).to_double();
        if (!std::isfinite(x)) return std::nullopt;
        return x;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

namespace {

double value_or_throw(const ex& e, const GiNaC::exmap& defaults) {
    const auto v = value_at(e, defaults);
    if (!v)
        throw std::invalid_argument(
            "rotgen inertia: an entry is not a finite real number at the defaults");
    return *v;
}

} // namespace

ex canonical_fraction(const ex& e, const GiNaC::exmap& defaults) {
    const ex expanded = e.expand();
    if (GiNaC::is_a<numeric>(expanded)) return expanded;
    const ex nd = expanded.numer_denom(); // normal(), then {numerator, denominator}
    ex n = nd.op(0).expand(), d = nd.op(1).expand();
    if (GiNaC::is_a<numeric>(d)) return (n / d).expand();
    if (const auto v = value_at(d, defaults); v && *v < 0) {
        n = (-n).expand();
        d = (-d).expand();
    }
    try {
        const numeric c = d.integer_content();
        if (!c.is_zero() && c != 1) {
            n = (n / c).expand();
            d = (d / c).expand();
        }
    } catch (const std::exception&) {
        // not a polynomial over the rationals: keep the scale normal() chose
    }
    // Distributed over the terms of n: GiNaC may hold a sum that is a factor of a product with
    // either sign (by hash order); a sum of monomials over d prints the same way every run.
    return (n * GiNaC::pow(d, -1)).expand();
}

namespace {

// √v for a positive rational v = p/q: √(pq)/q with pq = s² Π p_i (p_i distinct primes, found by
// trial division; a cofactor left after 10⁵ stays under one root).
ex prime_root(const numeric& v) {
    const numeric q = v.denom();
    numeric rest = v.numer() * q, outside = 1;
    ex roots = 1;
    for (numeric p = 2; p * p <= rest && p < 100000; p += 1) {
        int count = 0;
        while (GiNaC::irem(rest, p).is_zero()) {
            rest = rest / p;
            ++count;
        }
        for (int i = 0; i < count / 2; ++i)
            outside *= p;
        if (count % 2) roots *= GiNaC::sqrt(ex(p));
    }
    if (rest != 1) roots *= GiNaC::sqrt(ex(rest));
    return outside / q * roots;
}

struct radical_map : GiNaC::map_function {
    ex operator()(const ex& e) override {
        if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<numeric>(e.op(0)) &&
            GiNaC::is_a<numeric>(e.op(1))) {
            const numeric base = GiNaC::ex_to<numeric>(e.op(0)),
                          exponent = GiNaC::ex_to<numeric>(e.op(1));
            if (base.is_rational() && base.is_positive() && exponent.is_rational() &&
                exponent.denom() == 2)
                // base^(k/2) = base^((k − 1)/2) √base, k odd
                return GiNaC::pow(base, (exponent.numer() - 1) / 2) * prime_root(base);
        }
        return e.map(*this);
    }
};

// In each product, √a √b -> √(ab): the inverse of prime_root for printing (sqrt(6), not
// sqrt(2)*sqrt(3)); unique on the canonical form, where each term has its own set of primes.
struct merge_roots_map : GiNaC::map_function {
    ex operator()(const ex& e) override {
        if (!GiNaC::is_a<GiNaC::mul>(e)) return e.map(*this);
        numeric under = 1;
        ex rest = 1;
        for (std::size_t i = 0; i < e.nops(); ++i) {
            const ex f = e.op(i);
            if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<numeric>(f.op(0)) &&
                GiNaC::ex_to<numeric>(f.op(0)).is_pos_integer() && f.op(1) == numeric(1, 2))
                under *= GiNaC::ex_to<numeric>(f.op(0));
            else
                rest *= (*this)(f);
        }
        return rest * GiNaC::sqrt(ex(under));
    }
};

} // namespace

ex canonical_radicals(const ex& e) {
    radical_map m;
    return m(e).expand();
}

namespace {

// canonical_radicals, then the roots of each term merged again for printing.
ex printable_radicals(const ex& e) {
    merge_roots_map m;
    return m(canonical_radicals(e));
}

// q = n/d, exactly: a polynomial quotient where d divides n, else a canonical fraction.
ex exact_quotient(const ex& n, const ex& d, const GiNaC::exmap& defaults) {
    const ex ne = n.expand(), de = d.expand();
    if (GiNaC::is_a<numeric>(de)) return (ne / de).expand();
    try {
        ex q;
        if (GiNaC::divide(ne, de, q)) return q.expand();
    } catch (const std::exception&) {
        // not polynomials over the rationals (sin, sqrt, ...)
    }
    return canonical_fraction(ne / de, defaults);
}

// √x for x >= 0, with square factors of a rational x taken out: √(p/q) = s √r / q, pq = s² r.
ex exact_sqrt(const ex& x) {
    if (!GiNaC::is_a<numeric>(x) || !GiNaC::ex_to<numeric>(x).is_rational()) return GiNaC::sqrt(x);
    const numeric v = GiNaC::ex_to<numeric>(x);
    if (v.is_zero()) return 0;
    const numeric q = v.denom();
    numeric rest = v.numer() * q, outside = 1;
    for (numeric i = 2; i * i <= rest && i < 100000; i += 1)
        while (GiNaC::irem(rest, i * i).is_zero()) {
            rest = rest / (i * i);
            outside *= i;
        }
    return outside * GiNaC::sqrt(ex(rest)) / q;
}

matrix3 zero3() {
    matrix3 m;
    for (auto& row : m)
        for (auto& x : row)
            x = 0;
    return m;
}

matrix3 add(const matrix3& a, const matrix3& b) {
    matrix3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = (a[i][j] + b[i][j]).expand();
    return m;
}

matrix3 scale(const ex& s, const matrix3& a) {
    matrix3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = (s * a[i][j]).expand();
    return m;
}

matrix3 diagonal(const ex& a, const ex& b, const ex& c) {
    matrix3 m = zero3();
    m[0][0] = a;
    m[1][1] = b;
    m[2][2] = c;
    return m;
}

ex dot(const vector3& a, const vector3& b) {
    return (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).expand();
}

vector3 cross(const vector3& a, const vector3& b) {
    return {(a[1] * b[2] - a[2] * b[1]).expand(), (a[2] * b[0] - a[0] * b[2]).expand(),
            (a[0] * b[1] - a[1] * b[0]).expand()};
}

// n nᵀ for n = a/|a|, written a aᵀ / (aᵀ a).
matrix3 axis_projector(const vector3& a) {
    const ex norm2 = dot(a, a);
    matrix3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = (a[i] * a[j] / norm2).expand();
    return m;
}

} // namespace

// ---- rotations ----------------------------------------------------------------------------------

matrix3 rotation_x(const ex& a) {
    const ex c = GiNaC::cos(a), s = GiNaC::sin(a);
    return {{{1, 0, 0}, {0, c, s}, {0, -s, c}}};
}

matrix3 rotation_y(const ex& a) {
    const ex c = GiNaC::cos(a), s = GiNaC::sin(a);
    return {{{c, 0, -s}, {0, 1, 0}, {s, 0, c}}};
}

matrix3 rotation_z(const ex& a) {
    const ex c = GiNaC::cos(a), s = GiNaC::sin(a);
    return {{{c, s, 0}, {-s, c, 0}, {0, 0, 1}}};
}

matrix3 euler_rotation(const ex& phi, const ex& theta, const ex& psi) {
    // A = Az(psi) Ax(theta) Az(phi)  (5.25)
    return multiply(rotation_z(psi), multiply(rotation_x(theta), rotation_z(phi)));
}

matrix3 multiply(const matrix3& a, const matrix3& b) {
    matrix3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            ex s = 0;
            for (int k = 0; k < 3; ++k)
                s += a[i][k] * b[k][j];
            m[i][j] = s.expand();
        }
    return m;
}

matrix3 transpose(const matrix3& a) {
    matrix3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = a[j][i];
    return m;
}

matrix3 identity3() {
    return diagonal(1, 1, 1);
}

matrix3 transform_tensor(const matrix3& a, const matrix3& tensor) {
    // I'_ij = Σ_kl A_ik A_jl I_kl  (5.44)
    return multiply(multiply(a, tensor), transpose(a));
}

// ---- parts --------------------------------------------------------------------------------------

const std::vector<std::string>& part_kind_names() {
    static const std::vector<std::string> names{"point", "box", "rod", "cylinder", "sphere"};
    return names;
}

const char* part_kind_name(part_kind k) {
    return part_kind_names()[static_cast<int>(k)].c_str();
}

matrix3 point_mass_tensor(const ex& m, const vector3& d) {
    // m (d² δ_ij − d_i d_j)  (5.39)
    const ex d2 = dot(d, d);
    matrix3 t;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            t[i][j] = (m * ((i == j ? d2 : ex(0)) - d[i] * d[j])).expand();
    return t;
}

matrix3 central_tensor(const part& p) {
    const ex& m = p.mass;
    switch (p.kind) {
    case part_kind::point:
        return zero3();
    case part_kind::box: {
        const ex a2 = GiNaC::pow(p.size[0], 2), b2 = GiNaC::pow(p.size[1], 2),
                 c2 = GiNaC::pow(p.size[2], 2);
        const matrix3 own = diagonal((m * (b2 + c2) / 12).expand(), (m * (a2 + c2) / 12).expand(),
                                     (m * (a2 + b2) / 12).expand());
        if (!p.rotation) return own;
        // x_box = A x_body, so I_body = Aᵀ I_box A  (5.44 with A -> Aᵀ)
        const matrix3 a = euler_rotation((*p.rotation)[0], (*p.rotation)[1], (*p.rotation)[2]);
        matrix3 t = transform_tensor(transpose(a), own);
        for (auto& row : t)
            for (auto& x : row)
                x = printable_radicals(x);
        return t;
    }
    case part_kind::rod: {
        // m l²/12 (1 − n nᵀ)
        const matrix3 nn = axis_projector(p.axis);
        return scale(m * GiNaC::pow(p.length, 2) / 12, add(identity3(), scale(-1, nn)));
    }
    case part_kind::cylinder: {
        // m(3r² + l²)/12 (1 − n nᵀ) + m r²/2 n nᵀ
        const matrix3 nn = axis_projector(p.axis);
        const ex r2 = GiNaC::pow(p.radius, 2), l2 = GiNaC::pow(p.length, 2);
        return add(scale(m * (3 * r2 + l2) / 12, add(identity3(), scale(-1, nn))),
                   scale(m * r2 / 2, nn));
    }
    case part_kind::sphere: {
        // 2/5 m r² (solid), 2/3 m r² (thin shell)
        const ex k = p.hollow ? numeric(2, 3) : numeric(2, 5);
        return scale(k * m * GiNaC::pow(p.radius, 2), identity3());
    }
    }
    throw std::logic_error("rotgen inertia: unknown part kind");
}

body_inertia combine_parts(const std::vector<part>& parts, const std::optional<vector3>& pivot,
                           const GiNaC::exmap& defaults) {
    body_inertia b;
    ex mass = 0;
    vector3 moment{0, 0, 0}; // S = Σ m r
    for (const part& p : parts) {
        mass += p.mass;
        for (int i = 0; i < 3; ++i)
            moment[i] += p.mass * p.at[i];
    }
    b.mass = mass.expand();
    for (int i = 0; i < 3; ++i) {
        moment[i] = moment[i].expand();
        b.centre_of_mass[i] = exact_quotient(moment[i], b.mass, defaults); // c = S / M
    }
    if (pivot) {
        // Σ [ I_C,k + m_k (d² 1 − d dᵀ) ],  d = r_k − pivot  (parallel-axis theorem)
        b.pivot = *pivot;
        b.pivot_given = true;
        matrix3 sum = zero3();
        for (const part& p : parts) {
            vector3 d;
            for (int i = 0; i < 3; ++i)
                d[i] = (p.at[i] - (*pivot)[i]).expand();
            sum = add(sum, add(central_tensor(p), point_mass_tensor(p.mass, d)));
        }
        b.tensor = sum;
        return b;
    }
    // About the centre of mass: I_c = I_O − (S² 1 − S Sᵀ)/M = (M I_O − (S² 1 − S Sᵀ)) / M.
    b.pivot = b.centre_of_mass;
    matrix3 origin = zero3();
    for (const part& p : parts)
        origin = add(origin, add(central_tensor(p), point_mass_tensor(p.mass, p.at)));
    const matrix3 numerator = add(scale(b.mass, origin), scale(-1, point_mass_tensor(1, moment)));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            b.tensor[i][j] = exact_quotient(numerator[i][j], b.mass, defaults);
    return b;
}

// ---- principal axes -----------------------------------------------------------------------------

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

// The roots of det(T − λ1) = 0 from GiNaC's factorisation, or nullopt if a factor is an
// irreducible cubic (or the polynomial is not one factor() can split).
std::optional<std::vector<root>> exact_roots(const matrix3& t, const GiNaC::exmap& defaults) {
    const GiNaC::realsymbol lambda("lambda");
    matrix3 m = t;
    for (int i = 0; i < 3; ++i)
        m[i][i] = m[i][i] - lambda;
    ex p = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
            m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
            m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
               .expand();
    ex factored;
    try {
        p = p.numer_denom().op(0).expand(); // the numerator has the same roots
        if (p.degree(lambda) != 3 ||
            (GiNaC::is_a<GiNaC::add>(p) && p.nops() > max_polynomial_terms))
            return std::nullopt;
        factored = GiNaC::factor(p);
    } catch (const std::exception&) {
        return std::nullopt;
    }
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
    std::vector<root> roots;
    for (const auto& [factor_ex, multiplicity] : factors) {
        const ex f = factor_ex.expand();
        if (!f.has(lambda)) continue;
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
        for (int k = 0; k < multiplicity; ++k)
            for (const ex& r : found) {
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

// The axes in closed form for the exact moments `roots` (ascending), or nullopt.
std::optional<principal_axes> exact_axes(const matrix3& t, const Eigen::Matrix3d& tn,
                                         const std::vector<root>* roots, double scale,
                                         const GiNaC::exmap& defaults) {
    // equal[k]: root k equals root k+1 exactly; exactly different roots that coincide at the
    // defaults would give axes that are 0/0 there: numeric then.
    std::array<bool, 2> equal{};
    for (int k = 0; k < 2; ++k) {
        equal[k] =
            canonical_fraction((*roots)[k].value - (*roots)[k + 1].value, defaults).is_zero();
        if (!equal[k] && std::abs((*roots)[k].number - (*roots)[k + 1].number) <= 1e-9 * scale)
            return std::nullopt;
    }
    if (equal[0] && equal[1]) return std::nullopt; // a multiple of 1 is diagonal: handled before
    std::array<vector3, 3> dirs;
    if (!equal[0] && !equal[1]) {
        for (int k = 0; k < 3; ++k) {
            const auto d = simple_direction(t, (*roots)[k].value, scale * scale, defaults);
            if (!d) return std::nullopt;
            dirs[k] = *d;
        }
    } else {
        // A double moment: u the simple axis; v the body axis e_k least aligned with u, minus its
        // component along u; w = u × v. Rows (u, v, w) cyclically from u's place: det = +1.
        const int s = equal[0] ? 2 : 0;
        const auto u = simple_direction(t, (*roots)[s].value, scale * scale, defaults);
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
        dirs[s] = *u;
        dirs[(s + 1) % 3] = *vs;
        dirs[(s + 2) % 3] = w;
    }
    principal_axes r;
    r.exact_moments = r.exact_axes = true;
    std::size_t axes_size = 0;
    for (int k = 0; k < 3; ++k) {
        r.moments[k] = (*roots)[k].value;
        r.moment_values[k] = (*roots)[k].number;
        const vector3 u = normalised(dirs[k], defaults);
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
    // Check at the defaults: A orthonormal and A T Aᵀ = diag(moments).
    Eigen::Matrix3d a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            a(i, j) = r.axis_values[i][j];
    const Eigen::Matrix3d d = a * tn * a.transpose();
    if ((a * a.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9)
        return std::nullopt;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(d(i, j) - (i == j ? r.moment_values[i] : 0.0)) > 1e-9 * scale)
                return std::nullopt;
    return r;
}

} // namespace

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
    matrix3 t;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            t[i][j] = canonical_radicals(tensor[i][j]);
    principal_axes fallback = numeric_axes(tn);
    const auto roots = exact_roots(t, defaults);
    if (!roots) return fallback;
    const double scale =
        std::max(std::abs(fallback.moment_values[0]), std::abs(fallback.moment_values[2])) + 1e-300;
    for (int k = 0; k < 3; ++k)
        if (std::abs((*roots)[k].number - fallback.moment_values[k]) > 1e-9 * scale ||
            tree_size((*roots)[k].value) > max_moment_size)
            return fallback;
    if (auto exact = exact_axes(t, tn, &*roots, scale, defaults)) return *exact;
    // exact moments, numeric axes
    fallback.exact_moments = true;
    for (int k = 0; k < 3; ++k) {
        fallback.moments[k] = (*roots)[k].value;
        fallback.moment_values[k] = (*roots)[k].number;
    }
    return fallback;
}

// ---- stability ----------------------------------------------------------------------------------

const char* stability_kind_name(stability_kind k) {
    switch (k) {
    case stability_kind::stable:
        return "stable";
    case stability_kind::unstable:
        return "unstable";
    case stability_kind::neutral:
        return "neutral";
    case stability_kind::none:
        return "none";
    }
    return "?";
}

std::array<axis_stability, 3> stability_report(const principal_axes& principal,
                                               const GiNaC::exmap& defaults) {
    const auto& m = principal.moment_values;
    const double scale = std::max({std::abs(m[0]), std::abs(m[1]), std::abs(m[2])});
    const double tol = 1e-12 * scale;
    const top_class kind = classify(m);
    std::array<axis_stability, 3> report;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        axis_stability& s = report[i];
        s.axis = i + 1;
        s.rate = 0;
        s.rate_value = 0;
        if (kind == top_class::spherical) {
            // I ω̇ = 0: ω is constant, any deviation too.
            s.kind = stability_kind::stable;
        } else if (kind == top_class::rotor) {
            // The line (zero moment): nothing moves. Perpendicular to it: every axis in that
            // plane is principal with the same moment, a deviation is another steady rotation.
            s.kind = std::abs(m[i]) <= tol ? stability_kind::none : stability_kind::stable;
        } else if (std::abs(m[i] - m[j]) <= tol || std::abs(m[i] - m[k]) <= tol) {
            s.kind = stability_kind::neutral; // s_i = 0 with I_i equal to another moment
        } else {
            // s_i = (I_i − I_j)(I_i − I_k) / (I_j I_k)   (5.94, 5.100)
            const ex& Ii = principal.moments[i];
            const ex& Ij = principal.moments[j];
            const ex& Ik = principal.moments[k];
            const double value = (m[i] - m[j]) * (m[i] - m[k]) / (m[j] * m[k]);
            s.kind = value > 0 ? stability_kind::stable : stability_kind::unstable;
            s.rate_value = std::sqrt(std::abs(value));
            if (principal.exact_moments) {
                // |Ω| = √(|I_i − I_j| |I_i − I_k| / (I_j I_k)), the differences signed to be
                // positive at the defaults; a square under the root comes out of it.
                const auto positive = [&](const ex& e) {
                    const ex c = canonical_fraction(e, defaults);
                    return *value_at(c, defaults) < 0 ? canonical_fraction(-c, defaults) : c;
                };
                const ex a = positive(Ii - Ij), b = positive(Ii - Ik);
                const bool square_num = (a - b).expand().is_zero(),
                           square_den = (Ij - Ik).expand().is_zero();
                const ex radicand = canonical_fraction(a * b / (Ij * Ik), defaults);
                if (square_num && square_den)
                    s.rate = canonical_fraction(a / Ij, defaults);
                else
                    s.rate = exact_sqrt(radicand);
            } else {
                s.rate = float_numeric(s.rate_value);
            }
        }
        s.stable = s.kind == stability_kind::stable;
    }
    return report;
}

inertia_report analyse_inertia(const matrix3& tensor, const GiNaC::exmap& defaults) {
    inertia_report r;
    r.tensor = tensor;
    r.principal = find_principal_axes(tensor, defaults);
    r.kind = classify(r.principal.moment_values);
    r.stability = stability_report(r.principal, defaults);
    return r;
}

} // namespace rotgen
