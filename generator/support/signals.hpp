// rotgen — what a signal does to a run, the one mechanism every command uses.
//
//   SIGINT, SIGTERM   remove every registered temporary, print one line on standard error,
//                     "rotgen: interrupted; nothing written" (or the note the command set:
//                     set_interrupt_note), and exit 130 / 143;
//   SIGPIPE           (the reader went away: `rotgen simulate S -o - | head -3`) remove every
//                     registered temporary and exit 141 quietly, as shells expect.
//
// Test hook (read only by tests): ROTGEN_TEST_SIGNAL=NAME:STAGE raises signal NAME (INT, TERM or
// PIPE) when the pipeline stage STAGE (support/timings.hpp: derive, compile, integrate, write,
// members, ...) begins, so that a test interrupts a run at a known place without racing a timer.
#pragma once

#include <string>

namespace rotgen {

// Registers a temporary file to remove if the process is ended by a signal; forget_temporary()
// when it was renamed or removed. At most 64 at a time.
void register_temporary(const std::string& path);
void forget_temporary(const std::string& path);

// Installs the handlers above (main() calls it first).
void remove_temporaries_on_signal();

// The line SIGINT/SIGTERM print after "rotgen: ", for instance "interrupted; kept
// out/summary.partial.csv (12 members)"; empty: back to the default. At most 1000 bytes.
void set_interrupt_note(const std::string& note);

// Records that `what` (a file, or "standard output") was written whole: from then on the
// interrupt line says "interrupted; wrote <what>[ and N more files]" instead of "nothing written".
void note_written(const std::string& what);
// Records that a file note_written named was removed again (a sweep's journal stamp, when the run
// fails before any member finished): the interrupt line no longer counts it.
void note_removed(const std::string& what);

// A function the handler calls first, with the signal (async-signal-safe; nullptr: none), which
// then prints the line itself: a command that keeps something of an interrupted run (the sweep's
// journal) sets it.
void set_interrupt_hook(void (*hook)(int));

// The test hook: raises the signal ROTGEN_TEST_SIGNAL names if its stage is `stage`.
void signal_test_hook(const std::string& stage);

// Test hook (read only by tests): ROTGEN_TEST_PAUSE=STAGE:SECONDS sleeps that long when `stage`
// is STAGE ("report": before the command line prints an error), so that a test holds one process
// at a known place (an MPI rank while another exits) without racing a timer.
void pause_test_hook(const std::string& stage);

} // namespace rotgen
