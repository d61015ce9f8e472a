// rotgen sweep across MPI ranks (built with ROTGEN_MPI): a static block per rank, the rest through
// an atomic counter in an MPI window on rank 0; each rank's main thread alone calls MPI. The design
// is written down in sweep/distribute.hpp.
#ifdef ROTGEN_HAVE_MPI

#include "support/error.hpp"
#include "sweep/distribute.hpp"
#include "sweep/journal.hpp"
#include "sweep/parallel.hpp"
#include "sweep/sharing.hpp"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <exception>
#include <iostream>
#include <list>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace rotgen {

struct mpi_session::counter_window {
    std::uint64_t* base = nullptr;
    MPI_Win win = MPI_WIN_NULL;
};

struct mpi_session::node_group {
    MPI_Comm comm = MPI_COMM_NULL;
};

namespace {

constexpr int results_tag = 3;
constexpr int message_tag = 4; // an error's text, to rank 0
constexpr std::size_t message_bytes = std::size_t(1)
                                      << 20;       // a message's outcomes (or one), at most
constexpr auto nap = std::chrono::milliseconds(1); // the main thread's sleep when nothing happens

// A main thread's sleep while a message it sends or receives is on its way (a large one moves on
// only in MPI calls at both ends): 50 us, doubled each time the message is still on its way, up to
// the 1 ms nap. On 16 cores, 4 ranks of 4 threads with lanes took 0.23 s with the 1 ms nap where
// 50 us took 0.18 s (rank 0 then blocked in MPI_Recv). A fixed 50 us, though, woke a main thread
// up to 20 times while its message waited for rank 0 to take it, on the core its worker needed:
// on 2 cores, `mpirun -n 2` sweeps took 4-8% longer than with this backoff (bench/results/
// sweep_naps.md).
class transfer_wait {
  public:
    void sleep() {
        std::this_thread::sleep_for(m_wait);
        m_wait = std::min(2 * m_wait, std::chrono::microseconds(nap));
    }
    void reset() { m_wait = first; }

  private:
    static constexpr std::chrono::microseconds first{50};
    std::chrono::microseconds m_wait = first;
};

bool started_by_mpirun() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
        if (std::getenv(v)) return true;
    return false;
}

using range = group_range;

// The MPI window on rank 0, two numbers: the next group to hand out, and rank 0's front (the
// members it has written). Every access is atomic (MPI_Fetch_and_op), with passive target.
class shared_counter {
  public:
    shared_counter(const mpi_session& s, std::uint64_t next) : m_win(s.counter()->win) {
        if (s.rank() == 0) {
            op(0, next, MPI_REPLACE);
            op(1, 0, MPI_REPLACE);
        }
        MPI_Barrier(MPI_COMM_WORLD); // no one reads before they are set
    }
    std::uint64_t next() { return op(0, 0, MPI_NO_OP); }
    std::uint64_t fetch_add(std::uint64_t n) { return op(0, n, MPI_SUM); }
    std::uint64_t front() { return op(1, 0, MPI_NO_OP); }
    void publish_front(std::uint64_t members) { op(1, members, MPI_REPLACE); }

  private:
    std::uint64_t op(MPI_Aint slot, std::uint64_t value, MPI_Op what) {
        std::uint64_t old = 0;
        MPI_Fetch_and_op(&value, &old, MPI_UINT64_T, 0, slot, what, m_win);
        MPI_Win_flush(0, m_win);
        return old;
    }
    MPI_Win m_win;
};

// The chunks a rank's threads take groups from (in order), filled by its main thread; and the
// main thread's sleep, cut short when a chunk runs out or the threads finish or fail.
class local_queue {
  public:
    // The next group (waits for one); `none` once closed and empty.
    std::size_t take() {
        std::unique_lock<std::mutex> lock(m_mutex);
        m_more.wait(lock, [&] { return !m_chunks.empty() || m_closed; });
        if (m_chunks.empty()) return none;
        const std::size_t g = m_chunks.front().first++;
        if (m_chunks.front().first == m_chunks.front().second) {
            m_chunks.pop_front();
            m_event = true;
            m_main.notify_one();
        }
        return g;
    }
    void push(range r) {
        const std::lock_guard<std::mutex> lock(m_mutex);
        if (r.first < r.second) m_chunks.push_back(r);
        m_more.notify_all();
    }
    void close() {
        const std::lock_guard<std::mutex> lock(m_mutex);
        m_closed = true;
        m_more.notify_all();
    }
    std::size_t depth() {
        const std::lock_guard<std::mutex> lock(m_mutex);
        return m_chunks.size();
    }
    void wake() {
        const std::lock_guard<std::mutex> lock(m_mutex);
        m_event = true;
        m_main.notify_one();
    }
    void sleep() {
        std::unique_lock<std::mutex> lock(m_mutex);
        m_main.wait_for(lock, nap, [&] { return m_event; });
        m_event = false;
    }

