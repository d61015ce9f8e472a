// rotgen sweep: what one process and every rank share (pack/unpack, the members on this process's
// threads), and the build without MPI. The MPI build's ranks: distribute_mpi.cpp.
#include "sweep/distribute.hpp"

#include "sweep/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>

namespace rotgen {

namespace {

template <class T> void put(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T> T get(const std::string& in, std::size_t& at) {
    if (at + sizeof(T) > in.size()) throw std::runtime_error("sweep: a truncated MPI message");
    T v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
}

void put_doubles(std::string& out, const std::vector<double>& v) {
    put<std::uint64_t>(out, v.size());
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

std::vector<double> get_doubles(const std::string& in, std::size_t& at) {
    std::vector<double> v(get<std::uint64_t>(in, at));
    if (at + v.size() * sizeof(double) > in.size())
        throw std::runtime_error("sweep: a truncated MPI message");
    std::memcpy(v.data(), in.data() + at, v.size() * sizeof(double));
    at += v.size() * sizeof(double);
    return v;
}

void put_string(std::string& out, const std::string& s) {
    put<std::uint64_t>(out, s.size());
    out += s;
}

std::string get_string(const std::string& in, std::size_t& at) {
    const std::size_t n = get<std::uint64_t>(in, at);
    if (at + n > in.size()) throw std::runtime_error("sweep: a truncated MPI message");
    at += n;
    return in.substr(at - n, n);
}

// Runs group g, each outcome to slot(member, outcome).
template <class Slot>
void run_group(const member_groups& gs, std::size_t g, const batch_work& work, const Slot& slot) {
    std::vector<member_outcome> o = work(gs.first(g), gs.members(g));
    for (std::size_t k = 0; k < o.size(); ++k)
        slot(gs.first(g) + k, std::move(o[k]));
}

// The groups this process takes (take() gives the next, or one past the last), on its threads,
// each admitted by the window `out` before it starts and its outcomes delivered to it; `done`
// counts the members.
void run_here(const std::function<std::size_t()>& take, const member_groups& gs, unsigned jobs,
              const batch_work& work, in_order& out, std::atomic<std::size_t>& done,
              const std::function<void()>& tick) {
    run_pool(
        jobs,
        [&] {
            const std::size_t g = take();
            if (g >= gs.size()) return none;
            return out.admit(gs.first(g) + gs.members(g)) ? g : none;
        },
        [&](std::size_t g) {
            try {
                run_group(gs, g, work, [&](std::size_t m, member_outcome o) {
                    out.deliver(m, std::move(o));
                    ++done;
                });
            } catch (...) {
                out.stop(); // the threads waiting for the window stop too
                throw;
            }
        },
        tick);
}

} // namespace

std::string pack(const std::vector<std::pair<std::size_t, member_outcome>>& outcomes) {
    std::string out;
    put<std::uint64_t>(out, outcomes.size());
    for (const auto& [m, o] : outcomes) {
        put<std::uint64_t>(out, m);
        put_string(out, o.summary_row);
        put<std::uint64_t>(out, o.steps);
        put<std::uint64_t>(out, o.rhs_evals);
        put_string(out, o.status);
        put<std::uint8_t>(out, o.in_lanes ? 1 : 0);
        put_doubles(out, o.trajectory);
    }
    return out;
}

std::vector<rank_work> run_in_process(std::size_t count, std::size_t group, unsigned jobs,
                                      const batch_work& work, in_order& out,
                                      const std::function<void(std::size_t)>& progress,
                                      work_clock::time_point start) {
    const member_groups gs{count, group};
    std::atomic<std::size_t> next{0}, done{0};
    work_clock clock(start);
    run_here([&] { return next++; }, gs, jobs, clock.wrap(work), out, done,
             [&] { progress(done); });
    return {clock.read()};
}

std::vector<std::pair<std::size_t, member_outcome>> unpack(const std::string& in) {
    std::size_t at = 0;
    std::vector<std::pair<std::size_t, member_outcome>> outcomes(get<std::uint64_t>(in, at));
    for (auto& [m, o] : outcomes) {
        m = get<std::uint64_t>(in, at);
        o.summary_row = get_string(in, at);
        o.steps = get<std::uint64_t>(in, at);
        o.rhs_evals = get<std::uint64_t>(in, at);
        o.status = get_string(in, at);
        o.in_lanes = get<std::uint8_t>(in, at) != 0;
        o.trajectory = get_doubles(in, at);
    }
    return outcomes;
}

#ifndef ROTGEN_HAVE_MPI

struct mpi_session::counter_window {};
struct mpi_session::node_group {};
mpi_session::mpi_session() = default;
mpi_session::~mpi_session() = default;
bool mpi_session::all(bool ok) const {
    return ok;
}
std::size_t mpi_session::broadcast(std::size_t value) const {
    return value;
}
std::size_t mpi_session::least(std::size_t value) const {
    return value;
}
std::vector<unsigned char> mpi_session::node_union(std::vector<unsigned char> bits) const {
    return bits;
}
std::string mpi_session::first_message(const std::string& mine) const {
    return mine;
}
std::string mpi_session::name() const {
    return "this process";
}

std::vector<rank_work> run_distributed(const mpi_session&, std::size_t count, std::size_t group,
                                       unsigned jobs, const batch_work& work, in_order* out,
                                       const std::function<void(std::size_t)>& progress,
                                       work_clock::time_point start) {
    return run_in_process(count, group, jobs, work, *out, progress, start);
}

#endif // the MPI build: distribute_mpi.cpp

} // namespace rotgen
