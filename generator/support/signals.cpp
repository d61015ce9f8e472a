#include "support/signals.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace rotgen {

namespace {

// What the handler reads: fixed storage, no allocation in the handler.
constexpr std::size_t max_temporaries = 64, max_path = 4096, max_note = 1024;
std::array<std::array<char, max_path>, max_temporaries> g_temporaries{};
std::array<volatile sig_atomic_t, max_temporaries> g_used{};

// Two note buffers: one is written while the handler may read the other, then they swap.
const char* const default_note = "rotgen: interrupted; nothing written\n";
std::array<std::array<char, max_note>, 2> g_notes{};
volatile sig_atomic_t g_note = -1;  // -1: default_note
std::vector<std::string> g_written; // note_written's, in order

void (*volatile g_hook)(int) = nullptr; // set_interrupt_hook

// Guards every writer of the state above (threads of one process, such as Python's, register
// their temporaries at once); the handler takes no lock: it reads flags set after their buffers.
std::mutex g_writers;

extern "C" void on_signal(int sig) {
    void (*hook)(int) = g_hook;
    if (hook) hook(sig);
    for (std::size_t i = 0; i < max_temporaries; ++i)
        if (g_used[i]) ::unlink(g_temporaries[i].data());
    if (sig != SIGPIPE && !hook) {
        const char* note = g_note < 0 ? default_note : g_notes[g_note].data();
        [[maybe_unused]] const ssize_t n = ::write(2, note, std::strlen(note));
    }
    ::_exit(128 + sig);
}

} // namespace

void register_temporary(const std::string& path) {
    const std::lock_guard<std::mutex> lock(g_writers);
    if (path.size() >= max_path) return;
    for (std::size_t i = 0; i < max_temporaries; ++i)
        if (!g_used[i]) {
            std::memcpy(g_temporaries[i].data(), path.c_str(), path.size() + 1);
            g_used[i] = 1;
            return;
        }
}

void forget_temporary(const std::string& path) {
    const std::lock_guard<std::mutex> lock(g_writers);
    for (std::size_t i = 0; i < max_temporaries; ++i)
        if (g_used[i] && path == g_temporaries[i].data()) g_used[i] = 0;
}

void remove_temporaries_on_signal() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGINT, &sa, nullptr);
    ::sigaction(SIGTERM, &sa, nullptr);
    ::sigaction(SIGPIPE, &sa, nullptr);
}

void set_interrupt_hook(void (*hook)(int)) {
    g_hook = hook;
}

namespace {

void set_note_locked(const std::string& note) {
    if (note.empty()) {
        g_note = -1;
        return;
    }
    const std::string line = "rotgen: " + note.substr(0, max_note - 16) + "\n";
    const int next = g_note == 0 ? 1 : 0;
    std::memcpy(g_notes[next].data(), line.c_str(), line.size() + 1);
    g_note = next;
}

} // namespace

void set_interrupt_note(const std::string& note) {
    const std::lock_guard<std::mutex> lock(g_writers);
    set_note_locked(note);
}

// The interrupt line for the files written so far.
void set_written_note_locked() {
    const std::size_t more = g_written.empty() ? 0 : g_written.size() - 1;
    set_note_locked(g_written.empty()
                        ? ""
                        : "interrupted; wrote " + g_written.front() +
                              (more == 0 ? ""
                                         : " and " + std::to_string(more) +
                                               (more == 1 ? " more file" : " more files")));
}

void note_written(const std::string& what) {
    const std::lock_guard<std::mutex> lock(g_writers);
    g_written.push_back(what);
    set_written_note_locked();
}

void note_removed(const std::string& what) {
    const std::lock_guard<std::mutex> lock(g_writers);
    const auto it = std::find(g_written.begin(), g_written.end(), what);
    if (it == g_written.end()) return;
    g_written.erase(it);
    set_written_note_locked();
}

void signal_test_hook(const std::string& stage) {
    static const char* const hook = std::getenv("ROTGEN_TEST_SIGNAL");
    if (!hook) return;
    const char* colon = std::strchr(hook, ':');
    if (!colon || stage != colon + 1) return;
    const std::string name(hook, colon);
    ::raise(name == "INT" ? SIGINT : name == "PIPE" ? SIGPIPE : SIGTERM);
}

void pause_test_hook(const std::string& stage) {
    static const char* const hook = std::getenv("ROTGEN_TEST_PAUSE");
    if (!hook) return;
    const char* colon = std::strchr(hook, ':');
    if (!colon || stage != std::string(hook, colon)) return;
    std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(colon + 1)));
}

} // namespace rotgen
