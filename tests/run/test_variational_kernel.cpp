// The compiled variational kernel of a run with sensitivities (run/variational.hpp): f and
// S' = (d f/d y) S + (d f/d P) D lowered together, against the same form's compiled rhs and
// Jacobian and d f/d P evaluated by GiNaC, multiplied out at run time, at one point with random S
// and D, in every form.
#include "support.hpp"

#include "expr/numbers.hpp"
#include "run/prepared.hpp"
#include "run/sensitivity_start.hpp"
#include "run/variational.hpp"
#include "scene/scene.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <string>
#include <vector>

using namespace rotgen;

namespace {

using row_major = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// d f/d P of the form at (t, y, p), by GiNaC: its derivatives evaluated at 30 digits, not lowered
// (at 17 the full tensor's long expressions round to 2e-12).
row_major parameter_jacobian_at(const form_expressions& f, double t, const Eigen::VectorXd& y,
                                const std::vector<double>& p) {
    const scoped_digits digits(30);
    GiNaC::exmap at;
    for (std::size_t i = 0; i < f.state.size(); ++i)
        at[f.state[i].symbol] = GiNaC::numeric(y[static_cast<Eigen::Index>(i)]);
    for (std::size_t i = 0; i < f.parameters.size(); ++i)
        at[f.parameters[i].symbol] = GiNaC::numeric(p[i]);
    at[f.time] = GiNaC::numeric(t);
    const std::vector<GiNaC::ex> dfdp = variational_system_of(f).dfdp;
    const auto n = static_cast<Eigen::Index>(f.state.size()),
               np = static_cast<Eigen::Index>(f.parameters.size());
    row_major F(n, np);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index m = 0; m < np; ++m)
            F(i, m) = GiNaC::ex_to<GiNaC::numeric>(
                          GiNaC::evalf(dfdp[static_cast<std::size_t>(i * np + m)].subs(
                              at, GiNaC::subs_options::no_pattern)))
                          .to_double();
    return F;
}

// The largest difference, relative to max(|value|, 1), between rotgen_variational's (f, S') and
// (f, J S + F D) from the form's other kernels, at y = 0.3 ... 1.1, S and D Eigen's Random.
double worst_against_product(const std::string& name, const std::string& text) {
    const test::scratch_file file("variational_" + name + ".yaml", text);
    const scene_spec scene = load_scene(file.path);
    stage_timings timings;
    const prepared_scene prepared(scene, timings);
    bool cached = false;
    const compiled_form& cf = prepared.compiled(scene.form, timings, &cached);
    REQUIRE(cf.variational != nullptr);
    const auto n = static_cast<Eigen::Index>(cf.f.state.size()),
               np = static_cast<Eigen::Index>(cf.f.parameters.size()),
               k = static_cast<Eigen::Index>(sensitivity_key_names(scene, cf.f).size());
    std::vector<double> p;
    for (Eigen::Index i = 0; i < np; ++i)
        p.push_back(0.8 + 0.1 * double(i));
    const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(n, 0.3, 1.1);
    const row_major S = row_major::Random(n, k), D = row_major::Random(np, k);
    std::vector<double> v = p; // the parameters, then D row-major
    v.insert(v.end(), D.data(), D.data() + D.size());
    Eigen::VectorXd augmented(n + n * k), out(n + n * k), f(n);
    augmented << y, Eigen::Map<const Eigen::VectorXd>(S.data(), n * k);
    const double t = 0.4;
    cf.variational(v.data(), t, augmented.data(), out.data());
    const loaded_system sys = cf.system(p);
    row_major J(n, n);
    sys.rhs(t, y.data(), f.data());
    sys.jacobian(t, y.data(), J.data());
    const row_major F = parameter_jacobian_at(cf.f, t, y, p);
    const row_major product = J * S + F * D;
    Eigen::VectorXd expected(n + n * k);
    expected << f, Eigen::Map<const Eigen::VectorXd>(product.data(), n * k);
    return ((out - expected).cwiseAbs().array() / expected.cwiseAbs().array().max(1.0)).maxCoeff();
}

std::string scene_text(const std::string& model, const std::string& form,
                       const std::string& initial, const std::string& keys) {
    return "model: " + test::model_path(model) + "\nform: " + form + "\ninitial: {" + initial +
           "}\ntime: {start: 0, end: 1, samples: 2}\n"
           "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\nswitch_chart: false\n"
           "sensitivities: [" +
           keys + "]\n";
}

} // namespace

TEST_CASE("the compiled variational kernel equals the Jacobian times S plus the parameter "
          "Jacobian times dP/ds in every form",
          "[sensitivities]") {
    const std::string top = "phi: 0, theta: 0.5, psi: 0, phi_dot: 0.3, theta_dot: 0.1, psi_dot: 5";
    const std::string all = "initial.phi, initial.theta, initial.psi, initial.phi_dot, "
                            "initial.theta_dot, initial.psi_dot, parameters.I1, parameters.I3, "
                            "parameters.M, parameters.g, parameters.h";
    // the bound about 10x the error observed (in the comment)
    const auto [name, model, form, initial, keys, bound] = GENERATE_COPY(
        table<std::string, std::string, std::string, std::string, std::string, double>(
            {{"lagrangian", "heavy_top", "lagrangian", top, all, 1e-14}, // 1.1e-15
             {"reduced", "heavy_top", "reduced", top,
              "initial.theta, initial.psi_dot, parameters.h", 2e-14},                   // 2.5e-15
             {"body", "heavy_top", "body", top, "initial.theta, parameters.I3", 2e-15}, // 2.2e-16
             {"hamiltonian", "heavy_top", "hamiltonian", top, "parameters.h", 6e-15},   // 5.7e-16
             {"tensor", "full_tensor_top", "lagrangian",
              "phi: 0.2, theta: 0.8, psi: -0.4, omega1: 0.5, omega2: -0.3, omega3: 4",
              "initial.psi, initial.omega1, parameters.Ixy, parameters.cz, parameters.Izz",
              2e-11}})); // 1.9e-12: the lowered kernel's rounding of the tensor's long expressions
    CAPTURE(name);
    const double worst = worst_against_product(name, scene_text(model, form, initial, keys));
    CAPTURE(worst);
    CHECK(worst < bound);
}
