#include "support/error.hpp"

#include <algorithm>
#include <cctype>

namespace rotgen {

std::string to_string(const source_location& where) {
    std::string s = where.file.empty() ? std::string("<input>") : where.file;
    if (where.line > 0) {
        s += ":" + std::to_string(where.line);
        if (where.column > 0) s += ":" + std::to_string(where.column);
    }
    return s;
}

// Optimal string alignment distance: insertions, deletions, substitutions and transpositions of
// adjacent characters each cost 1, so a swapped pair of keys is one typo ("dop835" is 1 from
// "dop853", 2 from "dopri5").
static std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i)
        d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j)
        d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t cost = a[i - 1] != b[j - 1] ? 1 : 0;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

static std::string lower_case(std::string s) {
    for (char& c : s)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string closest_name(const std::string& word, const std::vector<std::string>& candidates) {
    for (const auto& c : candidates)
        if (c != word && lower_case(c) == lower_case(word)) return c;
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(1, word.size() / 3) + 1;
    for (const auto& c : candidates) {
        const std::size_t d = edit_distance(word, c);
        if (d < best_distance) {
            best_distance = d;
            best = c;
        }
    }
    return best;
}

} // namespace rotgen
