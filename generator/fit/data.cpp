#include "fit/data.hpp"

#include "expr/numbers.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace rotgen {

namespace {

const double missing = std::numeric_limits<double>::quiet_NaN();

// The measurable columns of the scene's model: every recordable name's columns.
std::vector<std::string> measurable(const scene_spec& scene) {
    std::vector<std::string> out{"t"};
    for (const auto& name : recordable_names(scene.model.angles))
        for (const auto& c : record_columns(name))
            out.push_back(c);
    return out;
}

std::vector<std::string> split_fields(const std::string& line) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ','))
        fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    return fields;
}

std::string trimmed(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// Where field `f` of a line starts (1-based column).
int column_of(const std::vector<std::string>& fields, std::size_t f) {
    int col = 1;
    for (std::size_t i = 0; i < f; ++i)
        col += static_cast<int>(fields[i].size()) + 1;
    return col;
}

// The header's names checked: `t` once, every other a measurable column, none twice, q0..q3
// all four or none. `at(i)` locates name i.
template <class At>
void check_header(const std::vector<std::string>& names, const scene_spec& scene, At at) {
    const std::vector<std::string> known = measurable(scene);
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (std::find(known.begin(), known.end(), names[i]) == known.end()) {
            const std::string best = closest_name(names[i], known);
            throw user_error(at(i), "unknown column '" + names[i] + "' (not recordable for this " +
                                        "scene's model" +
                                        (best.empty() ? ")" : "; did you mean '" + best + "'?)"));
        }
        if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) !=
            names.begin() + static_cast<std::ptrdiff_t>(i))
            throw user_error(at(i), "column '" + names[i] + "' appears twice");
    }
    if (std::find(names.begin(), names.end(), "t") == names.end())
        throw user_error(at(0), "no 't' column (the measurement times)");
    std::size_t quaternion = 0;
    for (const auto& n : names)
        quaternion += n.size() == 2 && n[0] == 'q' && n[1] >= '0' && n[1] <= '3';
    if (quaternion != 0 && quaternion != 4)
        throw user_error(at(0),
                         "the attitude needs all four columns q0, q1, q2, q3 (scalar first)");
    if (names.size() < 2) throw user_error(at(0), "no measured column besides 't'");
}

// The table checked and arranged: times in the span, the quaternion complete per row and
// normalised. `at(row, col)` locates a field.
template <class At>
measured_data arrange(const std::vector<std::string>& names,
                      const std::vector<std::vector<double>>& columns, const scene_spec& scene,
                      const std::string& source, At at) {
    measured_data d;
    d.file = source;
    const std::size_t rows = columns.empty() ? 0 : columns[0].size();
    if (rows == 0) throw user_error(at(0, 0), "no measurements (no rows after the header)");
    const double lo = std::min(scene.t_start, scene.t_end),
                 hi = std::max(scene.t_start, scene.t_end);
    std::array<std::size_t, 4> qc{};
    bool has_q = false;
    for (std::size_t c = 0; c < names.size(); ++c) {
        const std::string& n = names[c];
        if (n == "t") {
            d.t = columns[c];
            for (std::size_t r = 0; r < rows; ++r)
                if (!(d.t[r] >= lo && d.t[r] <= hi))
                    throw user_error(at(r, c), "time " + format_double(d.t[r]) +
                                                   " is outside the scene's span [" +
                                                   format_double(lo) + ", " + format_double(hi) +
                                                   "]");
        } else if (n.size() == 2 && n[0] == 'q' && n[1] >= '0' && n[1] <= '3') {
            qc[static_cast<std::size_t>(n[1] - '0')] = c;
            if (!has_q) d.columns.push_back("q"), d.values.emplace_back();
            has_q = true;
        } else {
            d.columns.push_back(n);
            d.values.push_back(columns[c]);
        }
    }
    for (std::size_t r = 0; r < rows && has_q; ++r) {
        std::array<double, 4> q{};
        std::size_t given = 0;
        for (std::size_t k = 0; k < 4; ++k)
            q[k] = columns[qc[k]][r], given += !std::isnan(q[k]);
        const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (given != 0 && given != 4)
            throw user_error(at(r, qc[0]),
                             "the attitude needs all four of q0..q3 in a row, or none");
        if (given == 4 && !(norm > 0.5 && norm < 2))
            throw user_error(at(r, qc[0]), "the quaternion's norm is " + format_double(norm) +
                                               " (expected a unit quaternion)");
        for (auto& x : q)
            x = given == 4 ? x / norm : missing;
        d.q.push_back(q);
    }
    return d;
}

} // namespace

