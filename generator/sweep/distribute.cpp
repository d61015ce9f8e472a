#include "sweep/distribute.hpp"

#include "sweep/parallel.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>

#ifdef ROTGEN_HAVE_MPI
#include <mpi.h>

#include <chrono>
#include <thread>
#endif

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

// The groups of `group` members (the last may be shorter) of members 0 .. count-1.
struct groups {
    std::size_t count, group;
    std::size_t size() const { return (count + group - 1) / group; }
    std::size_t first(std::size_t g) const { return g * group; }
    std::size_t members(std::size_t g) const { return std::min(group, count - g * group); }
};

// Runs group g, each outcome to slot(member, outcome).
template <class Slot>
void run_group(const groups& gs, std::size_t g, const batch_work& work, const Slot& slot) {
    std::vector<member_outcome> o = work(gs.first(g), gs.members(g));
    for (std::size_t k = 0; k < o.size(); ++k)
        slot(gs.first(g) + k, std::move(o[k]));
}

// The groups this process takes (take() gives the next, or one past the last), on its threads,
// each admitted by the window `out` before it starts and its outcomes delivered to it; `done`
// counts the members.
void run_here(const std::function<std::size_t()>& take, const groups& gs, unsigned jobs,
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

// One process: every member on this process's threads.
std::vector<std::size_t> run_here(const groups& gs, unsigned jobs, const batch_work& work,
                                  in_order& out, const std::function<void(std::size_t)>& progress) {
    std::atomic<std::size_t> next{0}, done{0};
    run_here([&] { return next++; }, gs, jobs, work, out, done, [&] { progress(done); });
    return {done};
}

} // namespace

std::string pack(const std::vector<std::pair<std::size_t, member_outcome>>& outcomes) {
    std::string out;
    put<std::uint64_t>(out, outcomes.size());
    for (const auto& [m, o] : outcomes) {
        put<std::uint64_t>(out, m);
        put_doubles(out, o.final_row);
        put_doubles(out, o.drifts);
        put_doubles(out, o.event_times);
        put<std::uint64_t>(out, o.steps);
        put<std::uint64_t>(out, o.rhs_evals);
        put<std::uint64_t>(out, o.status.size());
        out += o.status;
        put<std::uint8_t>(out, o.in_lanes ? 1 : 0);
        put_doubles(out, o.trajectory);
    }
    return out;
}

std::vector<std::pair<std::size_t, member_outcome>> unpack(const std::string& in) {
    std::size_t at = 0;
    std::vector<std::pair<std::size_t, member_outcome>> outcomes(get<std::uint64_t>(in, at));
    for (auto& [m, o] : outcomes) {
        m = get<std::uint64_t>(in, at);
        o.final_row = get_doubles(in, at);
        o.drifts = get_doubles(in, at);
        o.event_times = get_doubles(in, at);
        o.steps = get<std::uint64_t>(in, at);
        o.rhs_evals = get<std::uint64_t>(in, at);
        const std::size_t n = get<std::uint64_t>(in, at);
        if (at + n > in.size()) throw std::runtime_error("sweep: a truncated MPI message");
        o.status = in.substr(at, n);
        at += n;
        o.in_lanes = get<std::uint8_t>(in, at) != 0;
        o.trajectory = get_doubles(in, at);
    }
    return outcomes;
}

#ifndef ROTGEN_HAVE_MPI

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

std::vector<std::size_t> run_distributed(const mpi_session&, std::size_t count, std::size_t group,
                                         unsigned jobs, const batch_work& work, in_order* out,
                                         const std::function<void(std::size_t)>& progress) {
    return run_here(groups{count, group}, jobs, work, *out, progress);
}

#else

namespace {

enum tag : int { request = 1, assignment = 2, results = 3 };

bool started_by_mpirun() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
        if (std::getenv(v)) return true;
    return false;
}