  private:
    std::mutex m_mutex;
    std::condition_variable m_more, m_main;
    std::deque<range> m_chunks;
    bool m_closed = false, m_event = false;
};

// A rank's threads, on a thread of their own (the main thread is MPI's): groups from the queue,
// each outcome to `out(member, outcome)`.
class rank_threads {
  public:
    using sink = std::function<void(std::size_t, member_outcome&&)>;
    rank_threads(unsigned jobs, const member_groups& gs, const batch_work& work, local_queue& queue,
                 sink out)
        : m_out(std::move(out)), m_thread([this, jobs, gs, &work, &queue] {
              try {
                  run_pool(
                      jobs, [&] { return queue.take(); },
                      [&](std::size_t g) { run(gs, g, work, queue); }, {});
              } catch (...) {
                  fail(std::current_exception(), queue);
              }
              m_finished = true;
              queue.wake();
          }) {}
    rank_threads(const rank_threads&) = delete;
    rank_threads& operator=(const rank_threads&) = delete;
    ~rank_threads() { m_thread.join(); }
    bool finished() const { return m_finished; }
    // Ends every rank (MPI_Abort) after one line on standard error if a thread failed.
    void check(int rank) const;

  private:
    void run(const member_groups& gs, std::size_t g, const batch_work& work, local_queue& queue) {
        try {
            std::vector<member_outcome> o = work(gs.first(g), gs.members(g));
            for (std::size_t k = 0; k < o.size(); ++k)
                m_out(gs.first(g) + k, std::move(o[k]));
        } catch (...) { // the other threads may be waiting for work: the main thread ends them
            fail(std::current_exception(), queue);
            throw;
        }
    }
    void fail(std::exception_ptr e, local_queue& queue) {
        {
            const std::lock_guard<std::mutex> lock(m_mutex);
            if (!m_failure) m_failure = std::move(e);
        }
        m_failed = true;
        queue.wake();
    }
    sink m_out;
    mutable std::mutex m_mutex;
    std::exception_ptr m_failure;
    std::atomic<bool> m_failed{false}, m_finished{false};
    std::thread m_thread; // last: started when the rest is ready
};

// An internal error (a writer's too) ends every rank, or the others would wait forever: one line,
// rank 0's journal cut back to its last whole chunk (as an interruption leaves it), MPI_Abort.
[[noreturn]] void abort_all(std::exception_ptr e, int rank) {
    std::string what = "an unknown failure";
    try {
        std::rethrow_exception(e);
    } catch (const user_error& u) {
        what = u.message();
    } catch (const std::exception& x) {
        what = x.what();
    } catch (...) {
    }
    std::cerr << "rotgen: error: " << what << " (MPI rank " << rank << ")\n" << std::flush;
    if (rank == 0) journal_abandon(0);
    MPI_Abort(MPI_COMM_WORLD, 1);
    std::abort(); // not reached
}

void rank_threads::check(int rank) const {
    if (!m_failed) return;
    const std::lock_guard<std::mutex> lock(m_mutex);
    abort_all(m_failure, rank);
}

// The main thread's side of a rank's queue: it keeps jobs + 1 chunks ahead (fetched from the
// counter), and passes a fetched chunk on to the threads when its members fit rank 0's window.
struct feeder {
    const sharing& sh;
    shared_counter& counter;
    local_queue& queue;
    std::deque<range> fetched; // not yet in the queue: waiting for the window
    std::size_t front = 0;     // rank 0's front, as last seen
    bool exhausted = false;

    void fetch_ahead() {
        while (!exhausted && queue.depth() + fetched.size() < sh.jobs + 1) {
            if (const std::optional<range> r = take_chunk(sh, counter))
                fetched.push_back(*r);
            else
                exhausted = true;
        }
    }
    template <class Front> void admit(const Front& read_front) {
        while (!fetched.empty()) {
            const std::size_t end = sh.gs.end(fetched.front().second);
            if (end > front + sh.window && end > (front = read_front()) + sh.window) break;
            queue.push(fetched.front());
            fetched.pop_front();
        }
        if (exhausted && fetched.empty()) queue.close();
    }
};