bool measured_data::has_q() const {
    return !q.empty();
}

measured_data read_measured(const std::string& path, const scene_spec& scene) {
    std::ifstream in(path);
    if (!in) throw user_error({path}, "cannot read the measurements: no such file or unreadable");
    std::string line;
    int number = 0;
    std::vector<std::string> names;
    std::vector<std::vector<double>> columns;
    std::vector<int> lines;
    std::vector<std::vector<int>> starts; // per row, where each field starts
    while (std::getline(in, line)) {
        ++number;
        if (trimmed(line).empty() || line[0] == '#') continue;
        std::vector<std::string> fields = split_fields(line);
        if (names.empty()) {
            for (auto& f : fields)
                names.push_back(trimmed(f));
            check_header(names, scene, [&](std::size_t i) {
                return source_location{path, number, column_of(fields, i)};
            });
            columns.resize(names.size());
            continue;
        }
        if (fields.size() != names.size())
            throw user_error({path, number, 1}, std::to_string(fields.size()) + " fields, the " +
                                                    "header has " + std::to_string(names.size()));
        starts.emplace_back();
        for (std::size_t c = 0; c < fields.size(); ++c) {
            starts.back().push_back(column_of(fields, c));
            const std::string f = trimmed(fields[c]);
            const source_location where{path, number, column_of(fields, c)};
            if (f.empty() && names[c] == "t") throw user_error(where, "no time in this row");
            if (!f.empty() && !is_decimal(f))
                throw user_error(where, "'" + f + "' is not a number (leave the field empty " +
                                            "for a missing measurement)");
            const double v = f.empty() ? missing : std::strtod(f.c_str(), nullptr);
            if (!f.empty() && !std::isfinite(v))
                throw user_error(where, "'" + f + "' is not a finite number");
            columns[c].push_back(v);
        }
        lines.push_back(number);
    }
    if (names.empty())
        throw user_error({path, 1, 1}, "no header (expected t and measured columns)");
    measured_data d = arrange(names, columns, scene, path, [&](std::size_t r, std::size_t c) {
        if (lines.empty()) return source_location{path, number, 1};
        return source_location{path, lines[r], starts[r][c]};
    });
    d.line = lines;
    return d;
}

measured_data measured_from_columns(const std::vector<std::string>& names,
                                    const std::vector<std::vector<double>>& columns,
                                    const scene_spec& scene, const std::string& source) {
    check_header(names, scene, [&](std::size_t i) {
        return source_location{source, 1, static_cast<int>(i) + 1};
    });
    for (std::size_t c = 0; c < names.size(); ++c)
        for (std::size_t r = 0; r < columns[c].size(); ++r)
            if (names[c] == "t" && !std::isfinite(columns[c][r]))
                throw user_error({source, static_cast<int>(r) + 2, static_cast<int>(c) + 1},
                                 "no finite time in this row");
    measured_data d = arrange(names, columns, scene, source, [&](std::size_t r, std::size_t c) {
        return source_location{source, static_cast<int>(r) + 2, static_cast<int>(c) + 1};
    });
    for (std::size_t r = 0; r < d.t.size(); ++r)
        d.line.push_back(static_cast<int>(r) + 2);
    return d;
}

std::vector<std::string> measured_records(const measured_data& data) {
    std::vector<std::string> out;
    for (const auto& c : data.columns) {
        if (c == "q") {
            for (const char* n : {"q0", "q1", "q2", "q3"})
                out.push_back(n);
        } else if (c.rfind("body_", 0) == 0) {
            const std::string name = c.substr(0, 6);
            if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
        } else {
            out.push_back(c);
        }
    }
    return out;
}

} // namespace rotgen
