#include "support/template.hpp"

#include <stdexcept>

namespace rotgen {

std::string fill_placeholders(const std::string& in,
                              const std::map<std::string, std::string>& values,
                              const std::string& name, placeholders mode) {
    const bool strict = mode == placeholders::all_required;
    std::string out;
    std::size_t i = 0;
    while (i < in.size()) {
        const std::size_t at = in.find('@', i);
        if (at == std::string::npos) break;
        const std::size_t end = in.find('@', at + 1);
        if (end == std::string::npos && strict)
            throw std::logic_error("template " + name + ": unterminated placeholder");
        const auto v =
            end == std::string::npos ? values.end() : values.find(in.substr(at + 1, end - at - 1));
        if (v == values.end()) {
            if (strict)
                throw std::logic_error("template " + name + " needs a value for @" +
                                       in.substr(at + 1, end - at - 1) + "@");
            out += in.substr(i, at + 1 - i); // not a placeholder: keep the '@'
            i = at + 1;
            continue;
        }
        out += in.substr(i, at - i) + v->second;
        i = end + 1;
    }
    out += in.substr(i);
    return out;
}

} // namespace rotgen
