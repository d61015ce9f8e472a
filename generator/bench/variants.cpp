// rotgen bench: choosing the variants of a scene's equations.
#include "bench/variants.hpp"

#include "expr/print.hpp"
#include "support/error.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace rotgen::bench {

namespace {

// Builds the variants one by one, refusing those the model or the initial state cannot give and
// duplicates of a label already there.
struct variant_builder {
    const model_spec& spec;
    const derivation& d;
    bool euler_usable;
    std::vector<variant> variants;
    std::string refusal; // why the last form could not be built

    bool add(form_kind form, lagrangian_strategy strategy, bool quaternion, role r,
             bool specialised, bool lowered) {
        variant v;
        v.form = form;
        v.strategy = strategy;
        v.r = r;
        v.specialised = specialised;
        v.lowered = lowered;
        try {
            v.f = build_form(spec, d, form, strategy, quaternion);
        } catch (const user_error& e) {
            refusal = e.problem();
            return false; // no such form for this model (e.g. reduced without cyclic coordinates)
        }
        v.quaternion = form == form_kind::body && v.f.state.size() == 7;
        if (form == form_kind::body && quaternion != v.quaternion) return false;
        if (form != form_kind::body && !euler_usable) return false;
        v.label = form_label(form, strategy, v.quaternion) + (specialised ? "" : "+runtime") +
                  (lowered ? "" : "+unlowered");
        for (const auto& existing : variants)
            if (existing.label == v.label) return false;
        v.unit = "wp" + std::to_string(variants.size()) + "_" + spec.name;
        v.outputs = {"rhs", "jacobian"};
        for (const char* o : {"energy", "momenta", "omega", "rotation", "ignored_rates"})
            if (v.f.outputs.count(o)) v.outputs.push_back(o);
        v.has_A = v.f.outputs.count("rotation") > 0;
        v.has_energy = v.f.outputs.count("energy") > 0;
        variants.push_back(std::move(v));
        return true;
    }
};

// The main variant (the scene's form, as `simulate` runs it), then its +runtime and +unlowered.
void add_main(variant_builder& b, form_kind form, bool orientation, const scene_spec& scene) {
    const auto strategy = lagrangian_strategy::explicit_inverse;
    if (!b.add(form, strategy, orientation, role::main, true, true))
        if (!b.add(form, strategy, true, role::main, true, true))
            throw user_error(scene.where, "the scene's form cannot be benchmarked: " + b.refusal);
    b.variants[0].implicit_runs = true;
    const form_kind main_form = b.variants[0].form;
    const bool main_quat = b.variants[0].quaternion;
    b.add(main_form, strategy, main_quat, role::runtime, false, true);
    b.add(main_form, strategy, main_quat, role::unlowered, true, false);
}

// The other forms (the first only with --quick, and body:quaternion for the split methods).
void add_alternatives(variant_builder& b, bool quick, bool split_form) {
    struct alt {
        form_kind form;
        lagrangian_strategy strategy;
        bool quaternion;
    };
    std::vector<alt> alts = {{form_kind::lagrangian, lagrangian_strategy::explicit_inverse, false},
                             {form_kind::lagrangian, lagrangian_strategy::solve, false},
                             {form_kind::hamiltonian, lagrangian_strategy::explicit_inverse, false},
                             {form_kind::reduced, lagrangian_strategy::explicit_inverse, false},
                             {form_kind::body, lagrangian_strategy::explicit_inverse, true},
                             {form_kind::body, lagrangian_strategy::explicit_inverse, false}};
    if (quick) {
        const alt body_quaternion = alts[4];
        alts.resize(1);
        if (split_form) alts.push_back(body_quaternion);
    }
    for (const auto& a : alts)
        if (b.add(a.form, a.strategy, a.quaternion, role::alternative, true, true))
            b.variants.back().implicit_runs = true;
}

// The unlowered variants' text; a variant is dropped when its text would be unreasonably long.
void print_unlowered(std::vector<variant>& variants) {
    for (auto& v : variants) {
        if (v.lowered) continue;
        GiNaC::exmap folded;
        for (const auto& p : v.f.parameters)
            if (p.specialisable) folded[p.symbol] = exact_decimal(p.value);
        v.naive = naive_rhs(v, folded);
    }
    variants.erase(
        std::remove_if(variants.begin(), variants.end(),
                       [](const variant& v) { return !v.lowered && v.naive.size() > 400000; }),
        variants.end());
}

// The long runs' variant: the Hamiltonian form (canonical: the midpoint rule is symplectic there).
std::optional<std::size_t> hamiltonian_variant(const std::vector<variant>& variants) {
    std::optional<std::size_t> h;
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i].form == form_kind::hamiltonian && variants[i].r != role::runtime &&
            variants[i].lowered)
            h = i;
    return h;
}

} // namespace

std::string form_label(form_kind form, lagrangian_strategy strategy, bool quaternion) {
    switch (form) {
    case form_kind::lagrangian:
        return strategy == lagrangian_strategy::solve ? "lagrangian:solve" : "lagrangian:explicit";
    case form_kind::hamiltonian:
        return "hamiltonian";
    case form_kind::reduced:
        return "reduced";
    case form_kind::body:
        return quaternion ? "body:quaternion" : "body:omega";
    case form_kind::rotor:
    case form_kind::rotor_x:
        return to_string(form);
    }
    return "";
}

variant_set choose_variants(const scene_spec& scene, const model_spec& spec, const derivation& d,
                            bool euler_usable, bool orientation, bool quick, bool split_form) {
    variant_builder b{spec, d, euler_usable, {}, {}};
    add_main(b, scene.form, orientation, scene);
    add_alternatives(b, quick, split_form);
    print_unlowered(b.variants);
    variant_set set;
    set.variants = std::move(b.variants);
    set.hamiltonian = hamiltonian_variant(set.variants);
    return set;
}

std::optional<std::size_t> split_variant(const std::vector<variant>& variants) {
    for (std::size_t i = 0; i < variants.size(); ++i) {
        const variant& v = variants[i];
        if (v.form == form_kind::body && v.quaternion && v.specialised && v.lowered) return i;
    }
    return std::nullopt;
}

std::string naive_rhs(const variant& v, const GiNaC::exmap& folded) {
    std::ostringstream os;
    os << "namespace rotgen {\nnamespace models {\nnamespace " << v.unit << "_naive {\n"
       << "// The rates printed expression by expression: no common subexpressions shared, no\n"
       << "// trigonometry hoisted (the `+unlowered` variant of the work-precision bench).\n"
       << "template <class T>\nvoid rhs(T t, const T* y, T* dydt, const " << v.unit
       << "::params<T>& p) {\n"
       << "    using std::sin; using std::cos; using std::tan; using std::sqrt; using std::pow;\n"
       << "    using std::exp; using std::log; using std::abs; using std::atan2; using std::asin;\n"
       << "    using std::acos; using std::atan; using std::sinh; using std::cosh; using "
          "std::tanh;\n"
       << "    (void)t; (void)y; (void)p;\n"
       << print_rhs_inline(v.f, folded, "T") << "}\n} // namespace " << v.unit
       << "_naive\n} // namespace models\n} // namespace rotgen\n";
    return os.str();
}

} // namespace rotgen::bench