// Waits for a collective without spinning: a blocking MPI call keeps a core busy, and the ranks
// waiting for rank 0 to prepare (a compilation, on a cold kernel cache) would take the cores it
// needs when there are fewer cores than ranks.
void wait_quietly(MPI_Request& r) {
    for (int flag = 0; MPI_Test(&r, &flag, MPI_STATUS_IGNORE) == MPI_SUCCESS && !flag;)
        std::this_thread::sleep_for(nap);
}

// Waits for every rank without spinning.
void quiet_barrier() {
    MPI_Request r;
    MPI_Ibarrier(MPI_COMM_WORLD, &r);
    wait_quietly(r);
}

// Rank 0's receipt of the other ranks' outcomes. A message is taken (MPI_Imrecv) as soon as it is
// seen and delivered once it has arrived, so that the main thread never waits for a transfer: a
// message above MPI's eager size moves only when its sender's main thread calls MPI, and a blocking
// MPI_Recv here waited for it while rank 0's threads ran out of work (on 16 cores, 4 ranks of 4
// threads with lanes spent 0.2 s of a 0.23 s run in MPI_Recv).
class receiver {
  public:
    // Takes every message that has come, and delivers one that has arrived into `out` (one at a
    // time: between two, the main thread keeps its own threads' queue filled). Returns how many
    // outcomes it delivered.
    std::size_t poll(in_order& out) {
        take_new();
        for (auto it = m_pending.begin(); it != m_pending.end(); ++it) {
            int flag = 0;
            MPI_Test(&it->second, &flag, MPI_STATUS_IGNORE);
            if (!flag) continue;
            const std::string buffer = std::move(it->first);
            m_pending.erase(it);
            std::size_t got = 0;
            for (auto& [m, o] : unpack(buffer)) {
                out.deliver(m, std::move(o));
                ++got;
            }
            return got;
        }
        return 0;
    }
    bool waiting() const { return !m_pending.empty(); } // a message is on its way

  private:
    void take_new() {
        for (;;) {
            int flag = 0;
            MPI_Message message;
            MPI_Status st;
            MPI_Improbe(MPI_ANY_SOURCE, results_tag, MPI_COMM_WORLD, &flag, &message, &st);
            if (!flag) return;
            int bytes = 0;
            MPI_Get_count(&st, MPI_BYTE, &bytes);
            m_pending.push_back({std::string(std::size_t(bytes), '\0'), MPI_REQUEST_NULL});
            auto& [buffer, request] = m_pending.back();
            MPI_Imrecv(buffer.data(), bytes, MPI_BYTE, &message, &request);
        }
    }
    std::list<std::pair<std::string, MPI_Request>> m_pending; // node-based: buffers stay put
};

// Rank 0: its threads deliver into `out`; its main thread receives the others' outcomes into it
// and publishes its front.
void run_root(const mpi_session& s, const sharing& sh, const batch_work& work, in_order& out,
              const std::function<void(std::size_t)>& progress) {
    shared_counter counter(s, sh.dynamic_start());
    local_queue queue;
    feeder feed{sh, counter, queue, {}};
    feed.fetched.push_back(sh.first_block(0));
    receiver incoming;
    {
        rank_threads threads(
            unsigned(sh.jobs), sh.gs, work, queue,
            [&](std::size_t m, member_outcome&& o) { out.deliver(m, std::move(o)); });
        std::uint64_t published = 0;
        auto last = std::chrono::steady_clock::now();
        transfer_wait transfer;
        try {
            while (!(threads.finished() && out.done() == sh.gs.count)) {
                threads.check(0);
                feed.fetch_ahead();
                feed.admit([&] { return out.done(); });
                const std::size_t got = incoming.poll(out);
                if (out.done() != published) counter.publish_front(published = out.done());
                if (std::chrono::steady_clock::now() - last > std::chrono::milliseconds(100)) {
                    progress(out.done());
                    last = std::chrono::steady_clock::now();
                }
                if (got == 0 && incoming.waiting()) {
                    transfer.sleep(); // it moves on in MPI calls
                    continue;
                }
                transfer.reset();
                if (got == 0) queue.sleep();
            }
        } catch (...) { // the writer failed
            abort_all(std::current_exception(), 0);
        }
        threads.check(0);
    } // the threads joined
    quiet_barrier();
}

