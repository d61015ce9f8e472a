// rotgen — spec/: `inertia:` (three principal moments or a symmetric 3x3 matrix, (5.39) sign
// convention) and the checks every tensor passes, whether given or computed from parts: finite
// and real at the defaults, positive definite, the triangle inequality (model_reader,
// spec_detail.hpp).
#include "spec/spec_detail.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>

namespace rotgen::spec_detail {

void model_reader::read_inertia(const YAML::Node& n) {
    const auto bad = [&] {
        return user_error(at(n), "'inertia' must be three principal moments [I1, I2, I3] or a "
                                 "symmetric 3x3 matrix [[Ixx, Ixy, Ixz], [...], [...]]");
    };
    if (!n.IsSequence() || n.size() != 3) throw bad();
    const bool full = n[0].IsSequence();
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            m_spec.inertia[i][j] = 0;
    if (!full) {
        for (std::size_t i = 0; i < 3; ++i)
            m_spec.inertia[i][i] = expression(n[i], m_names, "inertia");
    } else {
        for (std::size_t i = 0; i < 3; ++i) {
            if (!n[i].IsSequence() || n[i].size() != 3) throw bad();
            for (std::size_t j = 0; j < 3; ++j)
                m_spec.inertia[i][j] = expression(n[i][j], m_names, "inertia");
        }
        for (std::size_t i = 0; i < 3; ++i)
            for (std::size_t j = i + 1; j < 3; ++j)
                if (!(m_spec.inertia[i][j] - m_spec.inertia[j][i]).expand().is_zero())
                    throw user_error(at(n[j][i]), "inertia is not symmetric: entry [" +
                                                      std::to_string(j + 1) + "][" +
                                                      std::to_string(i + 1) + "] differs from [" +
                                                      std::to_string(i + 1) + "][" +
                                                      std::to_string(j + 1) + "]");
    }
    set_diagonal_flag();
    check_physical(n, "inertia");
}

void model_reader::set_diagonal_flag() {
    m_spec.inertia_diagonal = true;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            if (i != j && !m_spec.inertia[i][j].is_zero()) m_spec.inertia_diagonal = false;
}

// With the parameters at their defaults the principal moments must be non-negative and satisfy
// the triangle inequality I1 + I2 >= I3 (and permutations); a moment may be zero only exactly,
// and only one: the linear rotor (flagged in the spec, Example 5.4).
void model_reader::check_physical(const YAML::Node& n, const std::string& what) {
    const GiNaC::exmap defaults = m_spec.parameter_defaults();
    Eigen::Matrix3d I;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // Each entry of `inertia:` and each part's mass and size were checked finite and
            // real; the sums of the tensor may still overflow double (inf, or inf - inf = NaN).
            I(i, j) = double_value(m_spec.inertia[i][j], defaults);
            if (!std::isfinite(I(i, j)))
                throw user_error(at(n), what + " is not finite with the parameters' defaults "
                                               "(too large for double precision)");
        }
    const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
    const double scale = m.cwiseAbs().maxCoeff();
    std::ostringstream moments;
    moments << "(" << m[0] << ", " << m[1] << ", " << m[2] << ")";
    if (const std::string problem = negative_moment_problem({m[0], m[1], m[2]}); !problem.empty())
        throw user_error(at(n), what + " is not physical: " + problem);
    // Zero moments decided exactly (inertia/rotor.cpp), not from the eigensolver's 1e-17.
    const int zeros = exact_zero_moments(m_spec.inertia);
    if (zeros >= 2)
        throw user_error(at(n), what + " has every principal moment zero " + moments.str() +
                                    ": a point at the fixed point has no rotation to describe");
    if (zeros == 1) { // with the triangle inequality above: I1 = 0, I2 = I3
        m_spec.rotor = true;
        m_spec.rotor_where = at(n);
        return;
    }
    if (!(scale > 0) || m[0] <= 1e-14 * scale)
        throw user_error(at(n), what + " has a principal moment that is zero to double precision " +
                                    moments.str() +
                                    " but not exactly; a body on a line (a linear rotor, Example "
                                    "5.4) has I1 = 0 exactly: give its moments exactly");
    // m ascending: m0 + m1 >= m2 is the one of the three inequalities that can fail; equality
    // is the planar limit (a lamina: I3 = I1 + I2, the perpendicular-axis theorem).
    if (const std::string problem = triangle_problem({m[0], m[1], m[2]}); !problem.empty())
        throw user_error(at(n), what + " is not physical: " + problem);
}

} // namespace rotgen::spec_detail
