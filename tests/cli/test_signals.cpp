// Issue 24, "interrupted and piped runs leave nothing behind": SIGINT and SIGTERM print one line
// and exit 130 / 143 with every temporary removed; a reader that went away (SIGPIPE) ends the run
// quietly with 141. The signals come from the test hook ROTGEN_TEST_SIGNAL=NAME:STAGE
// (support/signals.hpp) or from a pipe closed before the run writes: nothing races a timer. A
// missing handler would show as a death by the signal (run_rotgen's status -1), not as an exit.
#include "files_support.hpp"
#include "support/signals.hpp"

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

// A short heavy-top scene with one event at t = 0.5, in `dir`/top.yaml.
void top_scene(const std::string& dir) {
    write_top_scene(dir + "/top.yaml",
                    "events: [{name: half, when: t - 0.5, direction: rising}]\n");
}

// `rotgen ARGS` in `dir` with ROTGEN_TEST_SIGNAL=hook.
run_result run_hooked(const std::string& hook, const std::string& args, const std::string& dir) {
    ::setenv("ROTGEN_TEST_SIGNAL", hook.c_str(), 1);
    run_result r = run_rotgen(args, dir);
    ::unsetenv("ROTGEN_TEST_SIGNAL");
    return r;
}

} // namespace

TEST_CASE("SIGTERM or SIGINT during a run: one line, exit 143 or 130, nothing left behind",
          "[cli][signals]") {
    const std::string dir = fresh_folder("signals_simulate");
    top_scene(dir);
    const std::string outputs = " -o out.csv --events ev.csv --plot p.png";
    for (const std::string stage : {"compile", "integrate"}) {
        INFO(stage);
        const run_result r = run_hooked("TERM:" + stage, "simulate top.yaml" + outputs, dir);
        CHECK(r.status == 143);
        CHECK(r.err == "rotgen: interrupted; nothing written\n");
        CHECK(entries_in(dir) == 1); // the scene: no output, no temporary
    }
    // after the CSV and the events were made, while the plot is drawn: the outputs appear
    // together once all are complete (issue 46), so none of them is there yet
    const run_result r = run_hooked("INT:plot", "simulate top.yaml" + outputs, dir);
    CHECK(r.status == 130);
    CHECK(r.err == "rotgen: interrupted; nothing written\n");
    CHECK(entries_in(dir) == 1); // no out.csv, ev.csv or p.png, no temporary
}

TEST_CASE("emit and bench interrupted: one line, the exit status, no folder made",
          "[cli][signals]") {
    const std::string dir = fresh_folder("signals_emit_bench");
    top_scene(dir);
    run_result r = run_hooked("INT:write", "emit '" + model_path("heavy_top") + "' -o hdr", dir);
    CHECK(r.status == 130);
    CHECK(r.err == "rotgen: interrupted; nothing written\n");
    r = run_hooked("TERM:derive", "bench top.yaml --quick -o bench", dir);
    CHECK(r.status == 143);
    CHECK(r.err == "rotgen: interrupted; nothing written\n");
    CHECK(entries_in(dir) == 1); // neither hdr/ nor bench/
}

TEST_CASE("a reader that went away ends the run quietly with 141, no temporary left",
          "[cli][signals]") {
    const std::string dir = fresh_folder("signals_pipe");
    top_scene(dir);
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    ::close(fds[0]); // the reader is gone before the run writes: every write gets SIGPIPE
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int err = ::open((dir + "/err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (::chdir(dir.c_str()) != 0 || err < 0) ::_exit(99);
        ::dup2(fds[1], 1);
        ::dup2(err, 2);
        ::execl(ROTGEN_EXE, ROTGEN_EXE, "simulate", "top.yaml", "-o", "-", "-q", nullptr);
        ::_exit(98);
    }
    ::close(fds[1]);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    CHECK(WIFEXITED(status)); // not killed by SIGPIPE: the handler ran
    CHECK(WEXITSTATUS(status) == 141);
    CHECK(read_file(dir + "/err.txt").empty());
    fs::remove(dir + "/err.txt");
    // top.events.csv's temporary was open while the CSV went into the pipe: removed
    CHECK(entries_in(dir) == 1);
}

namespace {

// The line a SIGTERM prints after `what` was done to the interrupt line's record of written files
// (in a child process, whose handler exits 143), and its exit status.
std::pair<int, std::string> line_after(const std::function<void()>& what) {
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ::dup2(fds[1], 2);
        rotgen::remove_temporaries_on_signal();
        what();
        ::raise(SIGTERM);
        ::_exit(99); // not reached: the handler exits
    }
    ::close(fds[1]);
    std::string text;
    char buf[512];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;)
        text.append(buf, std::size_t(n));
    ::close(fds[0]);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

} // namespace

// A file written and then removed again (a sweep's journal stamp when the sweep fails before any
// member finished) is no longer named by the interrupt line (sweep/writer.cpp).
TEST_CASE("the interrupt line names no file that was removed again", "[cli][signals]") {
    const auto removed = line_after([] {
        rotgen::note_written("out/sweep.partial");
        rotgen::note_removed("out/sweep.partial");
    });
    CHECK(removed.first == 143);
    CHECK(removed.second == "rotgen: interrupted; nothing written\n");
    const auto one_left = line_after([] {
        rotgen::note_written("out/sweep.partial");
        rotgen::note_written("out/summary.csv");
        rotgen::note_removed("out/sweep.partial");
    });
    CHECK(one_left.first == 143);
    CHECK(one_left.second == "rotgen: interrupted; wrote out/summary.csv\n");
}
