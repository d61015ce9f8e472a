#include "cli/options.hpp"

#include "support/error.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace rotgen {

namespace {

const option_spec* find_option(const command_spec& c, const std::string& word) {
    for (const auto& o : c.options) {
        if (o.name == word) return &o;
        for (const auto& a : o.aliases)
            if (a == word) return &o;
    }
    return nullptr;
}

[[noreturn]] void unknown_option(const command_spec& c, const std::string& word) {
    std::vector<std::string> names;
    for (const auto& o : c.options) {
        names.push_back(o.name);
        names.insert(names.end(), o.aliases.begin(), o.aliases.end()); // --outptu: --output
    }
    const std::string best = closest_name(word.substr(0, word.find('=')), names);
    usage_error(c, "unknown option '" + word + "' for " + c.name +
                       (best.empty() ? "" : "; did you mean '" + best + "'?"));
}

// Whether an argument after an option that takes a value is another option rather than its value:
// it starts with '-' and is longer than "-" (standard input or output), but is not a negative
// number ("-j -1" then says what -j takes, not that it needs a value).
bool looks_like_option(const std::string& a) {
    if (a.size() < 2 || a[0] != '-') return false;
    return !(std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.');
}

} // namespace

const std::string& parsed_options::empty() {
    static const std::string none;
    return none;
}

const std::string& parsed_options::value(const std::string& name,
                                         const std::string& fallback) const {
    const auto it = m_values.find(name);
    return it == m_values.end() ? fallback : it->second;
}

std::vector<std::string> parsed_options::values(const std::string& name) const {
    const auto it = m_repeated.find(name);
    return it == m_repeated.end() ? std::vector<std::string>{} : it->second;
}

void usage_error(const command_spec& c, const std::string& problem) {
    throw user_error({"rotgen " + c.name}, problem);
}

parsed_options parse_options(const command_spec& c, const std::vector<std::string>& args) {
    parsed_options p;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-h" || a == "--help") {
            p.help = true;
            continue;
        }
        if (a.size() < 2 || a[0] != '-') { // the operand ("-" alone is one: standard input/output)
            if (c.operand.empty()) usage_error(c, c.name + " takes no " + a);
            if (!p.operand.empty())
                usage_error(c, c.name + " takes one " + c.operand + ", got '" + p.operand +
                                   "' and '" + a + "'");
            p.operand = a;
            continue;
        }
        const std::size_t eq = a.find('=');
        const std::string word = a.substr(0, eq);
        const option_spec* o = find_option(c, word);
        if (!o) unknown_option(c, a);
        if (p.has(o->name) && !o->repeatable) usage_error(c, o->name + " given twice");
        std::string v;
        if (eq != std::string::npos) {
            if (o->value.empty()) usage_error(c, o->name + " takes no value");
            v = a.substr(eq + 1);
        } else if (!o->value.empty() && !o->optional_value) {
            if (i + 1 >= args.size() || looks_like_option(args[i + 1]))
                usage_error(c, o->name + " needs a value (" + o->value + ")");
            v = args[++i];
        }
        p.m_values[o->name] = v;
        if (o->repeatable) p.m_repeated[o->name].push_back(v);
    }
    if (!p.help && !c.operand.empty() && p.operand.empty())
        usage_error(c, c.name + " needs a " + c.operand + ": rotgen " + c.name + " " + c.synopsis);
    return p;
}

std::string help_text(const command_spec& c) {
    std::ostringstream os;
    os << "usage: rotgen " << c.name << " " << c.synopsis << "\n\n" << c.summary << "\n";
    if (!c.options.empty()) os << "\noptions:\n";
    std::size_t width = 0;
    std::vector<std::string> left;
    for (const auto& o : c.options) {
        std::string l = o.name;
        for (const auto& a : o.aliases)
            l += ", " + a;
        if (!o.value.empty()) l += o.optional_value ? "[=" + o.value + "]" : " " + o.value;
        width = std::max(width, l.size());
        left.push_back(l);
    }
    // a help of several lines: each continuation line starts under the first line's text
    const std::string indent(width + 4, ' ');
    for (std::size_t i = 0; i < c.options.size(); ++i) {
        os << "  " << left[i] << std::string(width + 2 - left[i].size(), ' ');
        std::istringstream lines(c.options[i].help);
        std::string line;
        for (bool first = true; std::getline(lines, line); first = false)
            os << (first ? "" : indent)
               << line.substr(std::min(line.find_first_not_of(' '), line.size())) << "\n";
    }
    os << "  -h, --help" << std::string(width > 8 ? width - 8 : 2, ' ') << "this text\n";
    return os.str();
}

} // namespace rotgen
