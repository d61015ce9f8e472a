// rotgen — inertia/: whether principal moments can belong to a body (§5.4): none negative, and
// each at most the sum of the other two (I1 + I2 >= I3 and permutations; equality is a lamina).
#include "inertia/inertia.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rotgen {

namespace {

std::array<double, 3> ascending(std::array<double, 3> m) {
    std::sort(m.begin(), m.end());
    return m;
}

std::string moments_text(const std::array<double, 3>& m) {
    std::ostringstream os;
    os << "(" << m[0] << ", " << m[1] << ", " << m[2] << ")";
    return os.str();
}

} // namespace

std::string negative_moment_problem(const std::array<double, 3>& moments) {
    const std::array<double, 3> m = ascending(moments);
    const double scale = std::max(std::abs(m[0]), std::abs(m[2]));
    if (m[0] < -1e-12 * scale) return "a principal moment is negative " + moments_text(m);
    return "";
}

std::string triangle_problem(const std::array<double, 3>& moments) {
    const std::array<double, 3> m = ascending(moments);
    // ascending: m0 + m1 >= m2 is the one of the three inequalities that can fail
    if (m[0] + m[1] >= m[2] * (1 - 1e-12)) return "";
    std::ostringstream sum;
    sum << m[0] << " + " << m[1] << " < " << m[2];
    return "principal moments " + moments_text(m) +
           " break the triangle inequality (each at most the sum of the other two): " + sum.str();
}

} // namespace rotgen
