// rotgen — the one command-line parser: every command declares its options once, and gets its
// parsing, its error messages and its --help text from that declaration (as git's
// parse-options.c does for its builtins).
//
// Errors are user errors located at "rotgen <command>" (exit status 2):
//   unknown option '--quik' for bench; did you mean '--quick'?
//   --form needs a value (lagrangian|hamiltonian|reduced|body)
//   --form given twice
//   simulate takes one scene file, got 'a.yaml' and 'b.yaml'
//   simulate needs a scene file: rotgen simulate SCENE.yaml [options]
#pragma once

#include <map>
#include <string>
#include <vector>

namespace rotgen {

struct option_spec {
    std::string name;  // "--form", "-o"
    std::string value; // what its value is, for errors and help ("DIR"); empty: a flag
    std::string help;  // one line for --help
    std::vector<std::string> aliases; // other spellings: "--output", "--specialize"
    bool optional_value = false;      // also accepted as a bare flag; a value only as --name=VALUE
    bool repeatable = false;          // may be given more than once (values() has them all)
};

struct command_spec {
    std::string name;     // "simulate"
    std::string operand;  // "scene file"; empty when the command takes none
    std::string synopsis; // "SCENE.yaml [-o out.csv] [--plot out.png]"
    std::string summary;  // what the command does, one paragraph, for --help
    std::vector<option_spec> options;
};

class parsed_options {
  public:
    std::string operand;
    bool help = false; // -h or --help: the caller prints help_text() and returns 0

    bool has(const std::string& name) const { return m_values.count(name) > 0; }
    // The value given to `name` (by its canonical name); `fallback` if it was not given.
    const std::string& value(const std::string& name, const std::string& fallback = empty()) const;
    // Every value given to a repeatable option, in order.
    std::vector<std::string> values(const std::string& name) const;

  private:
    friend parsed_options parse_options(const command_spec&, const std::vector<std::string>&);
    static const std::string& empty();
    std::map<std::string, std::string> m_values; // canonical name -> value ("" for a flag)
    std::map<std::string, std::vector<std::string>> m_repeated; // repeatable options' values
};

// Parses `args` (those after the command name). Throws user_error.
parsed_options parse_options(const command_spec& command, const std::vector<std::string>& args);

// "usage: rotgen <name> <synopsis>", the summary, and one line per option.
std::string help_text(const command_spec& command);

// The user error "rotgen <command>: <problem>", for checks of option values after parsing.
[[noreturn]] void usage_error(const command_spec& command, const std::string& problem);

} // namespace rotgen
