// Fuzz target 1: the expression language (generator/expr_parse.cpp) on raw bytes.
// The name table is that of a torque: the angles, their rates, t, and a few parameters.
// An accepted expression is also evaluated in double precision (as spec.cpp checks it): any value
// will do, but the expression must consist of what the generated code knows (fuzz_support.hpp).
#include "expr/angles.hpp"
#include "expr/expr_parse.hpp"
#include "fuzz_support.hpp"

using namespace rotgen;

namespace {
const name_table& names() {
    static const name_table table = [] {
        name_table t;
        const auto& s = symbols();
        for (int i = 0; i < 3; ++i) {
            t[angle_convention{}.names[i]] = s.q[i];
            t[angle_convention{}.names[i] + "_dot"] = s.qd[i];
        }
        t["t"] = s.t;
        for (const char* p : {"I1", "I2", "I3", "M", "g", "h", "a", "b", "c", "w"})
            t[p] = GiNaC::realsymbol(p);
        return t;
    }();
    return table;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    fuzz::expect_result_or_user_error([&] {
        const GiNaC::ex e = parse_expression(text, names(), {"fuzz.yaml", 3, 12}, "torque");
        GiNaC::exmap at = fuzz::generic_state();
        int k = 0;
        for (const auto& kv : names())
            if (!at.count(kv.second)) at[kv.second] = 0.25 + 0.5 * k++;
        (void)fuzz::double_value(e, at); // any value (NaN, inf) is fine; a crash or hang is not
    });
    return 0;
}
