// rotgen sweep — which members an ensemble has: the scene's `sweep:` block and the command line's
// `--vary` entries, checked and expanded into one row of values per member.
//
//   sweep:
//     mode: grid                  # grid (Cartesian product) | zip (element-wise) | random
//     vary:
//       initial.theta: {from: 0.1, to: 1.5, count: 64}   # or {values: [...]}; random: {from, to}
//       parameters.h: {values: [0.05, 0.1, 0.2]}
//     members: 1000               # random mode only, with seed: 42 (default 0)
//
// `--vary KEY=FROM:TO:COUNT` (or KEY=V1,V2,... or, in random mode, KEY=FROM:TO) adds a key, or
// replaces the scene's entry for it. Keys: `initial.<name>` for a name of the scene's `initial`
// (the angles phi, theta, psi, and the rates the scene gives: phi_dot.., p_phi.. or omega1..3)
// and `parameters.<name>` for a parameter of the model.
//
// Member order: grid mode counts like nested loops in the order the keys are written, the last key
// fastest; zip mode takes the i-th value of every key; random mode draws, member by member and key
// by key, u = (x >> 11) * 2^-53 in [0, 1) from std::mt19937_64(seed) (whose output sequence the
// C++ standard fixes) and takes from + (to - from) * u: no standard-library distribution is used,
// so the values are the same with every compiler and library. A range {from, to, count} is
// from + (to - from) * i / (count - 1), i = 0 .. count - 1, the last exactly `to` (as the sample
// times are).
#pragma once

#include "run/engine.hpp"
#include "scene/scene.hpp"
#include "scene/value_keys.hpp"
#include "support/error.hpp"

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace rotgen {

enum class sweep_mode { grid, zip, random };

// key, where (the entry in the scene, or "rotgen sweep --vary ..."), target, index: value_key's
struct sweep_key : value_key {
    std::vector<double> values; // grid and zip: the values listed
    double from = 0, to = 0;    // random, and a range {from, to, count}
    std::size_t count = 0;      // a range's count (its values computed when asked); 0: a list
    std::size_t size() const { return count != 0 ? count : values.size(); }
    double value(std::size_t i) const; // the i-th value (grid and zip)
};

struct sweep_plan {
    sweep_mode mode = sweep_mode::grid;
    std::vector<sweep_key> keys;
    long members = 0; // random mode
    std::uint64_t seed = 0;
    source_location where; // the `sweep:` block, or the scene file
};

// The plan from the scene's `sweep:` block (re-read from scene.file) and the `--vary` arguments.
// Throws user_error, located at the offending entry, for an unknown key, an empty range, a count
// that is not positive, zip keys of different lengths, a value outside its range (theta in
// [0, pi]), no key at all.
sweep_plan read_sweep_plan(const scene_spec& scene, const std::vector<std::string>& cli_vary);

// The members' rows, one value per key (in the plan's key order), computed when asked: a grid or
// zip member's from its index, a random member's from the generator's state saved every 4,096
// members (2.5 KB each), so that an ensemble of 1e8 members holds its rows in about 60 MB.
class member_table {
  public:
    explicit member_table(const sweep_plan& plan); // keeps a reference to `plan`
    std::size_t size() const { return m_size; }
    std::vector<double> row(std::size_t member) const;

  private:
    static constexpr std::size_t checkpoint_every = 4096;
    const sweep_plan& m_plan;
    std::size_t m_size = 0;
    std::vector<std::mt19937_64> m_checkpoints; // random mode
};

// Every member's row (for small plans: tests).
std::vector<std::vector<double>> member_rows(const sweep_plan& plan);

// The scene's values with one member's row substituted.
member_values member_of(const sweep_plan& plan, const member_values& base,
                        const std::vector<double>& row);

} // namespace rotgen