// The outcomes a rank's threads finished, for its main thread to send.
class outbox {
  public:
    void add(std::size_t m, member_outcome&& o) {
        const std::lock_guard<std::mutex> lock(m_mutex);
        m_items.emplace_back(m, std::move(o));
    }
    std::vector<std::pair<std::size_t, member_outcome>> take() {
        const std::lock_guard<std::mutex> lock(m_mutex);
        return std::exchange(m_items, {});
    }

  private:
    std::mutex m_mutex;
    std::vector<std::pair<std::size_t, member_outcome>> m_items;
};

// The bytes an outcome takes in a message, about.
std::size_t packed_size(const member_outcome& o) {
    return 64 + o.status.size() + o.summary_row.size() + 8 * o.trajectory.size();
}

// Messages on their way to rank 0 (MPI_Isend), each kept until it is delivered.
class sender {
  public:
    // Sends `items` in messages of at most message_bytes (or one outcome).
    void send(std::vector<std::pair<std::size_t, member_outcome>>&& items) {
        std::vector<std::pair<std::size_t, member_outcome>> batch;
        std::size_t bytes = 0;
        for (std::size_t k = 0; k < items.size(); ++k) {
            bytes += packed_size(items[k].second);
            batch.push_back(std::move(items[k]));
            if (bytes >= message_bytes || k + 1 == items.size()) {
                m_sending.push_back({pack(batch), MPI_REQUEST_NULL});
                auto& [buffer, request] = m_sending.back();
                MPI_Isend(buffer.data(), int(buffer.size()), MPI_BYTE, 0, results_tag,
                          MPI_COMM_WORLD, &request);
                batch.clear();
                bytes = 0;
            }
        }
    }
    // Whether every message has been delivered (forgets those that have).
    bool idle() {
        for (auto it = m_sending.begin(); it != m_sending.end();) {
            int flag = 0;
            MPI_Test(&it->second, &flag, MPI_STATUS_IGNORE);
            it = flag ? m_sending.erase(it) : std::next(it);
        }
        return m_sending.empty();
    }

  private:
    std::list<std::pair<std::string, MPI_Request>> m_sending;
};

// A rank other than 0: its threads' outcomes go to rank 0.
void run_other(const mpi_session& s, const sharing& sh, const batch_work& work) {
    shared_counter counter(s, 0);
    local_queue queue;
    feeder feed{sh, counter, queue, {}};
    feed.fetched.push_back(sh.first_block(std::size_t(s.rank())));
    outbox box;
    sender sends;
    {
        rank_threads threads(unsigned(sh.jobs), sh.gs, work, queue,
                             [&](std::size_t m, member_outcome&& o) { box.add(m, std::move(o)); });
        transfer_wait transfer;
        for (;;) {
            threads.check(s.rank());
            feed.fetch_ahead();
            feed.admit([&] { return counter.front(); });
            const bool finished = threads.finished(); // before the last outcomes are taken
            sends.send(box.take());
            const bool idle = sends.idle();
            if (idle && finished) break;
            if (!idle) { // a large message moves on only in this thread's MPI calls
                transfer.sleep();
                continue;
            }
            transfer.reset();
            queue.sleep();
        }
        threads.check(s.rank());
    }
    quiet_barrier();
}

// Every rank's share of the run, on rank 0 (rank order); the others get nothing.
std::vector<rank_work> gather(const mpi_session& s, const rank_work& mine) {
    const double sent[4] = {double(mine.members), mine.busy, mine.first, mine.last};
    std::vector<double> got(s.rank() == 0 ? 4 * std::size_t(s.size()) : 0);
    MPI_Request r;
    MPI_Igather(sent, 4, MPI_DOUBLE, got.data(), 4, MPI_DOUBLE, 0, MPI_COMM_WORLD, &r);
    wait_quietly(r);
    std::vector<rank_work> all;
    for (std::size_t k = 0; k < got.size(); k += 4)
        all.push_back({std::size_t(got[k]), got[k + 1], got[k + 2], got[k + 3]});
    return all;
}

} // namespace

