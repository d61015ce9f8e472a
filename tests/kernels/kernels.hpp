// The generated kernels under test, behind one interface (double; rhs and jacobian also in long
// double).
// kernels.cpp fills the table from generated/units.hpp (written by tests/kernels/CMakeLists.txt).
#pragma once

#include <cstddef>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace rotgen_test {

enum class form { lagrangian, hamiltonian, reduced, body, body_omega };

struct kernel {
    std::string unit;
    form kind = form::lagrangian;
    std::size_t n = 0;
    std::vector<std::string> state_names, parameter_names;
    std::vector<unsigned char> pattern; // jacobian_pattern
    std::function<void(double, const double*, double*)> rhs, jacobian;
    std::function<void(double, const double*, double*, double*)> rhs_and_jacobian;
    std::function<void(long double, const long double*, long double*)> rhs_long, jacobian_long;
    std::function<double(const double*)> energy;
    // empty where the unit has no such function
    std::function<void(const double*, double*)> momenta, omega, rotation, mass_matrix,
        ignored_rates;
    std::function<void(const double*, double*)> quaternion_from_angles, angles_from_quaternion;
    // taylor(t, c, order): the Taylor coefficients (c: taylor_series blocks of order + 1)
    std::function<void(double, double*, int)> taylor;
    std::size_t taylor_series = 0;
    // The same kernel with other parameter values (in parameter_names order).
    std::function<kernel(const std::vector<double>&)> with_parameters;
};

const std::vector<kernel>& kernels();
const kernel& find_kernel(const std::string& unit);

// A random state for the kernel's layout: theta in [theta_min, pi - theta_min], phi and psi in
// [0, 2 pi), rates and momenta in [-2, 2], a quaternion of random direction and norm in [0.5, 2].
std::vector<double> random_state(const kernel& k, std::mt19937& rng, double theta_min = 0.3);

} // namespace rotgen_test
