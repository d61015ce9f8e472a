// rotgen bench: the bench's answer in scene terms (issue 50). For each error level it reached
// (1e-3 .. 1e-13), the fastest configuration `rotgen simulate` can run whose error is at most the
// level, printed as the scene lines that run it (`form: body`, `integrator: {method: dop853,
// rtol: 3e-09, atol: 3e-09}`), verified before it is printed: that scene run through the engine
// and measured with the one error measure (sampled_error.hpp) against its reference. Rows simulate
// cannot run (long double, float, unlowered, runtime parameters, another Lagrangian strategy,
// peers) are `bench only`: listed, never chosen. A row whose error is at the bench reference's own
// floor (at most 3x the reference's estimated error) is never chosen either.
//
// One function chooses (choose_scenes); the console, results.md's tables and its interpolated
// table print its choice.
#pragma once

#include "bench/driver.hpp"
#include "bench/variants.hpp"

#include <functional>
#include <string>
#include <vector>

namespace rotgen::bench {

// The scene `simulate` runs for a row: the bench's scene with the row's form and integrator (rtol
// = atol = tol, or the fixed step), or false when the row is bench only.
bool scene_of_row(const result_row& r, const std::vector<variant>& variants,
                  const scene_spec& scene, scene_spec& out);

// "bench only" or "" (simulate runs it).
std::string runnable_text(const result_row& r, const std::vector<variant>& variants,
                          const scene_spec& scene);

struct scene_choice {
    double level = 0;
    const result_row* row = nullptr; // null: no runnable configuration verified at the level
    scene_spec scene;                // what simulate runs for it
    double verified = 0;             // its measured error (the one measure), <= level
    std::string lines;               // "form: body\nintegrator: {...}"
    std::string why;                 // when row is null
};

// The measure of a scene (the verification): its error, NaN when it could not run.
using verify_fn = std::function<double(const scene_spec&)>;

// The choice per level (`levels`), from the runnable rows by median time, each verified; a row
// whose verified error exceeds the level is passed over for the next fastest (at most `tries`).
// `floor`: the bench reference's estimated error (rows at <= 3x it are not chosen).
std::vector<scene_choice> choose_scenes(const std::vector<result_row>& rows,
                                        const std::vector<variant>& variants,
                                        const scene_spec& scene, const std::vector<double>& levels,
                                        double floor, const verify_fn& verify, int tries = 4);

// The scene lines of a chosen scene: "form: body\nintegrator: {method: ...}".
std::string scene_lines(const scene_spec& s);

} // namespace rotgen::bench
