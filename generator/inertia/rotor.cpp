// rotgen — inertia/: exactly zero principal moments, and the linear rotor (Example 5.4, §5.5).
//
// A body on a line (two point masses on a massless rod: the chapter's dumbbell, Example 5.4, or a
// diatomic molecule) has I1 = 0 along the line and I2 = I3 across it. Computed numerically the zero
// comes out as 1e-17 and cannot be told from a very thin body; here it is decided exactly from the
// characteristic polynomial of the exact tensor (5.60–5.62),
//     det(I − λ1) = −(λ³ − c1 λ² + c2 λ − c3),
//     c1 = tr I,  c2 = Σ of the principal 2x2 minors,  c3 = det I,
// whose roots are the principal moments: c3 = 0 ⇔ a moment is 0; c2 = c3 = 0 ⇔ two are (λ² | the
// polynomial). With non-negative moments obeying the triangle inequality one zero moment forces
// the other two to be equal, I2 = I3 = c1/2: the rotor.
#include "inertia/inertia_detail.hpp"

namespace rotgen {

using GiNaC::ex;

namespace {

// e with sin(x)² written 1 − cos(x)² (parts turned by a parameter's angle give sin² + cos²),
// expanded and normalised: zero exactly when e is identically zero in the parameters (for the
// trigonometric identities only through sin² + cos² = 1).
ex simplified(const ex& e) {
    const ex x = GiNaC::wild(0);
    const ex once =
        e.expand().subs(GiNaC::pow(GiNaC::sin(x), 2) == 1 - GiNaC::pow(GiNaC::cos(x), 2),
                        GiNaC::subs_options::algebraic);
    return GiNaC::normal(once.expand());
}

struct invariants {
    ex c1, c2, c3;
};

invariants tensor_invariants(const matrix3& t) {
    invariants v;
    v.c1 = t[0][0] + t[1][1] + t[2][2];
    v.c2 = t[0][0] * t[1][1] - t[0][1] * t[1][0] + t[0][0] * t[2][2] - t[0][2] * t[2][0] +
           t[1][1] * t[2][2] - t[1][2] * t[2][1];
    v.c3 = t[0][0] * (t[1][1] * t[2][2] - t[1][2] * t[2][1]) -
           t[0][1] * (t[1][0] * t[2][2] - t[1][2] * t[2][0]) +
           t[0][2] * (t[1][0] * t[2][1] - t[1][1] * t[2][0]);
    return v;
}

} // namespace

int exact_zero_moments(const matrix3& tensor) {
    const invariants v = tensor_invariants(tensor);
    if (!simplified(v.c3).is_zero()) return 0;
    if (!simplified(v.c2).is_zero()) return 1;
    return simplified(v.c1).is_zero() ? 3 : 2;
}

std::optional<GiNaC::ex> exact_rotor_moment(const matrix3& tensor) {
    if (exact_zero_moments(tensor) != 1) return std::nullopt;
    return simplified(tensor_invariants(tensor).c1 / 2);
}

// On the line: I c = 0 (the line is the kernel of a rotor's tensor, its zero moment's axis);
// then d = sqrt(c . c).
std::optional<GiNaC::ex> rotor_arm(const matrix3& tensor, const vector3& c) {
    for (int i = 0; i < 3; ++i)
        if (!simplified(tensor[i][0] * c[0] + tensor[i][1] * c[1] + tensor[i][2] * c[2]).is_zero())
            return std::nullopt;
    const ex d2 = simplified(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    return d2.is_zero() ? ex(0) : GiNaC::sqrt(d2);
}

} // namespace rotgen
