// rotgen — stage 4: lowering. GiNaC expressions become a straight-line program.
//
// GiNaC has no common-subexpression elimination; this module supplies it, on the expression DAG:
//
//   * every subexpression is converted once into a node of a hash-consed DAG (structurally equal
//     subexpressions are one node, whatever GiNaC's internal order);
//   * a sum is kept with its leading term positive, so a - b and b - a are one node (times -1);
//   * numeric coefficients stay outside products and sums (2*x*y is 2 times the node x*y), so that
//     x*y is shared with 3*x*y;
//   * integer powers become products by binary powering (x^2 = x*x, x^3 = x^2*x, x^4 = x^2*x^2),
//     negative ones a division, so x^2 is shared by x^2, x^3 and 1/x^2;
//   * sums are factored by a greedy Horner scheme (x y + x z -> x (y + z), a/s + b/s -> (a + b)/s),
//     and a common numeric factor goes outside when that saves multiplications;
//   * terms of a sum that differ only in their parameter factors are one term whose coefficient
//     is a single fraction, made by GiNaC's normal(): x y / I1 - x y / I2 -> (I2 - I1) x y /
//     (I1 I2). A difference of rounded reciprocals loses its accuracy when I1 ~ I2 (relative
//     error 4e-3 for I1 = 3, I2 = 3 (1 + 2^-45)); I2 - I1 of two inputs is exact (Sterbenz), so
//     the single fraction is accurate to a few roundings. Coefficients that cancel vanish.
//     A linear combination of sums with like terms that involve parameters, or with terms that
//     cancel, z (x + a y) - z (x + b y), becomes one sum first (x cancels exactly, a y - b y is
//     (a - b) y); other sums stay nodes;
//   * a product with one sum among its factors, each term of which cancels a factor with the
//     rest, is distributed: I3 x (1/I3 + y/(I1 x^2)) -> x + I3 y/(I1 x) (divisions cancelled);
//   * a pair of factors that two or more products share is one product node, the most frequent
//     pair first: x y z, x y w -> (x y) z, (x y) w (hash-consing alone shares equal products
//     only, and products are flat lists of factors);
//   * parameters over parameters in a product of state factors are one factor of their own,
//     ((I3 - I1)/I2) x y: the division is off the chain of operations on the state, and shared;
//   * a denominator is one node (a reciprocal), shared by every product that divides by it;
//   * sin and cos of each input (an angle) are computed once, named sin_<input>, cos_<input>;
//   * numbers stay exact rationals; GiNaC folds numeric arithmetic as it builds expressions.
//
// Lowering prints nothing: emit/printer.hpp prints a program as C++. A node used more than once
// becomes a temporary, and so does one that would print too long
// inline; the rest print inline where they are used. A sum printed inside another sum, or
// multiplied by a number, prints as one sum with the numbers multiplied in where that needs no
// more multiplications (c (a x + b y) -> (c a) x + (c b) y, exact; -(x - y) -> y - x).
// The result has the shape of SymEngine's `cse`: an ordered list of (temporary, expression) plus
// the outputs, each in terms of inputs and earlier temporaries.
//
// Determinism: GiNaC's term order changes from run to run (its hash seeds depend on addresses),
// so nothing here depends on it. Each node gets a 64-bit digest computed by rotgen from its content
// alone (kind, printed names and exact numbers, children's digests, commutative children sorted);
// children are ordered by digest, temporaries are numbered t000, t001, ... in a depth-first
// traversal from the outputs in that order, and the printer (emit/printer.hpp) sorts the terms of
// sums and factors of products by their printed text. Same expressions in, same program (and same
// bytes) out. (Two different nodes with one digest would be a collision: lowering throws rather
// than guess.) normal()'s output also changes from run to run, but only by a constant factor of
// numerator and denominator, which lowering fixes (expanded, the denominator's integer content 1,
// the sign by the DAG's leading-term rule).
#pragma once

#include <ginac/ginac.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rotgen {

// How the program refers to a GiNaC symbol. Inputs are matched by symbol object, never by name.
struct program_input {
    GiNaC::ex symbol;       // a GiNaC symbol
    std::string name;       // what the code writes for it: "theta", "p.I1", "t"
    std::string definition; // if not empty, `const T name = definition;` is emitted when used
    // A model constant (I1, M, ...), not state or time: terms that differ only in parameters are
    // combined into one fraction (see above).
    bool parameter = false;
};

