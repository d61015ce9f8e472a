// rotgen — inertia/: exact arithmetic for the tensors: values at the defaults, canonical fractions
// and radicals (reproducible printing), exact square roots and quotients, and 3x3 tensor algebra.
#include "inertia/inertia_detail.hpp"

#include <cmath>
#include <stdexcept>

namespace rotgen {

using GiNaC::ex;
using GiNaC::numeric;

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

namespace inertia_detail {

double value_or_throw(const ex& e, const GiNaC::exmap& defaults) {
    const auto v = value_at(e, defaults);
    if (!v)
        throw std::invalid_argument(
            "rotgen inertia: an entry is not a finite real number at the defaults");
    return *v;
}

} // namespace inertia_detail

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

namespace inertia_detail {

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

} // namespace inertia_detail

} // namespace rotgen
