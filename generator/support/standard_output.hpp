// rotgen — standard output, every write checked. A full disk or device behind standard output
// (`rotgen inspect top.yaml > /dev/full`) is an error like any other output's: exit 2 and one line
// "rotgen: error: standard output: cannot write: No space left on device". A reader that went away
// is not an error of the run: the write raises SIGPIPE, which ends the process quietly with 141
// (support/signals.hpp).
//
// main() installs a checked_output_buffer on std::cout; it writes with write(2) and keeps the first
// error (errno), so that the reason is known however late the check comes. flush_standard_output()
// flushes std::cout and throws when any write failed (also when std::cout has its usual buffer,
// as in the Python module: then from the stream's state and errno).
#pragma once

#include <array>
#include <streambuf>

namespace rotgen {

class checked_output_buffer : public std::streambuf {
  public:
    explicit checked_output_buffer(int fd);
    ~checked_output_buffer() override;
    // The errno of the first write that failed; 0 when none did.
    int error() const { return m_error; }

  protected:
    int_type overflow(int_type c) override;
    int sync() override;

  private:
    bool drain(); // writes the buffer out; false once a write failed
    int m_fd;
    int m_error = 0;
    std::array<char, 1 << 16> m_data{};
};

// Flushes std::cout; throws user_error({"standard output"}, "cannot write: <reason>") when a
// write to it failed.
void flush_standard_output();

} // namespace rotgen
