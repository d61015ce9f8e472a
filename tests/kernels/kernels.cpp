#include "kernels.hpp"

#include "units.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace rotgen_test {

namespace {

template <class Array> std::vector<std::string> strings(const Array& a) {
    return std::vector<std::string>(a.begin(), a.end());
}

template <class P, std::size_t... I>
P make_params(const std::vector<double>& v, std::index_sequence<I...>) {
    return P{v.at(I)...};
}

template <class P, std::size_t... I>
P make_params_long(const std::vector<double>& v, std::index_sequence<I...>) {
    return P{static_cast<long double>(v.at(I))...};
}

// What every unit has: sizes, names, rhs, jacobian, rhs_and_jacobian, energy, momenta. A generic
// lambda `make(p)` builds the kernel for parameters p.
#define ROTGEN_KERNEL(u, K, EXTRA)                                                                 \
    {                                                                                              \
        namespace ns = rotgen::models::u;                                                          \
        const auto make = [](auto self, const ns::params<double>& p,                               \
                             const ns::params<long double>& pl) -> kernel {                        \
            kernel k;                                                                              \
            k.unit = #u;                                                                           \
            k.kind = K;                                                                            \
            k.n = ns::state_size;                                                                  \
            k.state_names = strings(ns::state_names);                                              \
            k.parameter_names = strings(ns::parameter_names);                                      \
            k.pattern.assign(ns::jacobian_pattern.begin(), ns::jacobian_pattern.end());            \
            /* rhs and jacobian with the prepared parameters (the hoisted constants), the */       \
            /* long double ones and rhs_and_jacobian given params<T> (prepared at each call) */    \
            k.rhs = [q = ns::prepare(p)](double t, const double* y, double* f) {                   \
                ns::rhs(t, y, f, q);                                                               \
            };                                                                                     \
            k.rhs_long = [pl](long double t, const long double* y, long double* f) {               \
                ns::rhs(t, y, f, pl);                                                              \
            };                                                                                     \
            k.jacobian = [q = ns::prepare(p)](double t, const double* y, double* J) {              \
                ns::jacobian(t, y, J, q);                                                          \
            };                                                                                     \
            k.jacobian_long = [pl](long double t, const long double* y, long double* J) {          \
                ns::jacobian(t, y, J, pl);                                                         \
            };                                                                                     \
            k.rhs_and_jacobian = [p](double t, const double* y, double* f, double* J) {            \
                ns::rhs_and_jacobian(t, y, f, J, p);                                               \
            };                                                                                     \
            k.energy = [p](const double* y) { return ns::energy(y, p); };                          \
            k.momenta = [p](const double* y, double* o) { ns::momenta(y, o, p); };                 \
            k.taylor = [p](double t, double* c, int order) { ns::taylor(t, c, order, p); };        \
            k.taylor_series = ns::taylor_series;                                                   \
            EXTRA                                                                                  \
            k.with_parameters = [self](const std::vector<double>& v) {                             \
                return self(self,                                                                  \
                            make_params<ns::params<double>>(                                       \
                                v, std::make_index_sequence<ns::parameter_count>{}),               \
                            make_params_long<ns::params<long double>>(                             \
                                v, std::make_index_sequence<ns::parameter_count>{}));              \
            };                                                                                     \
            return k;                                                                              \
        };                                                                                         \
        v.push_back(make(make, ns::params<double>{}, ns::params<long double>{}));                  \
    }

#define ROTGEN_EXTRA_FULL                                                                          \
    k.omega = [p](const double* y, double* o) { ns::omega(y, o, p); };                             \
    k.rotation = [p](const double* y, double* o) { ns::rotation(y, o, p); };                       \
    k.mass_matrix = [p](const double* y, double* o) { ns::mass_matrix(y, o, p); };
#define ROTGEN_EXTRA_BODY                                                                          \
    ROTGEN_EXTRA_FULL                                                                              \
    k.quaternion_from_angles = [](const double* a, double* q) {                                    \
        ns::quaternion_from_angles(a, q);                                                          \
    };                                                                                             \
    k.angles_from_quaternion = [](const double* q, double* a) { ns::angles_from_quaternion(q, a); };
#define ROTGEN_EXTRA_BODY_OMEGA                                                                    \
    k.omega = [p](const double* y, double* o) { ns::omega(y, o, p); };                             \
    k.mass_matrix = [p](const double* y, double* o) { ns::mass_matrix(y, o, p); };
#define ROTGEN_EXTRA_REDUCED                                                                       \
    k.ignored_rates = [p](const double* y, double* o) { ns::ignored_rates(y, o, p); };

#define ROTGEN_KERNEL_LAGRANGIAN(u) ROTGEN_KERNEL(u, form::lagrangian, ROTGEN_EXTRA_FULL)
#define ROTGEN_KERNEL_HAMILTONIAN(u) ROTGEN_KERNEL(u, form::hamiltonian, ROTGEN_EXTRA_FULL)
#define ROTGEN_KERNEL_BODY(u) ROTGEN_KERNEL(u, form::body, ROTGEN_EXTRA_BODY)
#define ROTGEN_KERNEL_BODY_OMEGA(u) ROTGEN_KERNEL(u, form::body_omega, ROTGEN_EXTRA_BODY_OMEGA)
#define ROTGEN_KERNEL_REDUCED(u) ROTGEN_KERNEL(u, form::reduced, ROTGEN_EXTRA_REDUCED)

std::vector<kernel> make_kernels() {
    std::vector<kernel> v;
    ROTGEN_UNITS_LAGRANGIAN(ROTGEN_KERNEL_LAGRANGIAN)
    ROTGEN_UNITS_HAMILTONIAN(ROTGEN_KERNEL_HAMILTONIAN)
    ROTGEN_UNITS_REDUCED(ROTGEN_KERNEL_REDUCED)
    ROTGEN_UNITS_BODY(ROTGEN_KERNEL_BODY)
    ROTGEN_UNITS_BODY_OMEGA(ROTGEN_KERNEL_BODY_OMEGA)
    return v;
}

} // namespace

