// rotgen — emission of the sensitivity kernels (emit/sensitivities.hpp).
#include "emit/sensitivities.hpp"

namespace rotgen {

namespace {

std::string join(const std::vector<std::string>& v, const std::string& sep) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i)
        s += (i ? sep : "") + v[i];
    return s;
}

std::string local(const std::string& name, std::size_t i, std::size_t j) {
    return name + "_" + std::to_string(i) + "_" + std::to_string(j);
}

} // namespace

variational_product variational_product_lines(const lowered_form& lf, const std::string& scalar) {
    const std::size_t n = lf.state_names.size(), k = lf.sensitivity_names.size(), w = n + k;
    variational_product r;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < w; ++c) {
            std::vector<std::string> terms;
            for (std::size_t m = 0; m < n; ++m) {
                const std::string s = "S[" + std::to_string(m * w + c) + "]";
                if (lf.sensitivity_dfdy_one[i * n + m]) {
                    terms.push_back(s);
                } else if (!lf.sensitivity_dfdy_zero[i * n + m]) {
                    terms.push_back(local("dfdy", i, m) + " * " + s);
                    ++r.operations.mul;
                }
            }
            if (c >= n && !lf.sensitivity_dfdp_zero[i * k + (c - n)])
                terms.push_back(local("dfdp", i, c - n));
            if (!terms.empty()) r.operations.add += terms.size() - 1;
            r.lines.push_back("    dSdt[" + std::to_string(i * w + c) + "] = " +
                              (terms.empty() ? "T(" + scalar + "(0))" : join(terms, " + ")) + ";");
        }
    return r;
}

std::map<std::string, std::string> sensitivity_values(const lowered_form& lf) {
    const std::size_t n = lf.state_names.size(), k = lf.sensitivity_names.size();
    std::vector<std::string> quoted;
    for (const auto& s : lf.sensitivity_names)
        quoted.push_back("\"" + s + "\"");
    return {{"k", std::to_string(k)},
            {"nk", std::to_string(n + k)},
            {"keys", join(lf.sensitivity_names, ", ")},
            {"key_names", join(quoted, ", ")}};
}

} // namespace rotgen
