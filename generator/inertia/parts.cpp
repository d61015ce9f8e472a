// rotgen — inertia/: exact rotation matrices (5.8, 5.9, 5.25), the tensor transformation (5.44),
// and the tensor of a body from its parts: central tensors of points, boxes, rods, cylinders and
// spheres, the parallel-axis shift (5.39) and the sum about a pivot or the centre of mass.
#include "inertia/inertia_detail.hpp"

#include <stdexcept>

namespace rotgen {

using GiNaC::ex;
using GiNaC::numeric;
using namespace inertia_detail;

namespace {

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

} // namespace rotgen
