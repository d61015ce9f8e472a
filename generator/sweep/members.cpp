#include "sweep/members.hpp"

#include "expr/angles.hpp"
#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "spec/spec.hpp"
#include "support/format.hpp"

#include <cmath>
#include <cstdlib>
#include <random>

namespace rotgen {

namespace {

constexpr double largest_member_count = 1e8; // a bound on memory, not on the method
constexpr double pi = 3.141592653589793238;

double checked(double v, const source_location& where, const std::string& what) {
    if (!std::isfinite(v) || std::fpclassify(v) == FP_SUBNORMAL)
        throw user_error(where, what + " must be a finite number, 0 or at least 2.2e-308 in size");
    return v;
}

double decimal(const std::string& text, const source_location& where, const std::string& what) {
    if (!is_decimal(text)) throw user_error(where, what + " must be a number, got '" + text + "'");
    return checked(std::strtod(text.c_str(), nullptr), where, what);
}

double yaml_number(const YAML::Node& n, const std::string& file, const std::string& what) {
    if (!n.IsScalar()) throw user_error(location_of(n, file), what + " must be a number");
    return decimal(n.Scalar(), location_of(n, file), what);
}

// A range {from, to, count} of `k`: checked here, its values computed when asked
// (sweep_key::value), so that a range of 1e8 values takes no memory and a grid too large is refused
// at once.
void set_range(sweep_key& k, double from, double to, double count, const source_location& where) {
    if (!(count >= 1) || count != std::floor(count) || count > largest_member_count)
        throw user_error(where, "count must be a whole number from 1 to 1e8");
    if (count > 1 && from == to)
        throw user_error(where, "empty range: from = to = " + format_double(from) + " with count " +
                                    format_double(count) +
                                    " (give {values: [...]} for repeated values)");
    k.from = from;
    k.to = to;
    k.count = static_cast<std::size_t>(count);
}

// One `vary:` entry of the scene: {from, to, count}, {values: [...]}, or (random) {from, to}.
sweep_key read_entry(const YAML::Node& key, const YAML::Node& n, const std::string& file,
                     sweep_mode mode) {
    sweep_key k;
    k.key = key.Scalar();
    k.where = location_of(key, file);
    if (!n.IsMap()) throw user_error(location_of(n, file), "'" + k.key + "' must be a mapping");
    const bool random = mode == sweep_mode::random;
    if (random)
        check_keys(n, {"from", "to"}, file, "a random sweep entry");
    else
        check_keys(n, {"from", "to", "count", "values"}, file, "a sweep entry");
    if (n["values"]) {
        if (n["from"] || n["to"] || n["count"])
            throw user_error(location_of(n, file), "give either values or from, to, count");
        if (!n["values"].IsSequence() || n["values"].size() == 0)
            throw user_error(location_of(n["values"], file), "empty range: values must be a "
                                                             "non-empty list of numbers");
        for (const auto& v : n["values"])
            k.values.push_back(yaml_number(v, file, "a value of '" + k.key + "'"));
        return k;
    }
    for (const char* need : random ? std::vector<const char*>{"from", "to"}
                                   : std::vector<const char*>{"from", "to", "count"})
        if (!n[need])
            throw user_error(location_of(n, file), "'" + k.key + "' needs " + need +
                                                       (random ? "" : " (or values: [...])"));
    k.from = yaml_number(n["from"], file, "from");
    k.to = yaml_number(n["to"], file, "to");
    if (!random)
        set_range(k, k.from, k.to, yaml_number(n["count"], file, "count"),
                  location_of(n["count"], file));
    else if (k.from == k.to)
        throw user_error(location_of(n, file), "empty range: from = to");
    return k;
}

// --vary KEY=FROM:TO:COUNT, KEY=V1,V2,... or (random) KEY=FROM:TO.
sweep_key read_cli(const std::string& arg, sweep_mode mode) {
    const source_location where{"rotgen sweep --vary " + arg};
    const auto eq = arg.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size())
        throw user_error(where, "expected KEY=FROM:TO:COUNT or KEY=V1,V2,...");
    sweep_key k;
    k.key = arg.substr(0, eq);
    k.where = where;
    std::vector<std::string> parts;
    const std::string rest = arg.substr(eq + 1);
    const char sep = rest.find(':') != std::string::npos ? ':' : ',';
    for (std::size_t b = 0, e; b <= rest.size(); b = e + 1) {
        e = rest.find(sep, b);
        if (e == std::string::npos) e = rest.size();
        parts.push_back(rest.substr(b, e - b));
    }
    if (mode == sweep_mode::random) {
        if (sep != ':' || parts.size() != 2)
            throw user_error(where, "a random sweep takes KEY=FROM:TO");
        k.from = decimal(parts[0], where, "from");
        k.to = decimal(parts[1], where, "to");
        if (k.from == k.to) throw user_error(where, "empty range: from = to");
    } else if (sep == ':') {
        if (parts.size() != 3) throw user_error(where, "expected KEY=FROM:TO:COUNT");
        set_range(k, decimal(parts[0], where, "from"), decimal(parts[1], where, "to"),
                  decimal(parts[2], where, "count"), where);
    } else {
        for (const auto& p : parts)
            k.values.push_back(decimal(p, where, "a value"));
    }
    return k;
}

// The middle angle in [0, pi] (proper Euler; theta of z-x-z) or [-pi/2, pi/2] (Tait-Bryan), as
// the scene requires of its own value.
void check_values(const sweep_key& k, const angle_convention& c) {
    if (k.target != sweep_key::angle || k.index != 1) return;
    const double lo = c.proper() ? 0 : -pi / 2, hi = c.proper() ? pi : pi / 2;
    std::vector<double> v = k.values;
    if (v.empty()) v = {k.from, k.to};
    for (double x : v)
        if (x < lo || x > hi)
            throw user_error(k.where, "initial " + c.names[1] + " = " + format_double(x) +
                                          " is outside " +
                                          (c.proper() ? "[0, pi]" : "[-pi/2, pi/2]") + " (" +
                                          c.description() + ")");
}

void read_block(const YAML::Node& block, const std::string& file, sweep_plan& plan) {
    plan.where = location_of(block, file);
    if (!block.IsMap()) throw user_error(plan.where, "'sweep' must be a mapping");
    check_keys(block, {"mode", "vary", "members", "seed"}, file, "sweep");
    if (const YAML::Node m = block["mode"]) {
        const std::string s = m.IsScalar() ? m.Scalar() : "";
        if (s == "grid" || s == "zip" || s == "random")
            plan.mode = s == "grid"  ? sweep_mode::grid
                        : s == "zip" ? sweep_mode::zip
                                     : sweep_mode::random;
        else
            throw user_error(location_of(m, file),
                             "unknown sweep mode '" + s + "' (expected grid, zip or random)");
    }
    for (const char* key : {"members", "seed"})
        if (block[key] && plan.mode != sweep_mode::random)
            throw user_error(location_of(block[key], file),
                             std::string(key) + " is for mode: random only");
    if (plan.mode == sweep_mode::random) {
        if (!block["members"]) throw user_error(plan.where, "a random sweep needs members");
        const double m = yaml_number(block["members"], file, "members");
        if (!(m >= 1) || m != std::floor(m) || m > largest_member_count)
            throw user_error(location_of(block["members"], file),
                             "members must be a whole number from 1 to 1e8");
        plan.members = static_cast<long>(m);
        if (block["seed"]) {
            const double s = yaml_number(block["seed"], file, "seed");
            if (s < 0 || s != std::floor(s) || s > 9e15)
                throw user_error(location_of(block["seed"], file),
                                 "seed must be a whole number from 0 to 9e15");
            plan.seed = static_cast<std::uint64_t>(s);
        }
    }
    if (const YAML::Node vary = block["vary"]) {
        if (!vary.IsMap()) throw user_error(location_of(vary, file), "'vary' must be a mapping");
        for (const auto& kv : vary) {
            for (const auto& k : plan.keys)
                if (k.key == kv.first.Scalar())
                    throw user_error(location_of(kv.first, file),
                                     "'" + k.key + "' given twice in vary");
            plan.keys.push_back(read_entry(kv.first, kv.second, file, plan.mode));
        }
    }
}

} // namespace

