// rotgen bench: the best configuration per accuracy.
#include "bench/summary.hpp"

#include "bench/numbers.hpp"

#include <algorithm>
#include <map>

namespace rotgen::bench {

namespace {

bool is_peer(const result_row& r) {
    return r.peer != "rotgen";
}

// The fastest measured point (by median) at matched accuracy at each level, per kind of peer.
std::vector<best_entry> best_measured(const std::vector<result_row>& rows,
                                      const std::vector<double>& levels) {
    std::vector<best_entry> best(levels.size(), best_entry{});
    for (std::size_t l = 0; l < levels.size(); ++l)
        for (const auto& r : rows) {
            if (!r.ok() || !matched_accuracy(r.error, levels[l]) || !std::isfinite(r.median))
                continue;
            const result_row*& slot = is_peer(r) ? best[l].peer : best[l].rotgen;
            if (!slot || r.median < slot->median) slot = &r;
        }
    return best;
}

// The cheapest run of a curve more accurate than a tenth of `level` (none: NaN time), as an upper
// bound of the curve's cost at the level (reach::beyond).
reach beyond_level(reach r, const std::vector<const result_row*>& points, double level) {
    for (const result_row* p : points)
        if (p->error <= level / 10 && !(p->median >= r.time))
            r.time = p->median, r.rhs = double(p->rhs), r.beyond = p->error;
    return r;
}

// The time a curve (points sorted by tolerance or step, coarsest first) needs to reach `level`:
// between two neighbouring points whose errors straddle the level, log(time) and log(RHS
// evaluations) are interpolated linearly in log(error); a measured point counts as it is if it
// is at matched accuracy (within the decade below the level). A curve that does neither but runs
// more accurately than the level competes with an upper bound (beyond_level); NaN time if it
// never gets there.
reach reach_on_curve(const std::string& name, const std::vector<const result_row*>& points,
                     double level) {
    reach best_here;
    best_here.curve = name;
    best_here.peer = points.front()->peer != "rotgen";
    for (std::size_t i = 0; i < points.size(); ++i) {
        const result_row& b = *points[i];
        if (matched_accuracy(b.error, level) && !(b.median >= best_here.time))
            best_here.time = b.median, best_here.rhs = double(b.rhs);
        if (i == 0) continue;
        const result_row& a = *points[i - 1];
        if (!(a.error > level && b.error <= level && b.error > 0)) continue;
        const double w =
            (std::log(level) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
        const double t =
            std::exp(std::log(a.median) + w * (std::log(b.median) - std::log(a.median)));
        const double n = std::exp(std::log(double(a.rhs)) +
                                  w * (std::log(double(b.rhs)) - std::log(double(a.rhs))));
        if (!(t >= best_here.time)) best_here.time = t, best_here.rhs = n;
    }
    return std::isfinite(best_here.time) ? best_here : beyond_level(best_here, points, level);
}

std::string curve_name(const result_row& r) {
    return (r.peer == "rotgen" ? "rotgen " : r.peer + " ") + method_key(r) + " " + r.scalar + " " +
           r.form;
}

void sort_curve(std::vector<const result_row*>& points) {
    std::sort(points.begin(), points.end(), [](const result_row* a, const result_row* b) {
        return a->tol > 0 ? a->tol > b->tol : a->step > b->step;
    });
}

// The fastest curve (interpolated) per level, per kind of peer.
std::vector<std::pair<reach, reach>> best_interpolated(const std::vector<result_row>& rows,
                                                       const std::vector<double>& levels) {
    std::map<std::string, std::vector<const result_row*>> curves_by_name;
    for (const auto& r : rows)
        if (r.ok() && std::isfinite(r.median) && r.error >= 0)
            curves_by_name[curve_name(r)].push_back(&r);
    std::vector<std::pair<reach, reach>> reached(levels.size()); // (rotgen, peer)
    for (auto& [name, points] : curves_by_name) {
        sort_curve(points);
        for (std::size_t l = 0; l < levels.size(); ++l) {
            const reach best_here = reach_on_curve(name, points, levels[l]);
            if (!std::isfinite(best_here.time)) continue;
            reach& slot = best_here.peer ? reached[l].second : reached[l].first;
            if (!(best_here.time >= slot.time)) slot = best_here;
        }
    }
    return reached;
}

} // namespace

std::string why_none(const std::vector<result_row>& rows, bool peer, double level) {
    const result_row* best = nullptr;
    for (const auto& r : rows)
        if (is_peer(r) == peer && r.ok() && std::isfinite(r.median) && r.error >= 0 &&
            (!best || r.error < best->error))
            best = &r;
    if (!best) return "no successful run";
    return "best reached " + short_number(best->error) + " (" + config_name(best) + ")" +
           (best->error <= level ? "" : ", above " + tol_text(level));
}

std::string reach_text(const reach& r) {
    const std::string bound = std::isfinite(r.beyond)
                                  ? "; an upper bound: its cheapest run reached " +
                                        short_number(r.beyond) + ", past the level's decade"
                                  : std::string();
    return short_number(r.time * 1e6) + " us (" + r.curve + bound + ")";
}

bool matched_accuracy(double error, double level) {
    return error <= level && error > level / 10;
}

std::string method_key(const result_row& r) {
    const bool adaptive = r.method == "dop853" || r.method == "dopri5" || r.method == "rkf78";
    return adaptive && r.step > 0 ? r.method + " fixed" : r.method;
}

std::string method_title(const result_row& r) {
    return r.peer == "rotgen" ? method_key(r) : r.peer + " " + method_key(r);
}

std::string config_name(const result_row* r) {
    if (!r) return std::string("—");
    std::string s = (r->peer == "rotgen" ? "rotgen " : r->peer + " ") + r->method + " " +
                    r->scalar + " " + r->form;
    s += r->tol > 0 ? " tol " + tol_text(r->tol) : " h " + short_number(r->step, 3);
    return s;
}

bench_summary summarise(const std::vector<result_row>& rows) {
    bench_summary s;
    for (int e = 3; e <= 13; ++e)
        s.levels.push_back(std::pow(10.0, -e));
    s.best = best_measured(rows, s.levels);
    s.reached = best_interpolated(rows, s.levels);
    return s;
}

reach curve_reach(const std::vector<result_row>& rows, const result_row& r, double level) {
    std::vector<const result_row*> points;
    for (const auto& p : rows)
        if (p.ok() && std::isfinite(p.median) && p.error >= 0 && curve_name(p) == curve_name(r))
            points.push_back(&p);
    sort_curve(points);
    return reach_on_curve(curve_name(r), points, level);
}

const result_row* fewest(const std::vector<result_row>& rows, const std::string& peer,
                         const std::string& method, double level) {
    const result_row* b = nullptr;
    for (const auto& r : rows)
        if (r.ok() && r.peer == peer && method_key(r) == method && r.scalar == "double" &&
            r.variant == 0 && matched_accuracy(r.error, level) && (!b || r.rhs < b->rhs))
            b = &r;
    return b;
}

} // namespace rotgen::bench