// The outcomes of a chunk of groups, run on the threads; `sent` (the previous chunk's outcomes,
// long delivered by then) is completed before they are returned to be sent.
std::vector<std::pair<std::size_t, member_outcome>>
run_chunk(const groups& gs, const std::array<std::uint64_t, 2>& chunk, unsigned jobs,
          const batch_work& work, MPI_Request& sent) {
    const std::size_t first = gs.first(chunk[0]);
    std::vector<std::pair<std::size_t, member_outcome>> out(std::min(gs.count, gs.first(chunk[1])) -
                                                            first);
    std::atomic<std::size_t> next{chunk[0]};
    run_pool(
        jobs,
        [&] {
            const std::size_t g = next++;
            return g < chunk[1] ? g : none;
        },
        [&](std::size_t g) {
            run_group(gs, g, work, [&](std::size_t m, member_outcome o) {
                out[m - first] = {m, std::move(o)};
            });
        },
        {});
    MPI_Wait(&sent, MPI_STATUS_IGNORE);
    return out;
}

// Requests a worker keeps in flight: it asks for its next chunks before it runs the current one,
// two ahead, so that an answer is at hand when the chunk is done. Rank 0's main thread answers when
// it wakes (every millisecond, later when both cores are busy): with one request ahead, a worker
// on the 1,024-member heavy top waited 11 ms of its 84 for chunks near the end, where they are
// short.
constexpr int ahead = 2;

// A rank other than 0: runs the chunks of groups rank 0 assigns, on the threads, and sends their
// outcomes, until told that the queue is empty (an empty chunk, the answer to each of its last
// `ahead` requests). The outcomes go without waiting (MPI_Isend), completed after the next chunk:
// a blocking send waited for rank 0's main thread (in Open MPI even a message of 350 bytes did:
// 14 ms of a 1,024-member heavy-top sweep's 86).
void serve_as_worker(std::uint64_t rank, const groups& gs, unsigned jobs, const batch_work& work) {
    std::array<std::array<std::uint64_t, 2>, ahead> chunks{};
    std::array<MPI_Request, ahead> pending{};
    const auto ask = [&](std::size_t slot) {
        MPI_Send(nullptr, 0, MPI_BYTE, 0, request, MPI_COMM_WORLD);
        MPI_Irecv(chunks[slot].data(), 2, MPI_UINT64_T, 0, assignment, MPI_COMM_WORLD,
                  &pending[slot]);
    };
    for (std::size_t slot = 0; slot < ahead; ++slot)
        ask(slot);
    std::string bytes; // the outcomes being sent
    MPI_Request sent = MPI_REQUEST_NULL;
    if (rank < gs.size()) { // its own first group, asked of no one
        bytes = pack(run_chunk(gs, {rank, rank + 1}, jobs, work, sent));
        MPI_Isend(bytes.data(), int(bytes.size()), MPI_BYTE, 0, results, MPI_COMM_WORLD, &sent);
    }
    for (std::size_t slot = 0;; slot = (slot + 1) % ahead) {
        MPI_Wait(&pending[slot], MPI_STATUS_IGNORE); // answers come in the order asked
        const std::array<std::uint64_t, 2> chunk = chunks[slot];
        if (chunk[0] == chunk[1]) break;
        ask(slot);
        bytes = pack(run_chunk(gs, chunk, jobs, work, sent));
        MPI_Isend(bytes.data(), int(bytes.size()), MPI_BYTE, 0, results, MPI_COMM_WORLD, &sent);
    }
    MPI_Waitall(ahead, pending.data(), MPI_STATUSES_IGNORE); // the other empty answers
    MPI_Wait(&sent, MPI_STATUS_IGNORE);
}

// Rank 0's side of the queue: the chunks of groups it hands out (in group order, each sent only
// when its members fit the window, so that no rank runs ahead of the writer by more than the
// window), and the members each rank ran.
struct coordinator {
    const mpi_session& s;
    const groups& gs;
    std::atomic<std::size_t>& next; // the next group, shared with rank 0's threads
    in_order& out;
    std::vector<std::size_t> ran;                                      // members per rank
    std::vector<std::pair<int, std::array<std::uint64_t, 2>>> waiting; // chunks not yet sent
    int finished = 0; // empty chunks sent: `ahead` to each worker rank at the end