sweep_plan read_sweep_plan(const scene_spec& scene, const std::vector<std::string>& cli_vary) {
    sweep_plan plan;
    plan.where = scene.where;
    const YAML::Node root = load_yaml_file(scene.file);
    if (const YAML::Node block = root["sweep"]) read_block(block, scene.file, plan);
    for (const auto& arg : cli_vary) {
        sweep_key k = read_cli(arg, plan.mode);
        bool replaced = false;
        for (auto& old : plan.keys)
            if (old.key == k.key) old = k, replaced = true;
        if (!replaced) plan.keys.push_back(k);
    }
    if (plan.keys.empty())
        throw user_error(plan.where, "nothing to vary: give a sweep: block with vary: or "
                                     "--vary KEY=FROM:TO:COUNT");
    for (auto& k : plan.keys) {
        resolve_value_key(scene, k, "sweep key");
        check_values(
            k, scene.model.angles); // distinct keys set distinct values: each value has one name
    }
    if (plan.mode == sweep_mode::zip)
        for (const auto& k : plan.keys)
            if (k.size() != plan.keys.front().size())
                throw user_error(k.where, "zip lengths differ: '" + k.key + "' has " +
                                              std::to_string(k.size()) + " values, '" +
                                              plan.keys.front().key + "' has " +
                                              std::to_string(plan.keys.front().size()));
    if (plan.mode == sweep_mode::grid) {
        double n = 1;
        for (const auto& k : plan.keys)
            n *= double(k.size());
        if (n > largest_member_count)
            throw user_error(plan.where,
                             "the grid has " + short_number(n) + " members; at most 1e8");
    }
    return plan;
}

