// rotgen — spec/: reading a model file: the YAML helpers of spec.hpp (load_yaml_file, location_of,
// check_keys), load_model and parse_model, and the parameter tables of a model_spec. The reader
// itself is model_reader (spec_detail.hpp).
#include "spec/spec_detail.hpp"

#include "expr/numbers.hpp"
#include "support/memory_files.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>

#include <sys/stat.h>

namespace rotgen {

source_location location_of(const YAML::Node& node, const std::string& file) {
    const YAML::Mark m = node.Mark();
    source_location where{file, m.line + 1, m.column + 1};
    if (node.IsScalar() && node.Tag() == "!") where = where.shifted(1); // inside the quotes
    return where;
}

namespace {

// YAML text has no control characters other than tab, line feed and carriage return; a file with
// one (an image, a compiled program, a UTF-16 file) is refused at the first. (Bytes that are not
// UTF-8 are left to yaml-cpp: kept fuzz inputs hold them inside otherwise readable models.)
void check_text(const std::string& path, const std::string& source) {
    int line = 1, column = 1;
    for (std::size_t i = 0; i < source.size();) {
        const unsigned char c = static_cast<unsigned char>(source[i]);
        const bool control = (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f;
        if (control) {
            char byte[8];
            std::snprintf(byte, sizeof byte, "0x%02x", c);
            throw user_error({path, line, column}, std::string("not a text file (byte ") + byte +
                                                       " here): a model or scene is YAML text");
        }
        if (c == '\n') line += 1, column = 0;
        if ((c & 0xc0) != 0x80) column += 1; // a UTF-8 continuation byte is no new column
        i += 1;
    }
}

// YAML forbids tabs in indentation; yaml-cpp's own message about them does not say so. The first
// line whose indentation holds a tab, if any.
void check_indentation(const std::string& path, const std::string& source) {
    int line = 1;
    for (std::size_t start = 0; start < source.size(); ++line) {
        std::size_t end = source.find('\n', start);
        if (end == std::string::npos) end = source.size();
        const std::size_t text = source.find_first_not_of(" \t", start);
        if (text < end && source[text] != '#' && source[text] != '\r') {
            const std::size_t tab = source.find('\t', start);
            if (tab < text)
                throw user_error({path, line, static_cast<int>(tab - start) + 1},
                                 "a tab in the indentation: YAML forbids tabs there; indent "
                                 "with spaces");
        }
        start = end + 1;
    }
}

// The file's text (support/memory_files.hpp first: a text held in memory under that name).
std::string read_source(const std::string& path) {
    std::string source;
    if (memory_file(path, source)) return source;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
        throw user_error({path}, "is a folder, not a file; give a model or scene file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw user_error({path}, "cannot open file: " + std::string(std::strerror(errno)));
    // At most 1 MiB: a model or scene is a few hundred bytes, and `model: /dev/zero` must end.
    constexpr std::size_t max_size = std::size_t(1) << 20;
    char chunk[1 << 14];
    do {
        in.read(chunk, sizeof chunk);
        source.append(chunk, static_cast<std::size_t>(in.gcount()));
        if (source.size() > max_size) throw user_error({path}, "file is larger than 1 MiB");
    } while (in);
    if (in.bad()) throw user_error({path}, "cannot read file");
    return source;
}

} // namespace

YAML::Node load_yaml_file(const std::string& path, std::string* source_out) {
    const std::string source = read_source(path);
    if (source_out) *source_out = source;
    check_text(path, source);
    try {
        YAML::Node root = YAML::Load(source);
        if (!root.IsMap())
            throw user_error({path, 1, 1}, "expected a YAML mapping at the top level");
        return root;
    } catch (const YAML::Exception& e) {
        check_indentation(path, source);
        throw user_error({path, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg);
    }
}

void check_keys(const YAML::Node& map, const std::vector<std::string>& allowed,
                const std::string& file, const std::string& what) {
    std::set<std::string> seen;
    for (const auto& kv : map) {
        if (!kv.first.IsScalar())
            throw user_error(location_of(kv.first, file), "keys of " + what + " must be names");
        const std::string key = kv.first.Scalar();
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
            const std::string best = closest_name(key, allowed);
            throw user_error(location_of(kv.first, file),
                             "unknown field '" + key + "' in " + what +
                                 (best.empty() ? "" : "; did you mean '" + best + "'?"));
        }
        if (!seen.insert(key).second)
            throw user_error(location_of(kv.first, file),
                             "duplicate field '" + key + "' in " + what);
    }
}

name_table model_spec::parameter_names() const {
    name_table names;
    for (const auto& p : parameters)
        names[p.name] = p.symbol;
    return names;
}

GiNaC::exmap model_spec::parameter_defaults() const {
    GiNaC::exmap m;
    for (const auto& p : parameters)
        m[p.symbol] = float_numeric(p.value);
    return m;
}

model_spec parse_model(const YAML::Node& node, const std::string& file, const std::string& source) {
    if (!node.IsMap()) throw user_error(location_of(node, file), "a model must be a YAML mapping");
    return spec_detail::model_reader(file, source).read(node);
}

model_spec load_model(const std::string& path, const std::string& command) {
    std::string source;
    const YAML::Node root = load_yaml_file(path, &source);
    if (const YAML::Node model = root["model"]; model && !root["inertia"] && !root["body"])
        throw user_error(
            location_of(model, path),
            "this is a scene file (it names its model with 'model:'); " + command +
                " takes a model file" +
                (model.IsScalar() ? ", such as the one it names, '" + model.Scalar() + "'" : ""));
    return parse_model(root, path, source);
}

} // namespace rotgen
