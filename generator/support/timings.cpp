#include "support/timings.hpp"

#include <cstdio>

namespace rotgen {

double stage_timings::total(const std::string& stage) const {
    double s = 0;
    for (const auto& e : m_entries)
        if (e.stage == stage) s += e.seconds;
    return s;
}

void stage_timings::print(std::ostream& os) const {
    for (const auto& e : m_entries) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "rotgen: timing %-9s %8.4f s", e.stage.c_str(), e.seconds);
        os << buf << (e.detail.empty() ? "" : "  " + e.detail) << "\n";
    }
}

} // namespace rotgen
