#include "run/lanes.hpp"
#include "run/tolerance_layout.hpp"

#include "support/error.hpp"

#include <cstdlib>
#include <memory>
#include <sstream>
#include <type_traits>

namespace rotgen {

namespace {

// The translation unit of the batch kernels: the form's header; rotgen_rhs_lanes, which runs
// rhs<xsimd::batch<double>> over the lanes a batch at a time, and with the Taylor method
// rotgen_taylor_lanes, taylor<xsimd::batch<double>> the same way (the lanes' coefficients laid out
// as lane_taylor_system says, runtime/lanes.hpp); rotgen_lane_width.
std::string lane_source(const compiled_form& cf) {
    const form_expressions& f = cf.f;
    const std::size_t n = f.state.size();
    std::ostringstream s;
    s << cf.header << "\n// ---- rotgen sweep --lanes: the batch kernels ----\n"
      << "#include <xsimd/xsimd.hpp>\n#include <vector>\n\n"
      << "namespace {\nnamespace rg_model = rotgen::models::" << cf.unit << ";\n"
      << "using rg_batch = xsimd::batch<double>;\n"
      << "rg_model::params<rg_batch> rg_params(const double* v, unsigned long lanes,\n"
      << "                                     unsigned long l) {\n"
      << "    (void)v, (void)lanes, (void)l;\n"
      << "    rg_model::params<rg_batch> p;\n";
    for (std::size_t i = 0; i < f.parameters.size(); ++i)
        s << "    p." << f.parameters[i].name << " = rg_batch::load_unaligned(v + " << i
          << " * lanes + l);\n";
    s << "    return p;\n}\n"
      << "rg_model::prepared<rg_batch> rg_prepared(const double* w, unsigned long lanes,\n"
      << "                                         unsigned long l) {\n"
      << "    rg_model::prepared<rg_batch> p;\n"
      << "    static_cast<rg_model::params<rg_batch>&>(p) = rg_params(w, lanes, l);\n";
    for (std::size_t i = 0; i < cf.constants.size(); ++i)
        s << "    p." << cf.constants[i] << " = rg_batch::load_unaligned(w + "
          << f.parameters.size() + i << " * lanes + l);\n";
    s << "    return p;\n}\n}\n\n"
      << "extern \"C\" {\n"
      << "unsigned long rotgen_lane_width() { return rg_batch::size; }\n"
      << "void rotgen_rhs_lanes(const double* w, double t, const double* y, double* dydt,\n"
      << "                      unsigned long lanes) {\n"
      << "    for (unsigned long l = 0; l < lanes; l += rg_batch::size) {\n"
      << "        rg_batch yb[" << n << "], db[" << n << "];\n"
      << "        for (unsigned long c = 0; c < " << n << "; ++c)\n"
      << "            yb[c] = rg_batch::load_unaligned(y + c * lanes + l);\n"
      << "        rg_model::rhs(rg_batch(t), yb, db, rg_prepared(w, lanes, l));\n"
      << "        for (unsigned long c = 0; c < " << n << "; ++c)\n"
      << "            db[c].store_unaligned(dydt + c * lanes + l);\n"
      << "    }\n}\n";
    if (cf.sys.tay)
        s << "// 1 when every coefficient written is finite (x - x stays 0 for a finite x)\n"
          << "int rotgen_taylor_lanes(const double* v, double t, double* c, int order,\n"
          << "                        unsigned long lanes) {\n"
          << "    const unsigned long m = static_cast<unsigned long>(order) + 1;\n"
          << "    thread_local std::vector<rg_batch> cb;\n"
          << "    cb.resize(rg_model::taylor_series * m);\n"
          << "    rg_batch nonfinite(0.0);\n"
          << "    for (unsigned long l = 0; l < lanes; l += rg_batch::size) {\n"
          << "        for (unsigned long i = 0; i < " << n << "; ++i)\n"
          << "            cb[i * m] = rg_batch::load_unaligned(c + i * m * lanes + l);\n"
          << "        rg_model::" << cf.taylor_call
          << "(rg_batch(t), cb.data(), order, rg_params(v, lanes, l));\n"
          << "        for (unsigned long i = 0; i < " << n << "; ++i)\n"
          << "            for (unsigned long k = 1; k < m; ++k) {\n"
          << "                cb[i * m + k].store_unaligned(c + (i * m + k) * lanes + l);\n"
          << "                nonfinite += cb[i * m + k] - cb[i * m + k];\n"
          << "            }\n"
          << "    }\n"
          << "    return xsimd::all(nonfinite == rg_batch(0.0)) ? 1 : 0;\n}\n";
    s << "}\n";
    return s.str();
}

// Whether a `taylor` scene's batch kernel may use AVX-512: unless ROTGEN_LANES_TARGET=avx2 (to
// compare: lane by lane the operations are the same, and on the heavy top so were the results'
// bytes); "auto" or unset: yes.
bool lanes_may_be_wide() {
    const char* v = std::getenv("ROTGEN_LANES_TARGET");
    const std::string target = v ? v : "";
    if (target.empty() || target == "auto") return true;
    if (target == "avx2") return false;
    throw user_error({"ROTGEN_LANES_TARGET=" + target},
                     "unknown lane target; use avx2 (never AVX-512) or auto (the default)");
}

// The compiler flags of the batch kernel and the name of its target. Products are fused into
// sums where the CPU has FMA: a lane's bits are not its scalar run's anyway (vector sin and cos,
// shared steps), and a heavy-top Taylor expansion took 129 against 146 ns a lane
// (bench/results/taylor_kernel.md). A `taylor` scene's batches are 8 wide where the CPU has
// AVX-512 and `lanes` (the members run together) is a multiple of 8 (host_lane_vector_flags).
std::pair<std::string, std::string> lane_target(const std::string& method, std::size_t lanes) {
    const bool wide = method == "taylor" && lanes % 8 == 0 && lanes_may_be_wide();
    std::string arch;
    std::string flags = host_lane_vector_flags(&arch, wide);
#ifdef ROTGEN_XSIMD_INCLUDE
    const std::string dir = ROTGEN_XSIMD_INCLUDE; // not the system's: -I there breaks <cstdlib>
    if (dir != "/usr/include" && dir != "/usr/local/include") flags += " -I'" + dir + "'";
#endif
    return {flags, arch};
}

// The members' states and parameters laid out by lane (component c of lane l at c*lanes + l);
// lanes past the members repeat the first member (stopped: they only fill the last batch).
struct lane_batch {
    // the members' own timings (the sweep reports preparation only): the parts keep a reference
    // to it to their end, so it lives with them, at an address that a move of the batch keeps
    std::unique_ptr<stage_timings> timings = std::make_unique<stage_timings>();
    std::vector<std::unique_ptr<member_parts>> parts; // per member
    std::vector<std::size_t> lane_of;                 // member -> lane, or `alone`
    std::vector<std::size_t> member_of;               // lane -> member (members only)
    std::vector<Eigen::VectorXd> y0;
    std::vector<std::vector<double>> parameters;
    static constexpr std::size_t alone = static_cast<std::size_t>(-1);
};

// Starts every member (as run_member starts it); a member that cannot start in the scene's form,
// or whose start is a user error, runs alone.
lane_batch start_members(const prepared_scene& prepared,
                         const std::vector<member_values>& members) {
    lane_batch b;
    for (const member_values& values : members) {
        b.parts.push_back(run_parts(prepared, values, *b.timings));
        b.lane_of.push_back(lane_batch::alone);
        Eigen::VectorXd y;
        std::vector<double> p;
        try {
            if (!b.parts.back()->start(y, p)) continue;
        } catch (const user_error&) {
            continue; // run_member reports it
        }
        b.lane_of.back() = b.member_of.size();
        b.member_of.push_back(b.parts.size() - 1);
        b.y0.push_back(std::move(y));
        b.parameters.push_back(std::move(p));
    }
    return b;
}

// Component c of every lane: values[lane][c] at c*lanes + lane (lanes >= values.size(); the
// lanes past them repeat lane 0).
template <class V> std::vector<double> by_lane(const std::vector<V>& values, std::size_t lanes) {
    const std::size_t n = static_cast<std::size_t>(values[0].size());
    std::vector<double> out(n * lanes);
    for (std::size_t l = 0; l < lanes; ++l)
        for (std::size_t c = 0; c < n; ++c)
            out[c * lanes + l] = values[l < values.size() ? l : 0][static_cast<Eigen::Index>(c)];
    return out;
}

// Whether a lane carries the event through to the end: an event that acts (or counts its
// occurrences, `after`) needs the restart of a member's own run (run/actions.hpp), so the lane it
// occurs in leaves the batch there and the member runs alone, from its start.
bool runs_in_lanes(const event_spec& e) {
    return !e.acts() && e.after <= 1;
}

// A lane's run: its samples (none when the member must run alone), the events it met in time order,
// the terminal one that ended it (-1: none) and the work it took part in: the batch's steps and
// evaluations up to its own end (the step of its terminal event, or the batch's end).
struct lane_run {
    sample_states s;
    std::vector<member_event> events;
    int stopped_by = -1;
    step_stats stats;
};

// Lane l of a lane state: its n components, into yl (of size n).
void lane_into(const Eigen::VectorXd& y, std::size_t l, std::size_t lanes, Eigen::VectorXd& yl) {
    for (Eigen::Index c = 0; c < yl.size(); ++c)
        yl[c] = y[c * static_cast<Eigen::Index>(lanes) + static_cast<Eigen::Index>(l)];
}
Eigen::VectorXd lane_of(const Eigen::VectorXd& y, std::size_t l, std::size_t n, std::size_t lanes) {
    Eigen::VectorXd yl(static_cast<Eigen::Index>(n));
    lane_into(y, l, lanes, yl);
    return yl;
}

// The scene's events in every member's lane: event i of lane l is number l·E + i, its g the
// form's kernel on the lane's state and parameters. None is terminal here: a lane's terminal event
// ends that lane's run only (end_lanes), while the batch goes on.
event_set<double, Eigen::VectorXd> lane_events(const prepared_scene& prepared, const lane_batch& b,
                                               std::size_t lanes, std::vector<double>& scratch) {
    const scene_spec& scene = prepared.scene();
    stage_timings timings;
    const compiled_form& cf = prepared.compiled(scene.form, timings, nullptr);
    const std::size_t n = scratch.size();
    event_set<double, Eigen::VectorXd> events;
    for (std::size_t l = 0; l < b.member_of.size(); ++l)
        for (std::size_t i = 0; i < scene.events.size(); ++i)
            events.add(
                [g = cf.events[i], p = b.parameters[l].data(), l, n, lanes,
                 &scratch](double t, const Eigen::VectorXd& y) {
                    for (std::size_t c = 0; c < n; ++c)
                        scratch[c] = y[static_cast<Eigen::Index>(c * lanes + l)];
                    double out = 0;
                    g(p, t, scratch.data(), &out);
                    return out;
                },
                direction_of(scene.events[i]), false, scene.events[i].name);
    return events;
}

// Each lane's events from the batch's hits; a lane's first terminal event ends its run there: the
// events at that time (within the events' refinement tolerance) are its last, and its samples after
// that time are dropped (finish() ends its rows with the event's state).
void end_lanes(const scene_spec& scene, const event_set<double, Eigen::VectorXd>& events,
               std::size_t n, std::size_t lanes, std::vector<lane_run>& out) {
    const std::size_t per_lane = scene.events.size();
    for (const auto& hit : events.hits()) {
        lane_run& r = out[hit.index / per_lane];
        const std::size_t i = hit.index % per_lane;
        if (r.stopped_by >= 0) {
            const double t_end = r.events.back().t;
            if (std::abs(hit.t - t_end) > std::max(1e-14 * std::abs(t_end), 1e-15)) continue;
        }
        r.events.push_back({i, hit.t, lane_of(hit.y, hit.index / per_lane, n, lanes)});
        if (scene.events[i].stop && r.stopped_by < 0) {
            r.stopped_by = static_cast<int>(i);
            r.stats = hit.work; // what its own run, stopped there, reports
        }
    }
    for (lane_run& r : out) {
        if (r.stopped_by < 0) continue;
        const double t_stop = r.events.back().t;
        while (!r.s.empty() && r.s.last_t() > t_stop)
            r.s.pop_back();
    }
}

// Integrates the started members' lanes, `sys` (its lanes past the members stopped), over the
// scene's sample times with the scene's method.
template <class System, class Method>
std::vector<lane_run> run_system(const prepared_scene& prepared, lane_batch& b, System& sys,
                                 const Method& method) {
    const scene_spec& scene = prepared.scene();
    const std::size_t members = b.member_of.size(), n = sys.components(), lanes = sys.lanes();
    std::vector<lane_run> out(members);
    std::vector<double> scratch(n); // a lane's state, for its event functions
    event_set<double, Eigen::VectorXd> events = lane_events(prepared, b, lanes, scratch);
    std::vector<char> ended(members, 0); // by a terminal event (reported before later samples)
    std::size_t sample = 0, hits_seen = 0;
    Eigen::VectorXd yl(static_cast<Eigen::Index>(n)); // a lane's state at a sample
    const auto observe = [&](double t, const Eigen::VectorXd& y) {
        for (; hits_seen < events.hits().size(); ++hits_seen) {
            const std::size_t e = events.hits()[hits_seen].index, l = e / scene.events.size();
            if (!runs_in_lanes(scene.events[e % scene.events.size()])) {
                sys.stop(l); // it acts or counts here: it leaves the batch and runs alone
                continue;
            }
            if (scene.events[e % scene.events.size()].stop && !ended[l]) {
                ended[l] = 1;
                sys.stop(l); // its run is over: it stays where it is
            }
        }
        std::size_t live = 0;
        for (std::size_t l = 0; l < members; ++l) {
            if (!sys.is_live(l)) continue;
            lane_into(y, l, lanes, yl);
            if (!b.parts[b.member_of[l]]->keeps_chart(sample, t, yl)) {
                sys.stop(l); // it changes chart here: it runs alone
                continue;
            }
            out[l].s.add(t, yl);
            ++live;
        }
        ++sample;
        return live > 0;
    };
    const std::vector<double> times = sample_times(scene);
    for (lane_run& r : out)
        r.s.reserve(times.size(), n); // one allocation each, not one per doubling
    Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(by_lane(b.y0, lanes).data(),
                                                          static_cast<Eigen::Index>(n * lanes));
    const integration_result<double> res =
        events.size() > 0 ? integrate(sys, method, scene.t_start, y, times, observe, events)
                          : integrate(sys, method, scene.t_start, y, times, observe);
    for (lane_run& r : out)
        r.stats = res.stats;
    end_lanes(scene, events, n, lanes, out);
    // the observer stops the run when no lane is left (ended or to run alone)
    const bool ran = res.ok() || res.code == status::stopped_by_observer;
    for (std::size_t l = 0; l < members; ++l)
        if (!ran || (!sys.is_live(l) && !ended[l])) out[l] = {};
    return out;
}

// The lane system of the scene's form (with the Taylor method, its coefficients too) over the
// started members, integrated by run_system.
template <class Method>
std::vector<lane_run> integrate_lanes(const prepared_scene& prepared, const lane_kernels& k,
                                      lane_batch& b, const Method& method) {
    const std::size_t members = b.member_of.size(), n = static_cast<std::size_t>(b.y0[0].size());
    const std::size_t lanes = (members + k.width - 1) / k.width * k.width;
    const std::vector<double> p = by_lane(b.parameters, lanes);
    std::vector<std::vector<double>> prepared_values;
    for (const auto& v : b.parameters) {
        prepared_values.emplace_back(k.prepared_size);
        k.prepare(v.data(), prepared_values.back().data());
    }
    const std::vector<double> w = by_lane(prepared_values, lanes);
    const auto kernel = [&k, &w, lanes](double t, const double* y, double* dydt) {
        k.rhs(w.data(), t, y, dydt, lanes);
    };
    const auto run = [&](auto& sys) {
        for (std::size_t l = members; l < lanes; ++l)
            sys.stop(l);
        return run_system(prepared, b, sys, method);
    };
    if constexpr (std::is_same_v<Method, taylor<double>>) {
        const auto coefficients = [&k, &p, lanes](double t, double* c, int order) {
            return k.taylor(p.data(), t, c, order, lanes) != 0; // whether all are finite
        };
        lane_taylor_system<double, decltype(kernel), decltype(coefficients)> sys(
            kernel, coefficients, n, lanes);
        return run(sys);
    } else {
        lane_system<double, decltype(kernel)> sys(kernel, n, lanes);
        return run(sys);
    }
}

} // namespace

bool lanes_run(const std::string& method) {
    return method == "rk4" || method == "dop853" || method == "taylor";
}

void lane_check(const scene_spec& scene) {
    const std::string& m = scene.integrator.method;
    if (scene.sensitivities.active())
        throw user_error(scene.sensitivities.where,
                         "--lanes does not integrate sensitivities; run the sweep without --lanes");
    if (!lanes_run(m))
        throw user_error(scene.integrator_where,
                         "--lanes needs the method rk4, dop853 or taylor, not " + m +
                             " (or run the sweep without --lanes)");
}

lane_kernels compile_lanes(const prepared_scene& prepared, stage_timings& timings,
                           std::size_t lanes) {
#ifndef ROTGEN_HAVE_XSIMD
    (void)prepared, (void)timings, (void)lanes;
    throw user_error({"rotgen sweep"}, "--lanes: this rotgen was built without xsimd "
                                       "(libxsimd-dev); run the sweep without --lanes");
#else
    const compiled_form& cf = prepared.compiled(prepared.scene().form, timings, nullptr);
    const auto [flags, arch] = lane_target(prepared.scene().integrator.method, lanes);
    lane_kernels k;
    k.arch = arch;
    const std::string source = lane_source(cf);
    k.lib = timings.time("compile", cf.unit + " lanes",
                         [&] { return compile_and_load(source, cf.unit + "_lanes", flags); });
    k.rhs = reinterpret_cast<lane_kernels::kernel>(k.lib.symbol("rotgen_rhs_lanes"));
    using width_fn = unsigned long (*)();
    k.width = reinterpret_cast<width_fn>(k.lib.symbol("rotgen_lane_width"))();
    k.prepare = cf.prepare, k.prepared_size = cf.prepared_size();
    if (cf.sys.tay)
        k.taylor =
            reinterpret_cast<lane_kernels::taylor_kernel>(k.lib.symbol("rotgen_taylor_lanes"));
    return k;
#endif
}

// What the scene's tolerance is relative to: the layout of its form's state (compiled already).
static error_layout layout_of(const prepared_scene& prepared) {
    stage_timings timings;
    const scene_spec& scene = prepared.scene();
    return tolerance_layout(prepared.compiled(scene.form, timings, nullptr).f.state, scene);
}

std::vector<std::optional<run_result>> run_lanes(const prepared_scene& prepared,
                                                 const lane_kernels& kernels,
                                                 const std::vector<member_values>& members) {
    std::vector<std::optional<run_result>> results(members.size());
    for (const event_spec& e : prepared.scene().events)
        if (e.periodic) return results; // every member meets a time event: all run alone
    lane_batch b = start_members(prepared, members);
    if (b.member_of.empty()) return results;
    const integrator_spec& ig = prepared.scene().integrator;
    const long max_steps = ig.max_steps;
    const double step = ig.fixed_step() ? ig.step : 0.0;
    std::vector<lane_run> lanes;
    if (ig.method == "rk4") {
        rk4<double> m;
        m.step = ig.step;
        m.max_steps = static_cast<std::size_t>(max_steps);
        lanes = integrate_lanes(prepared, kernels, b, m);
    } else if (ig.method == "taylor") {
        taylor<double> m;
        m.rtol = ig.rtol, m.atol = ig.atol, m.step = step;
        calibrate(m, layout_of(prepared));
        m.max_steps = static_cast<std::size_t>(max_steps);
        lanes = integrate_lanes(prepared, kernels, b, m);
    } else {
        dop853<double> m(ig.rtol, ig.atol);
        m.fixed_step = step;
        calibrate(m, layout_of(prepared));
        m.max_steps = static_cast<std::size_t>(max_steps);
        lanes = integrate_lanes(prepared, kernels, b, m);
    }
    for (std::size_t m = 0; m < members.size(); ++m) {
        const std::size_t l = b.lane_of[m];
        if (l != lane_batch::alone && !lanes[l].s.empty())
            results[m] = b.parts[m]->finish(lanes[l].s, lanes[l].stats, std::move(lanes[l].events),
                                            lanes[l].stopped_by);
    }
    return results;
}

} // namespace rotgen