const std::vector<kernel>& kernels() {
    static const std::vector<kernel> v = make_kernels();
    return v;
}

const kernel& find_kernel(const std::string& unit) {
    for (const kernel& k : kernels())
        if (k.unit == unit) return k;
    throw std::runtime_error("no generated unit " + unit);
}

std::vector<double> random_state(const kernel& k, std::mt19937& rng, double theta_min) {
    const double pi = 3.141592653589793;
    // z-y-x models (satellite_zyx: yaw, pitch, roll) have the middle angle in [-pi/2, pi/2],
    // singular at its ends; the others are the chapter's z-x-z with theta in [0, pi]
    const bool tait_bryan = k.unit.find("_zyx") != std::string::npos;
    const double shift = tait_bryan ? -pi / 2 : 0;
    std::uniform_real_distribution<double> angle(0, 2 * pi),
        polar(theta_min + shift, pi - theta_min + shift), rate(-2, 2), norm(0.5, 2);
    std::normal_distribution<double> gauss;
    std::vector<double> y(k.n);
    double q2 = 0;
    for (std::size_t i = 0; i < k.n; ++i) {
        const std::string& s = k.state_names[i];
        if (s == "theta" || s == "pitch")
            y[i] = polar(rng);
        else if (s == "phi" || s == "psi" || s == "yaw" || s == "roll")
            y[i] = angle(rng);
        else if (s == "qw" || s == "qx" || s == "qy" || s == "qz")
            q2 += (y[i] = gauss(rng)) * y[i];
        else
            y[i] = rate(rng);
    }
    if (q2 > 0) {
        // a random orientation with theta in range (the body form has no singularity, but a chart-
        // derived torque, e.g. damping of Euler-angle rates, has one at theta = 0, pi), of any norm
        const double angles[3] = {angle(rng), polar(rng), angle(rng)};
        k.quaternion_from_angles(angles, y.data());
        const double scale = norm(rng);
        for (std::size_t i = 0; i < 4; ++i)
            y[i] *= scale;
    }
    return y;
}

} // namespace rotgen_test
