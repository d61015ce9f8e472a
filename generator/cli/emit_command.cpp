// rotgen emit MODEL.yaml -o DIR [--form lagrangian|hamiltonian|reduced|body]
//             [--outputs rhs,jacobian,energy,momenta,mass_matrix,omega,rotation,ignored_rates]
//             [--specialise | --specialise=NAME,NAME...] [--strategy explicit|solve] [--name UNIT]
//
// Writes DIR/<unit>.hpp (unit: the model's name, plus _<form> for forms other than lagrangian),
// through a temporary file renamed into place: a failed run leaves no partial header.
#include "cli/commands.hpp"
#include "derive/derive.hpp"
#include "emit/emit.hpp"
#include "support/error.hpp"
#include "spec/spec.hpp"

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

const char* const emit_usage =
    "usage: rotgen emit MODEL.yaml -o DIR [--form lagrangian|hamiltonian|reduced|body]\n"
    "                   [--outputs "
    "rhs,jacobian,energy,momenta,mass_matrix,omega,rotation,ignored_rates]\n"
    "                   [--specialise | --specialise=NAME,...] [--strategy explicit|solve]\n"
    "                   [--name UNIT]   (file UNIT.hpp, namespace rotgen::models::UNIT)\n";

user_error usage_error(const std::string& problem) {
    return user_error({"rotgen emit"}, problem);
}

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
    std::vector<std::string> items;
    std::string item;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        if (i == text.size() || text[i] == ',') {
            if (item.empty()) throw usage_error(option + ": empty name in '" + text + "'");
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

// Writes `text` to `path` via a temporary file in the same directory and a rename.
void write_atomically(const std::filesystem::path& dir, const std::string& file,
                      const std::string& text) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        throw user_error({dir.string()}, "the output path exists and is not a directory");
    fs::create_directories(dir, ec);
    if (ec) throw user_error({dir.string()}, "cannot create the output directory: " + ec.message());
    const fs::path target = dir / file;
    const fs::path temporary = dir / ("." + file + ".tmp." + std::to_string(::getpid()));
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            throw user_error({dir.string()}, "cannot write to the output directory: " +
                                                 std::string(std::strerror(errno)));
        out << text;
        out.flush();
        if (!out) {
            out.close();
            fs::remove(temporary, ec);
            throw user_error({target.string()}, "cannot write the header (disk full?)");
        }
    }
    fs::rename(temporary, target, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw user_error({target.string()}, "cannot move the header into place: " + ec.message());
    }
}

} // namespace

