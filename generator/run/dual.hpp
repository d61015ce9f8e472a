// rotgen — forward-mode derivatives of the columns a run computes at each sample rather than in
// its generated record program (run/kernels.hpp: the body form's Euler angles, their rates and
// momenta recovered from the quaternion; the attitude quaternion of the Euler-angle forms and of
// the body form, scalar part >= 0). A dual number carries a value and its derivatives along k
// directions (the sensitivity keys); evaluating the record's own code on duals is the chain rule
// through that code exactly, the branch it takes included (the sign flip q0 >= 0, the angles'
// wrap into [0, 2 pi), the choice of the well-conditioned formula). Not a finite difference.
//
// Only what that code uses is defined: + - * /, sin, cos, sqrt, atan2, hypot, fmod, abs and the
// comparisons (on the values). An empty derivative vector is a constant.
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <limits>

namespace rotgen {

struct dual {
    double v = 0;
    Eigen::VectorXd d; // the derivatives, one per direction; empty: a constant

    dual() = default;
    dual(double value) : v(value) {} // NOLINT: a constant where a double is written
    dual(double value, Eigen::VectorXd derivatives) : v(value), d(std::move(derivatives)) {}

    // a d + b e of two derivative vectors (either may be empty)
    static Eigen::VectorXd combine(double a, const Eigen::VectorXd& d, double b,
                                   const Eigen::VectorXd& e) {
        if (d.size() == 0) return e.size() == 0 ? Eigen::VectorXd() : Eigen::VectorXd(b * e);
        if (e.size() == 0) return a * d;
        return a * d + b * e;
    }
    // f(v) with f' = slope: the chain rule
    dual chain(double value, double slope) const {
        return {value, d.size() == 0 ? Eigen::VectorXd() : Eigen::VectorXd(slope * d)};
    }

    dual& operator+=(const dual& o) { return *this = *this + o; }
    dual& operator-=(const dual& o) { return *this = *this - o; }
    dual& operator*=(const dual& o) { return *this = *this * o; }
    dual& operator/=(const dual& o) { return *this = *this / o; }
    friend dual operator+(const dual& a, const dual& b) {
        return {a.v + b.v, combine(1, a.d, 1, b.d)};
    }
    friend dual operator-(const dual& a, const dual& b) {
        return {a.v - b.v, combine(1, a.d, -1, b.d)};
    }
    friend dual operator-(const dual& a) { return a.chain(-a.v, -1); }
    friend dual operator*(const dual& a, const dual& b) { // (ab)' = b a' + a b'
        return {a.v * b.v, combine(b.v, a.d, a.v, b.d)};
    }
    friend dual operator/(const dual& a, const dual& b) { // (a/b)' = a'/b - a b'/b^2
        return {a.v / b.v, combine(1 / b.v, a.d, -a.v / (b.v * b.v), b.d)};
    }
    friend bool operator<(const dual& a, const dual& b) { return a.v < b.v; }
    friend bool operator>(const dual& a, const dual& b) { return a.v > b.v; }
    friend bool operator<=(const dual& a, const dual& b) { return a.v <= b.v; }
    friend bool operator>=(const dual& a, const dual& b) { return a.v >= b.v; }
    friend bool operator==(const dual& a, const dual& b) { return a.v == b.v; }
    friend bool operator!=(const dual& a, const dual& b) { return a.v != b.v; }
};

inline dual sin(const dual& a) {
    return a.chain(std::sin(a.v), std::cos(a.v));
}
inline dual cos(const dual& a) {
    return a.chain(std::cos(a.v), -std::sin(a.v));
}
inline dual sqrt(const dual& a) {
    const double s = std::sqrt(a.v);
    return a.chain(s, 0.5 / s);
}
inline dual abs(const dual& a) {
    return a.chain(std::abs(a.v), a.v < 0 ? -1.0 : 1.0);
}
// the wrap moves the value by a constant: the derivative is a's
inline dual fmod(const dual& a, const dual& b) {
    return {std::fmod(a.v, b.v), a.d};
}
// d atan2(y, x) = (x dy - y dx) / (x^2 + y^2)
inline dual atan2(const dual& y, const dual& x) {
    const double r2 = x.v * x.v + y.v * y.v;
    return {std::atan2(y.v, x.v), dual::combine(x.v / r2, y.d, -y.v / r2, x.d)};
}
// d hypot(a, b) = (a da + b db) / hypot(a, b)
inline dual hypot(const dual& a, const dual& b) {
    const double h = std::hypot(a.v, b.v);
    return {h, dual::combine(a.v / h, a.d, b.v / h, b.d)};
}

} // namespace rotgen

namespace Eigen {
template <> struct NumTraits<rotgen::dual> : NumTraits<double> {
    using Real = rotgen::dual;
    using NonInteger = rotgen::dual;
    using Literal = rotgen::dual;
    using Nested = rotgen::dual;
    enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1 };
    enum { ReadCost = 1, AddCost = 3, MulCost = 3 };
};
} // namespace Eigen

template <> struct std::numeric_limits<rotgen::dual> : std::numeric_limits<double> {
    static rotgen::dual epsilon() { return std::numeric_limits<double>::epsilon(); }
};
