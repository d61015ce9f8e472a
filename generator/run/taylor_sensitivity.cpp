#include "run/taylor_sensitivity.hpp"

#include "emit/taylor.hpp"
#include "run/variational.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rotgen {

namespace {

using GiNaC::ex;

// dP/ds of the form parameter `p` by key j where it is known when compiling: a model parameter
// moves (by 1) only with its own key; none moves with all_initial (S(t0) = I, P held).
bool known_forcing(const scene_spec& scene, const form_parameter& p, std::size_t j, double& value) {
    value = 0;
    if (scene.sensitivities.all_initial) return true;
    const std::vector<parameter>& model = scene.model.parameters;
    bool of_model = false;
    for (const auto& m : model)
        of_model = of_model || m.name == p.name;
    if (!of_model) return false; // a cyclic momentum of the reduced form: the start gives it
    const value_key& key = scene.sensitivities.keys.at(j);
    if (key.target == value_key::parameter && model.at(key.index).name == p.name) value = 1;
    return true;
}

} // namespace

augmented_system augmented_rates(const scene_spec& scene, const form_expressions& f) {
    augmented_system a;
    a.n = f.state.size();
    a.keys = scene.sensitivities.all_initial ? a.n : scene.sensitivities.keys.size();
    const std::size_t n = a.n, k = a.keys, np = f.parameters.size();
    for (std::size_t i = 0; i < n; ++i)
        a.inputs.push_back({f.state[i].symbol, f.state[i].name, "y[" + std::to_string(i) + "]"});
    std::vector<ex> S; // S[i k + j] = d y_i/d s_j, the state after y
    for (std::size_t i = 0; i < n * k; ++i) {
        const GiNaC::realsymbol s("sens_" + std::to_string(i / k) + "_" + std::to_string(i % k));
        S.push_back(s);
        a.inputs.push_back({s, "sens_" + std::to_string(i / k) + "_" + std::to_string(i % k),
                            "y[" + std::to_string(n + i) + "]"});
    }
    for (const auto& p : f.parameters)
        a.inputs.push_back({p.symbol, "p." + p.name, "", p.specialisable});
    // dP/ds: numbers where known, else the kernel's inputs d[q]
    a.forcing.compiled.resize(static_cast<Eigen::Index>(np), static_cast<Eigen::Index>(k));
    std::vector<ex> dP(np * k);
    for (std::size_t l = 0; l < np; ++l)
        for (std::size_t j = 0; j < k; ++j) {
            double value = 0;
            double& compiled =
                a.forcing.compiled(static_cast<Eigen::Index>(l), static_cast<Eigen::Index>(j));
            if (known_forcing(scene, f.parameters[l], j, value)) {
                compiled = value;
                dP[l * k + j] = value;
                continue;
            }
            compiled = std::numeric_limits<double>::quiet_NaN();
            const std::string name = "d[" + std::to_string(a.forcing.inputs.size()) + "]";
            const GiNaC::realsymbol d(name);
            dP[l * k + j] = d;
            a.inputs.push_back({d, name, "", true});
            a.forcing.inputs.push_back({l, j});
        }
    a.inputs.push_back({f.time, "t", ""});
    // S' = (d f/d y) S + (d f/d P) dP/ds, the run's variational system (run/variational.hpp)
    a.rates = augmented_rates(variational_system_of(f), S, dP);
    return a;
}

std::string taylor_sensitivity_source(const augmented_system& a, const std::string& unit,
                                      std::size_t parameters) {
    const taylor_body b = print_taylor_body(lower(a.rates, a.inputs));
    std::ostringstream s;
    s << "\n// ---- rotgen run: the Taylor coefficients of (y, S), " << a.n << " + " << a.n << " x "
      << a.keys << " states (run/taylor_sensitivity.hpp) ----\n"
      << "namespace rotgen::models::" << unit << " {\n"
      << "template <class T>\n"
      << "void taylor_sensitivity(T t, T* c, int order, const params<T>& p, const T* d) {\n"
      << "    (void)d;\n"
      << b.text << "\n}\n}\n\n"
      << "extern \"C\" {\n"
      << "unsigned long rotgen_taylor_sensitivity_series() { return " << b.series << "; }\n"
      << "void rotgen_taylor_sensitivity(const double* v, double t, double* c, int order) {\n"
      << "    rg_model::taylor_sensitivity(t, c, order, rg_params(v), v + " << parameters
      << ");\n}\n}\n";
    return s.str();
}

std::vector<double> taylor_sensitivity_values(const augmented_forcing& forcing,
                                              const std::vector<double>& parameters,
                                              const Eigen::MatrixXd& dP) {
    for (Eigen::Index l = 0; l < dP.rows(); ++l)
        for (Eigen::Index j = 0; j < dP.cols(); ++j) {
            const double c = forcing.compiled(l, j);
            if (!std::isnan(c) && dP(l, j) != c)
                throw std::logic_error("taylor: the start's dP/ds differs from the compiled one");
        }
    std::vector<double> v = parameters;
    for (const auto& e : forcing.inputs)
        v.push_back(dP(static_cast<Eigen::Index>(e.parameter), static_cast<Eigen::Index>(e.key)));
    return v;
}

} // namespace rotgen
