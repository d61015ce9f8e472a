// rotgen — the provenance line: the first line of every CSV that holds a run's rows (simulate's
// samples, its events, the partial rows of a run that could not finish, the figures' data), saying
// which rotgen, which model and which form made it:
//
//   # rotgen 0.9.0 model heavy_top sha256 5d41402abc4b2a76b9719d911017c592... form lagrangian
//
//   VERSION  rotgen's version;
//   NAME     the model's `name:`;
//   HASH     SHA-256 of the bytes of the file the model was read from (the model file; the scene
//            file for a model given inline in a scene), 64 lower-case hex digits as `sha256sum
//            FILE` prints them: the same however the path is spelt, different after any edit;
//   FORM     the scene's form: lagrangian, hamiltonian, reduced, body or rotor.
//
// The fields are separated by single spaces; NAME is a C++ identifier. Readers skip lines that
// start with '#' before the header (pandas: read_csv(path, comment='#')); `simulate --from`
// refuses a run of another model or form (run/continue_from.hpp).
#pragma once

#include "forms/form_kind.hpp"
#include "spec/spec.hpp"

#include <optional>
#include <string>

namespace rotgen {

struct csv_provenance {
    std::string version, model, sha256, form;
};

// The provenance of a run of `model` in `form`, by this rotgen.
csv_provenance provenance_of(const model_spec& model, form_kind form);

// The line, without its line end: "# rotgen VERSION model NAME sha256 HASH form FORM".
std::string provenance_line(const csv_provenance& p);

// The fields of a provenance line (a trailing '\r' allowed); nullopt for any other line.
std::optional<csv_provenance> parse_provenance(const std::string& line);

} // namespace rotgen