    // The next chunk: remaining / (4 ranks) groups, at most an eighth of the window per rank.
    std::array<std::uint64_t, 2> take() {
        const std::size_t count = gs.size(), ranks = std::size_t(s.size());
        const std::size_t remaining = count - std::min(count, next.load());
        const std::size_t most = std::max<std::size_t>(1, out.window() / gs.group / (8 * ranks));
        const std::size_t size = std::clamp<std::size_t>(remaining / (4 * ranks), 1, most);
        const std::size_t begin = std::min(count, next.fetch_add(size));
        return {begin, std::min(count, begin + size)};
    }
    // Sends the waiting chunks that fit the window, in order.
    void send_waiting() {
        std::size_t sent = 0;
        for (; sent < waiting.size(); ++sent) {
            const auto& [rank, chunk] = waiting[sent];
            const std::size_t end = std::min(gs.count, gs.first(chunk[1]));
            if (chunk[0] != chunk[1] && !out.fits(end)) break;
            if (chunk[0] == chunk[1]) ++finished;
            MPI_Send(chunk.data(), 2, MPI_UINT64_T, rank, assignment, MPI_COMM_WORLD);
        }
        waiting.erase(waiting.begin(), waiting.begin() + std::ptrdiff_t(sent));
    }
    // Answers every pending message (requests: a chunk; results: into the window).
    void answer() {
        for (int flag = 1; flag;) {
            MPI_Status st;
            MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
            if (!flag) break;
            int bytes = 0;
            MPI_Get_count(&st, MPI_BYTE, &bytes);
            std::string buffer(std::size_t(bytes), '\0');
            MPI_Recv(buffer.data(), bytes, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
            if (st.MPI_TAG == results) {
                for (auto& [m, o] : unpack(buffer)) {
                    out.deliver(m, std::move(o));
                    ++ran[std::size_t(st.MPI_SOURCE)];
                }
                continue;
            }
            waiting.emplace_back(st.MPI_SOURCE, take());
        }
        send_waiting();
    }
};

} // namespace

mpi_session::mpi_session() {
    if (!started_by_mpirun()) return;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m_size);
    m_active = true;
}

mpi_session::~mpi_session() {
    if (m_active) MPI_Finalize();
}

std::size_t mpi_session::broadcast(std::size_t value) const {
    if (!m_active) return value;
    std::uint64_t v = value;
    MPI_Bcast(&v, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    return std::size_t(v);
}

std::size_t mpi_session::least(std::size_t value) const {
    if (!m_active) return value;
    std::uint64_t mine = value, least = 0;
    MPI_Allreduce(&mine, &least, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
    return std::size_t(least);
}

bool mpi_session::all(bool ok) const {
    if (!m_active) return ok;
    int mine = ok ? 1 : 0, every = 0;
    MPI_Allreduce(&mine, &every, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return every == 1;
}

std::vector<std::size_t> run_distributed(const mpi_session& s, std::size_t count, std::size_t group,
                                         unsigned jobs, const batch_work& work, in_order* out,
                                         const std::function<void(std::size_t)>& progress) {
    const groups gs{count, group};
    if (s.size() == 1) return run_here(gs, jobs, work, *out, progress);
    if (s.rank() != 0) {
        serve_as_worker(std::uint64_t(s.rank()), gs, jobs, work);
        return {};
    }
    // rank r's first group is group r (every rank starts at once and runs members); the others
    // are shared, from group R on
    std::atomic<std::size_t> next{std::min(gs.size(), std::size_t(s.size()))}, done{0};
    std::atomic<bool> started{false};
    coordinator c{s, gs, next, *out, std::vector<std::size_t>(std::size_t(s.size()), 0), {}};
    std::exception_ptr failure;
    std::atomic<bool> stopped{false};
    std::thread local([&] {
        try {
            run_here([&] { return started.exchange(true) ? next++ : std::size_t(0); }, gs, jobs,
                     work, *out, done, {});
        } catch (...) {
            failure = std::current_exception();
        }
        stopped = true;
    });
    auto last = std::chrono::steady_clock::now();
    while (!(stopped && failure) && (c.finished < ahead * (s.size() - 1) || out->done() < count)) {
        c.answer();
        if (std::chrono::steady_clock::now() - last > std::chrono::milliseconds(100)) {
            progress(out->done());
            last = std::chrono::steady_clock::now();
        }
        std::this_thread::sleep_for(std::chrono::microseconds(1000));
    }
    local.join();
    if (failure) MPI_Abort(MPI_COMM_WORLD, 1); // an internal error: the other ranks would wait
    c.ran[0] = done;
    return c.ran;
}

#endif

} // namespace rotgen
