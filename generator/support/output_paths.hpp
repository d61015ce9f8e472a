// rotgen — a run's outputs never collide: no two outputs of one run are the same file, and no
// output is one of the run's inputs. Every command that writes files checks its whole set here,
// before any work, so that a refused run writes nothing:
//
//   check_distinct_files({{"a.csv", "-o"}, {"a.csv", "--events"}}, {{"top.yaml", "the scene"}});
//   // user_error "a.csv: -o and --events name the same file; give each its own name"
//
// Two paths are the same file when they resolve to the same inode (hard links, symlinks, "./x"
// and "x", "-" and /dev/stdout when standard output is a file or a pipe), or, for files that do
// not exist yet, to the same path after following links. A character device (/dev/null, a
// terminal) takes any number of outputs: nothing in it can be destroyed or mixed.
#pragma once

#include <string>
#include <vector>

namespace rotgen {

struct named_file {
    std::string path; // as the user gave it ("-": standard output)
    std::string role; // how the user gave it: "-o", "--events", "the scene", "DIR/summary.csv"
};

// Throws user_error naming the first path of a collision and both roles.
void check_distinct_files(const std::vector<named_file>& outputs,
                          const std::vector<named_file>& inputs);

// "-", or an existing file that is not a regular one (after following links): a FIFO, a device,
// a socket. Such an output is written directly, and no sibling name is derived from it.
bool is_stream_output(const std::string& path);

// "-", or a path to the file standard output is open on (/dev/stdout, /proc/self/fd/1, the file
// it was redirected to): the data goes there, so the command's summary goes to standard error.
bool is_standard_output(const std::string& path);

// The file a path names after following symlinks, also when the last one dangles (the file that
// writing it would create).
std::string follow_links(const std::string& path);

} // namespace rotgen
