// rotgen — inertia/: the stability of steady, force-free rotation about each principal axis
// (§5.7, 5.90–5.100), and analyse_inertia, everything `rotgen inspect --inertia` shows.
#include "inertia/inertia_detail.hpp"

#include <algorithm>
#include <cmath>

#include "expr/numbers.hpp"

namespace rotgen {

using GiNaC::ex;
using namespace inertia_detail;

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
