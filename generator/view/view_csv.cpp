#include "view/view.hpp"

#include <cerrno>
#include <cstdlib>
#include <fstream>

namespace rotgen {

namespace {

std::vector<std::string> split_fields(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(line.substr(start, comma - start));
        if (comma == std::string::npos) return fields;
        start = comma + 1;
    }
}

// A field as the CSV writes numbers (%.17g, inf, nan); the column is 1-based.
double number_of(const std::string& field, const source_location& where) {
    const char* begin = field.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (field.empty() || end != begin + field.size())
        throw user_error(where, "not a number: '" + field + "'");
    return v;
}

} // namespace

csv_table read_run_csv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw user_error({path}, "cannot read the run's CSV");
    std::string line;
    csv_table table;
    int n = 1;
    // the provenance line, and any other comment before the header
    for (; std::getline(in, line) && !line.empty() && line[0] == '#'; ++n)
        if (n == 1) table.provenance = line;
    if (line.rfind("t,", 0) != 0)
        throw user_error({path, n, 1}, "not a CSV that rotgen simulate wrote: its header must "
                                       "start with 't,'");
    table.header_line = n;
    const auto header = split_fields(line);
    table.columns.assign(header.begin() + 1, header.end());
    for (++n; std::getline(in, line); ++n) {
        if (line.empty()) continue;
        const auto fields = split_fields(line);
        if (fields.size() != header.size())
            throw user_error({path, n, 1}, "a row of " + std::to_string(fields.size()) +
                                               " fields under a header of " +
                                               std::to_string(header.size()));
        std::vector<double> row;
        int column = 1;
        for (const auto& f : fields) {
            row.push_back(number_of(f, {path, n, column}));
            column += static_cast<int>(f.size()) + 1;
        }
        table.rows.push_back(std::move(row));
    }
    if (table.rows.empty())
        throw user_error({path, table.header_line + 1, 1}, "the CSV has no rows");
    return table;
}

} // namespace rotgen
