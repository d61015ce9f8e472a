#include "run/provenance.hpp"

#include "support/hash.hpp"

#include <sstream>

namespace rotgen {

csv_provenance provenance_of(const model_spec& model, form_kind form) {
    return {ROTGEN_VERSION, model.name, sha256_hex(model.source), to_string(form)};
}

std::string provenance_line(const csv_provenance& p) {
    return "# rotgen " + p.version + " model " + p.model + " sha256 " + p.sha256 + " form " +
           p.form;
}

std::optional<csv_provenance> parse_provenance(const std::string& line) {
    std::istringstream in(!line.empty() && line.back() == '\r' ? line.substr(0, line.size() - 1)
                                                               : line);
    std::string hash_mark, rotgen, model, sha, form, extra;
    csv_provenance p;
    in >> hash_mark >> rotgen >> p.version >> model >> p.model >> sha >> p.sha256 >> form >> p.form;
    if (!in || in >> extra || hash_mark != "#" || rotgen != "rotgen" || model != "model" ||
        sha != "sha256" || form != "form" || p.sha256.size() != 64 ||
        p.sha256.find_first_not_of("0123456789abcdef") != std::string::npos)
        return std::nullopt;
    return p;
}

} // namespace rotgen