// Arithmetic as printed: + and - (binary or unary), *, /, and calls (sin, cos, sqrt, pow, ...).
struct op_count {
    std::size_t add = 0, mul = 0, div = 0, call = 0;
    std::size_t total() const { return add + mul + div + call; }
    op_count& operator+=(const op_count& o) {
        add += o.add, mul += o.mul, div += o.div, call += o.call;
        return *this;
    }
};

struct lowered_node {
    enum class kind { input, number, constant, sum, product, call };
    kind k = kind::number;
    std::string name;     // input: the code's name for it; call: the function; constant: "pi"
    GiNaC::numeric value; // number: the value; sum: the constant term
    std::vector<std::pair<GiNaC::numeric, int>> terms; // sum: value + sum of coefficient * node
    std::vector<int> numerator, denominator;           // product: factors (repeats allowed)
    std::vector<int> args;                             // call
    std::uint64_t digest = 0;
    int height = 0;
};

struct lowered_program {
    std::vector<program_input> inputs;
    std::vector<lowered_node> nodes; // children before parents
    std::vector<int> outputs;        // one node per output expression
    struct step {
        int node;
        std::string name; // t000, t001, ... or sin_theta, cos_theta
    };
    std::vector<step> steps; // the temporaries, in order
    // With lower_options::hoist_parameters: the subexpressions of parameters alone that the
    // program reads by name instead of computing them (p.c000, ...; children before parents).
    // Their definitions are printed once per parameter set, outside the program (emit's
    // prepare()); they are not among the steps and not counted in `after`.
    std::vector<step> constants;
    std::map<int, std::string> temporary_name; // node -> its step's name
    std::vector<char> parametric;              // node -> of parameters and numbers alone
    op_count before; // the outputs printed naively, each on its own (no sharing, no hoisting)
    op_count after;  // the program as printed: temporaries plus outputs
};

struct lower_options {
    // A subexpression longer than this (roughly, in operations) becomes a temporary even if used
    // once: statements stay short, and array types with expression templates (Eigen) compile fast.
    std::size_t max_inline_ops = 12;
    // Parameter-only subexpressions are hoisted out of the program (lowered_program::constants):
    // every product of state factors with two or more parameter factors, or with a parameter
    // below the bar, takes its parameters as one factor of their own (x y I3/I1 -> x y (I3/I1),
    // x/I1 -> x (1/I1): a division becomes a multiplication), and each such factor, and each
    // parameter-only term or argument, is a named constant.
    bool hoist_parameters = false;
};

// Lowers `outputs` (in terms of the inputs' symbols; any other symbol is an internal error).
lowered_program lower(const std::vector<GiNaC::ex>& outputs,
                      const std::vector<program_input>& inputs, const lower_options& options = {});

// Lowers `outputs` as lower() does with every input a variable, then folds the inputs in
// `values` (symbol -> exact number) into the program: every subexpression of numbers alone
// becomes a number, computed exactly, and the rest keeps the runtime program's structure (its
// sharing and factoring). So the folded program never has more operations than the runtime one
// beyond a rare numeric coefficient at a use of a shared temporary. The program's inputs are
// `inputs` without the folded ones. std::nullopt when a folded value makes a denominator zero.
// (Folding before lowering, by substituting into the expressions, can lower to more operations:
// GiNaC distributes a number over a sum, 2 (x + y) -> 2 x + 2 y, so sums a product of a parameter
// and a sum shared are flattened and factored again another way.)
std::optional<lowered_program> lower_folded(const std::vector<GiNaC::ex>& outputs,
                                            const std::vector<program_input>& inputs,
                                            const GiNaC::exmap& values,
                                            const lower_options& options = {});

// Operations in `e` printed naively (integer powers as repeated products).
op_count count_ops(const GiNaC::ex& e);

// The program's value at a point, computed node by node with GiNaC floats (to check lowering
// against the original expressions). `values` maps input symbols to numbers; returns the outputs.
std::vector<GiNaC::numeric> evaluate(const lowered_program& program, const GiNaC::exmap& values);

// The children of a node: sum terms, numerator, denominator, call arguments.
std::vector<int> node_children(const lowered_node& node);

// Which inputs the printed program uses (to emit only the definitions it needs).
std::vector<bool> used_inputs(const lowered_program& program);

} // namespace rotgen