int cmd_emit(const std::vector<std::string>& args) {
    std::string model, dir;
    form_kind form = form_kind::lagrangian;
    lagrangian_strategy strategy = lagrangian_strategy::explicit_inverse;
    kernel_request request;
    header_options header;
    bool form_given = false, strategy_given = false, outputs_given = false;
    std::string specialise_text;
    const auto value = [&](std::size_t& i, const std::string& option, const std::string& expected) {
        if (i + 1 >= args.size() || (args[i + 1].size() > 1 && args[i + 1][0] == '-'))
            throw usage_error(option + " needs a value (" + expected + ")");
        return args[++i];
    };
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-h" || a == "--help") {
            std::cout << emit_usage;
            return 0;
        } else if (a == "-o" || a == "--output") {
            if (!dir.empty()) throw usage_error("-o given twice");
            dir = value(i, a, "a directory");
        } else if (a == "--form") {
            if (form_given) throw usage_error("--form given twice");
            form_given = true;
            const std::string f = value(i, a, "lagrangian, hamiltonian, reduced or body");
            if (f == "lagrangian")
                form = form_kind::lagrangian;
            else if (f == "hamiltonian")
                form = form_kind::hamiltonian;
            else if (f == "reduced")
                form = form_kind::reduced;
            else if (f == "body")
                form = form_kind::body;
            else {
                const std::string best =
                    closest_name(f, {"lagrangian", "hamiltonian", "reduced", "body"});
                throw usage_error("unknown form '" + f +
                                  "' (expected lagrangian, hamiltonian, reduced or body)" +
                                  (best.empty() ? "" : "; did you mean '" + best + "'?"));
            }
        } else if (a == "--strategy") {
            if (strategy_given) throw usage_error("--strategy given twice");
            strategy_given = true;
            const std::string s = value(i, a, "explicit or solve");
            if (s == "explicit")
                strategy = lagrangian_strategy::explicit_inverse;
            else if (s == "solve")
                strategy = lagrangian_strategy::solve;
            else
                throw usage_error("unknown strategy '" + s + "' (expected explicit or solve)");
        } else if (a == "--outputs") {
            if (outputs_given) throw usage_error("--outputs given twice");
            outputs_given = true;
            request.outputs = split_list(value(i, a, "a comma-separated list such as rhs,jacobian"), a);
        } else if (a == "--name") {
            if (!header.name.empty()) throw usage_error("--name given twice");
            header.name = value(i, a, "a C++ identifier");
            static const std::regex identifier("[A-Za-z_][A-Za-z0-9_]*");
            if (!std::regex_match(header.name, identifier))
                throw usage_error("--name '" + header.name + "' is not a C++ identifier");
        } else if (a == "--specialise" || a == "--specialize") {
            request.specialise_all = true;
            specialise_text = "--specialise";
        } else if (a.rfind("--specialise=", 0) == 0 || a.rfind("--specialize=", 0) == 0) {
            const std::string list = a.substr(a.find('=') + 1);
            request.specialise = split_list(list, "--specialise");
            specialise_text = "--specialise=" + list;
        } else if (a.size() > 1 && a[0] == '-') {
            const std::string best = closest_name(
                a, {"-o", "--form", "--outputs", "--specialise", "--strategy", "--name"});
            throw usage_error("unknown option '" + a + "' for emit" +
                              (best.empty() ? "" : "; did you mean '" + best + "'?"));
        } else if (model.empty()) {
            model = a;
        } else {
            throw usage_error("emit takes one model file, got '" + model + "' and '" + a + "'");
        }
    }
    if (model.empty())
        throw usage_error("emit needs a model file: rotgen emit MODEL.yaml -o DIR [options]");
    if (dir.empty()) throw usage_error("emit needs an output directory: -o DIR");
    if (strategy_given && form != form_kind::lagrangian)
        throw usage_error("--strategy applies to the Lagrangian form only (got --form " +
                          std::string(to_string(form)) + ")");

    // The command that regenerates exactly this header.
    std::string command = "rotgen emit " + shell_quote(model) + " -o " + shell_quote(dir) +
                          " --form " + to_string(form);
    if (form == form_kind::lagrangian)
        command += std::string(" --strategy ") + to_string(strategy);
    if (outputs_given) {
        std::string list;
        for (const auto& s : request.outputs)
            list += (list.empty() ? "" : ",") + s;
        command += " --outputs " + shell_quote(list);
    }
    if (!specialise_text.empty()) command += " " + shell_quote(specialise_text);
    if (!header.name.empty()) command += " --name " + header.name;
    header.command = command;

    const model_spec spec = load_model(model);
    const derivation d = derive(spec);
    const form_expressions f = build_requested_form(spec, d, form, strategy, request);
    const emitted_header h = emit_header(spec, lower_form(spec, f, request), header);
    write_atomically(dir, h.file_name, h.text);

    std::string summary;
    for (const auto& s : h.stats)
        summary += (summary.empty() ? "" : ", ") + s.function + " " +
                   std::to_string(s.before.total()) + " -> " + std::to_string(s.after.total());
    std::cout << "rotgen: wrote " << (std::filesystem::path(dir) / h.file_name).string()
              << " (operations: " << summary << ")\n";
    return 0;
}

} // namespace rotgen
