// rotgen emit MODEL.yaml -o DIR [--form lagrangian|hamiltonian|reduced|body|rotor]
//             [--outputs rhs,jacobian,energy,momenta,mass_matrix,omega,rotation,ignored_rates,
//                        taylor]
//             [--specialise | --specialise=NAME,NAME...] [--strategy explicit|solve] [--name UNIT]
//             [--sensitivities parameters.NAME,...]
//
// Writes DIR/<unit>.hpp (unit: the model's name, plus _<form> for forms other than lagrangian),
// through a temporary file renamed into place: a failed run leaves no partial header; -o -
// writes the header to standard output.
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "derive/derive.hpp"
#include "emit/emit.hpp"
#include "emit/taylor.hpp"
#include "spec/spec.hpp"
#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/output_paths.hpp"
#include "support/standard_output.hpp"
#include "support/timings.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>

namespace rotgen {

namespace {

const command_spec emit_command{
    "emit",
    "model file",
    "MODEL.yaml -o DIR [--form F] [--strategy S] [--outputs LIST] [--specialise[=NAMES]] [--name "
    "UNIT] [--sensitivities KEYS]",
    "Writes DIR/<unit>.hpp: the model's kernels as a dependency-free C++ header, templated on the\n"
    "scalar (unit: the model's name, plus _<form> for forms other than lagrangian). Written "
    "through\n"
    "a temporary renamed into place: a failed run leaves no partial header. -o - writes it to\n"
    "standard output.\n\n"
    "example: rotgen emit models/heavy_top.yaml -o generated --form hamiltonian --outputs "
    "rhs,energy",
    {{"-o",
      "DIR",
      "the output directory (created if missing); - for standard output",
      {"--output"}},
     {"--form",
      "lagrangian|hamiltonian|reduced|body|rotor",
      "the form of the equations (default lagrangian; rotor, the only one, for a linear rotor)",
      {}},
     {"--strategy",
      "explicit|solve",
      "Lagrangian form: explicit accelerations, or M and f solved inline",
      {}},
     {"--outputs",
      "LIST",
      "comma-separated: rhs,jacobian,energy,momenta,mass_matrix,omega,rotation,\n"
      "ignored_rates,taylor (default: all the form gives but taylor)",
      {}},
     {"--specialise",
      "NAMES",
      "fold parameter values into the code (all, or =I1,I3)",
      {"--specialize"},
      true},
     {"--name", "UNIT", "the unit: file UNIT.hpp, namespace rotgen::models::UNIT", {}},
     {"--sensitivities",
      "KEYS",
      "comma-separated parameters.NAME keys: add parameter_jacobian (df/dp) and\n"
      "variational_rhs (dS/dt = df/dy S + [0|df/dp]) for those parameters",
      {}},
     {"--timings", "", "print the wall time of each pipeline stage to standard error", {}}}};

[[noreturn]] void fail(const std::string& problem) {
    usage_error(emit_command, problem);
}

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
    std::vector<std::string> items;
    std::string item;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        if (i == text.size() || text[i] == ',') {
            if (item.empty()) fail(option + ": empty name in '" + text + "'");
            items.push_back(item);
            item.clear();
        } else if (text[i] != ' ') {
            item += text[i];
        }
    }
    return items;
}

std::string shell_quote(const std::string& s) {
    if (!s.empty() &&
        s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                            "_-./=,+:@%") == std::string::npos)
        return s;
    std::string q = "'";
    for (char c : s)
        q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// DIR/file, or standard output for -o -, checked before any work: DIR is a folder or can be
// made, and the header is not the model file.
std::string header_path(const std::string& dir, const std::string& file, const std::string& model) {
    namespace fs = std::filesystem;
    if (dir == "-") return dir;
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        throw user_error({dir}, "the output path exists and is not a directory");
    const std::string path = (fs::path(dir) / file).string();
    check_distinct_files({{path, "-o " + dir}}, {{model, "the model"}});
    return path;
}

