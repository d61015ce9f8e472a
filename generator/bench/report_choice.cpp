// rotgen bench: the choice in scene terms, as the console and results.md print it.
#include "bench/bench_internal.hpp"
#include "bench/numbers.hpp"

#include <sstream>

namespace rotgen::bench {

std::string choices_text(const bench_context& ctx, const std::string& indent) {
    std::ostringstream s;
    s << indent
      << "fastest configuration simulate runs at each error level (error: the largest over the "
         "samples of the attitude error and |dw|/|w|, measured by running the scene; rows marked "
         "bench only are never chosen):\n";
    bool any = false;
    for (const scene_choice& c : ctx.choices) {
        bool reached = false; // some successful row of the bench reached the level
        for (const auto& r : ctx.output.rows)
            reached = reached || (r.ok() && r.error <= c.level);
        if (!reached) continue;
        any = true;
        s << indent << "error <= " << tol_text(c.level) << ": ";
        if (!c.row) {
            s << "none (" << c.why << ")\n";
            continue;
        }
        s << config_name(c.row) << ", " << short_number(c.row->median * 1e6) << " us (bench error "
          << short_number(c.row->error) << "; run " << short_number(c.verified) << ")\n";
        std::istringstream lines(c.lines);
        for (std::string line; std::getline(lines, line);)
            s << indent << "    " << line << "\n";
    }
    if (!any) s << indent << "none: no configuration reached 1e-3\n";
    return s.str();
}

} // namespace rotgen::bench