mpi_session::mpi_session() {
    if (!started_by_mpirun()) return;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m_size);
    m_active = true;
    m_node = std::make_unique<node_group>();
    MPI_Comm& node = m_node->comm;
    // ROTGEN_TEST_NODE=K, the tests' hook: the ranks that give the same K play one node
    if (const char* k = std::getenv("ROTGEN_TEST_NODE"))
        MPI_Comm_split(MPI_COMM_WORLD, std::atoi(k), m_rank, &node);
    else
        MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    MPI_Comm_rank(node, &m_node_rank);
    MPI_Comm_size(node, &m_node_size);
    if (m_size == 1) return;
    m_counter = std::make_unique<counter_window>();
    MPI_Win_allocate(MPI_Aint(m_rank == 0 ? 2 * sizeof(std::uint64_t) : 0), sizeof(std::uint64_t),
                     MPI_INFO_NULL, MPI_COMM_WORLD, &m_counter->base, &m_counter->win);
    MPI_Win_lock_all(MPI_MODE_NOCHECK, m_counter->win);
}

mpi_session::~mpi_session() {
    if (m_counter) {
        MPI_Win_unlock_all(m_counter->win);
        MPI_Win_free(&m_counter->win);
    }
    if (m_node) MPI_Comm_free(&m_node->comm);
    if (m_active) MPI_Finalize();
}

std::vector<unsigned char> mpi_session::node_union(std::vector<unsigned char> bits) const {
    if (!m_node || m_node_size == 1) return bits;
    MPI_Request r;
    MPI_Iallreduce(MPI_IN_PLACE, bits.data(), int(bits.size()), MPI_BYTE, MPI_BOR, m_node->comm,
                   &r);
    wait_quietly(r);
    return bits;
}

std::size_t mpi_session::broadcast(std::size_t value) const {
    if (!m_active) return value;
    std::uint64_t v = value;
    MPI_Request r;
    MPI_Ibcast(&v, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &r);
    wait_quietly(r);
    return std::size_t(v);
}

std::size_t mpi_session::least(std::size_t value) const {
    if (!m_active) return value;
    std::uint64_t mine = value, least = 0;
    MPI_Request r;
    MPI_Iallreduce(&mine, &least, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD, &r);
    wait_quietly(r);
    return std::size_t(least);
}

std::string mpi_session::first_message(const std::string& mine) const {
    if (!m_active) return mine;
    const auto none = std::size_t(m_size);
    const std::size_t from = least(mine.empty() ? none : std::size_t(m_rank));
    if (from == none || (m_rank != 0 && std::size_t(m_rank) != from)) return "";
    if (from == 0) return mine; // rank 0's own
    if (m_rank != 0) {
        MPI_Send(mine.data(), int(mine.size()), MPI_CHAR, 0, message_tag, MPI_COMM_WORLD);
        return "";
    }
    MPI_Status st;
    MPI_Probe(int(from), message_tag, MPI_COMM_WORLD, &st);
    int n = 0;
    MPI_Get_count(&st, MPI_CHAR, &n);
    std::string text(std::size_t(n), '\0');
    MPI_Recv(text.data(), n, MPI_CHAR, int(from), message_tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return text;
}

std::string mpi_session::name() const {
    if (!m_active) return "this process";
    char host[MPI_MAX_PROCESSOR_NAME] = {};
    int length = 0;
    MPI_Get_processor_name(host, &length);
    return "MPI rank " + std::to_string(m_rank) + " on " + std::string(host, std::size_t(length));
}

bool mpi_session::all(bool ok) const {
    if (!m_active) return ok;
    int mine = ok ? 1 : 0, every = 0;
    MPI_Request r;
    MPI_Iallreduce(&mine, &every, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &r);
    wait_quietly(r);
    return every == 1;
}

std::vector<rank_work> run_distributed(const mpi_session& s, std::size_t count, std::size_t group,
                                       unsigned jobs, const batch_work& work, in_order* out,
                                       const std::function<void(std::size_t)>& progress,
                                       work_clock::time_point start) {
    if (s.size() == 1) return run_in_process(count, group, jobs, work, *out, progress, start);
    // every rank computes the same sharing (the same count, group and -j; rank 0's window)
    const sharing sh{{count, group},
                     s.broadcast(s.rank() == 0 ? out->window() : 0),
                     std::size_t(s.size()),
                     std::max<std::size_t>(1, jobs)};
    work_clock clock(start);
    if (s.rank() == 0)
        run_root(s, sh, clock.wrap(work), *out, progress);
    else
        run_other(s, sh, clock.wrap(work));
    return gather(s, clock.read());
}

} // namespace rotgen

#endif