// The folders of `dir` that do not exist yet, the deepest first (what create_directories makes).
std::vector<std::filesystem::path> missing_folders(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path p = fs::absolute(dir, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path())
        missing.push_back(p);
    return missing;
}

// The header at `path` (DIR created if missing) through support/'s atomic writer (never a
// partial header), or on standard output, handed to `outputs`. Returns the folders it made, the
// deepest first.
std::vector<std::filesystem::path> write_header(const std::string& dir, const std::string& path,
                                                const std::string& text, output_set& outputs) {
    namespace fs = std::filesystem;
    std::vector<fs::path> made;
    std::error_code ec;
    if (path != "-") {
        made = missing_folders(dir);
        fs::create_directories(dir, ec);
    }
    if (ec) throw user_error({dir}, "cannot create the output directory: " + ec.message());
    atomic_file out(path);
    out.stream() << text;
    out.commit(outputs);
    return made;
}

form_kind form_of(const std::string& f) {
    if (f.empty() || f == "lagrangian") return form_kind::lagrangian;
    if (f == "hamiltonian") return form_kind::hamiltonian;
    if (f == "reduced") return form_kind::reduced;
    if (f == "body") return form_kind::body;
    if (f == "rotor") return form_kind::rotor;
    const std::string best =
        closest_name(f, {"lagrangian", "hamiltonian", "reduced", "body", "rotor"});
    fail("unknown form '" + f + "' (expected lagrangian, hamiltonian, reduced, body or rotor)" +
         (best.empty() ? "" : "; did you mean '" + best + "'?"));
}

// A linear rotor's form is `rotor` (the default for it); other bodies have no rotor form.
form_kind rotor_form_of(const model_spec& spec, form_kind form, bool given) {
    if (spec.rotor && given && form != form_kind::rotor)
        throw user_error(spec.rotor_where, "model '" + spec.name +
                                               "' is a linear rotor (Example 5.4): its form is "
                                               "'rotor' (two angles), not --form " +
                                               to_string(form));
    if (!spec.rotor && form == form_kind::rotor)
        fail("--form rotor is the form of a linear rotor; model '" + spec.name + "' is not one");
    return spec.rotor ? form_kind::rotor : form;
}

lagrangian_strategy strategy_of(const std::string& s) {
    if (s.empty() || s == "explicit") return lagrangian_strategy::explicit_inverse;
    if (s == "solve") return lagrangian_strategy::solve;
    fail("unknown strategy '" + s + "' (expected explicit or solve)");
}

// The command that regenerates exactly this header (for its comment).
std::string regenerate_command(const parsed_options& o, form_kind form,
                               lagrangian_strategy strategy) {
    std::string command = "rotgen emit " + shell_quote(o.operand) + " -o " +
                          shell_quote(o.value("-o")) + " --form " + to_string(form);
    if (form == form_kind::lagrangian) command += std::string(" --strategy ") + to_string(strategy);
    if (o.has("--outputs")) {
        std::string list;
        for (const auto& s : split_list(o.value("--outputs"), "--outputs"))
            list += (list.empty() ? "" : ",") + s;
        command += " --outputs " + shell_quote(list);
    }
    if (o.has("--specialise"))
        command += " " + shell_quote(o.value("--specialise").empty()
                                         ? "--specialise"
                                         : "--specialise=" + o.value("--specialise"));
    if (o.has("--name")) command += " --name " + o.value("--name");
    if (o.has("--sensitivities"))
        command += " --sensitivities " + shell_quote(o.value("--sensitivities"));
    return command;
}