double sweep_key::value(std::size_t i) const {
    if (count == 0) return values[i];
    return i + 1 == count ? to : i == 0 ? from : from + (to - from) * double(i) / double(count - 1);
}

member_table::member_table(const sweep_plan& plan) : m_plan(plan) {
    if (plan.mode == sweep_mode::random) {
        m_size = static_cast<std::size_t>(plan.members);
        std::mt19937_64 gen(plan.seed);
        for (std::size_t m = 0; m < m_size; m += checkpoint_every) {
            m_checkpoints.push_back(gen);
            gen.discard(checkpoint_every * plan.keys.size());
        }
    } else if (plan.mode == sweep_mode::zip) {
        m_size = plan.keys.front().size();
    } else {
        m_size = 1;
        for (const auto& k : plan.keys)
            m_size *= k.size();
    }
}

std::vector<double> member_table::row(std::size_t m) const {
    const std::size_t nk = m_plan.keys.size();
    std::vector<double> row(nk);
    if (m_plan.mode == sweep_mode::random) {
        std::mt19937_64 gen = m_checkpoints[m / checkpoint_every];
        gen.discard((m % checkpoint_every) * nk);
        for (std::size_t k = 0; k < nk; ++k) {
            const double u = double(gen() >> 11) * 0x1.0p-53; // 53 random bits: [0, 1)
            row[k] = m_plan.keys[k].from + (m_plan.keys[k].to - m_plan.keys[k].from) * u;
        }
    } else if (m_plan.mode == sweep_mode::zip) {
        for (std::size_t k = 0; k < nk; ++k)
            row[k] = m_plan.keys[k].value(m);
    } else {
        for (std::size_t k = nk, rest = m; k-- > 0;) { // the last key fastest
            row[k] = m_plan.keys[k].value(rest % m_plan.keys[k].size());
            rest /= m_plan.keys[k].size();
        }
    }
    return row;
}

std::vector<std::vector<double>> member_rows(const sweep_plan& plan) {
    const member_table table(plan);
    std::vector<std::vector<double>> rows;
    for (std::size_t m = 0; m < table.size(); ++m)
        rows.push_back(table.row(m));
    return rows;
}

member_values member_of(const sweep_plan& plan, const member_values& base,
                        const std::vector<double>& row) {
    member_values v = base;
    for (std::size_t k = 0; k < plan.keys.size(); ++k) {
        const sweep_key& key = plan.keys[k];
        if (key.target == sweep_key::angle)
            v.angles[key.index] = row[k];
        else if (key.target == sweep_key::rate)
            v.initial_rates[key.index] = row[k];
        else
            v.parameters[key.index] = row[k];
    }
    return v;
}

} // namespace rotgen