void print_written(const std::string& path, const emitted_header& h) {
    std::string summary;
    for (const auto& s : h.stats)
        summary += (summary.empty() ? "" : ", ") + s.function + " " +
                   (s.summary.empty() ? std::to_string(s.before.total()) + " -> " +
                                            std::to_string(s.after.total())
                                      : s.summary);
    // with -o - the header is the data on standard output: this line goes to standard error
    (path == "-" ? std::cerr : std::cout)
        << "rotgen: wrote "
        << (path == "-" ? "standard output (" + h.file_name + "; " : path + " (")
        << "operations: " << summary << ")\n";
}

// Writes the header and commits it: standard output first, then the line that says what was
// written, then the file. When one fails, the folders made for it go again (only while empty: the
// output_set has removed its temporary by then), so that exit 2 leaves nothing.
void write_and_commit(const std::string& dir, const std::string& path, const emitted_header& h,
                      stage_timings& timings) {
    std::vector<std::filesystem::path> made;
    try {
        output_set outputs;
        timings.time("write", h.file_name,
                     [&] { made = write_header(dir, path, h.text, outputs); });
        outputs.commit_streams(); // -o -: the header, checked before the line that says so
        print_written(path, h);
        flush_standard_output(); // that line, checked before the header appears
        outputs.commit_files();
    } catch (const user_error&) {
        std::error_code ec;
        for (const auto& folder : made)
            std::filesystem::remove(folder, ec);
        throw;
    }
}

} // namespace

int cmd_emit(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(emit_command, args);
    if (o.help) {
        std::cout << help_text(emit_command);
        return 0;
    }
    const std::string dir = o.value("-o");
    if (dir.empty()) fail("emit needs an output directory: -o DIR");
    form_kind form = form_of(o.value("--form"));
    const lagrangian_strategy strategy = strategy_of(o.value("--strategy"));
    if (o.has("--strategy") && form != form_kind::lagrangian)
        fail("--strategy applies to the Lagrangian form only (got --form " +
             std::string(to_string(form)) + ")");
    static const std::regex identifier("[A-Za-z_][A-Za-z0-9_]*");
    if (o.has("--name") && !std::regex_match(o.value("--name"), identifier))
        fail("--name '" + o.value("--name") + "' is not a C++ identifier");
    kernel_request request;
    if (o.has("--outputs")) request.outputs = split_list(o.value("--outputs"), "--outputs");
    request.specialise_all = o.has("--specialise") && o.value("--specialise").empty();
    if (!o.value("--specialise").empty())
        request.specialise = split_list(o.value("--specialise"), "--specialise");
    if (o.has("--sensitivities"))
        request.sensitivities = split_list(o.value("--sensitivities"), "--sensitivities");

    stage_timings timings;
    const model_spec spec = load_model(o.operand, "emit");
    // A linear rotor has its own form (derive/rotor.hpp), derived where it is built.
    form = rotor_form_of(spec, form, o.has("--form"));
    const std::string path = header_path(
        dir, (o.has("--name") ? o.value("--name") : unit_name(spec.name, form)) + ".hpp",
        o.operand);
    const header_options header{regenerate_command(o, form, strategy), o.value("--name")};
    const derivation d = timings.time("derive", spec.name, [&]() -> derivation {
        if (spec.rotor) return {}; // a linear rotor is derived where its form is built
        return derive(spec);
    });
    const form_expressions f = timings.time("forms", to_string(form), [&] {
        return build_requested_form(spec, d, form, strategy, request);
    });
    const lowered_form lowered =
        timings.time("lower", to_string(form), [&] { return lower_form(spec, f, request); });
    const emitted_header h = timings.time("emit", to_string(form), [&] {
        try {
            return emit_header(spec, lowered, header);
        } catch (const taylor_unsupported& e) { // --outputs taylor: a model-wide refusal
            throw user_error({spec.file, 1, 1}, "model '" + spec.name + "': " + e.what() +
                                                    "; leave taylor out of --outputs");
        }
    });
    write_and_commit(dir, path, h, timings);
    if (o.has("--timings")) timings.print(std::cerr);
    return 0;
}

} // namespace rotgen
