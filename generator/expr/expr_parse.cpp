#include "expr/expr_parse.hpp"

#include "expr/symbols.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rotgen {

namespace {

using GiNaC::ex;

// Limits that keep a hostile expression from exhausting the stack, the memory or the time: the
// parser is recursive, and GiNaC evaluates numbers exactly (9^9^9 would have 3.7e8 digits).
constexpr int max_nesting = 200;         // parentheses, calls, exponents, nested in each other
constexpr std::size_t max_digits = 4000; // significant digits of one number literal
constexpr long max_exponent = 1000;      // |n| in x^n (except for the bases 0, 1 and -1)
constexpr std::size_t max_number_bits = 1u << 17; // an exact number, ~39000 decimal digits

// Bits in the numerator and denominator of the real and imaginary parts of a numeric.
std::size_t numeric_bits(const GiNaC::numeric& n) {
    const auto rational_bits = [](const GiNaC::numeric& r) -> std::size_t {
        if (!r.is_rational()) return 64; // not produced by the parser (no floats); be safe
        return static_cast<std::size_t>(r.numer().int_length()) +
               static_cast<std::size_t>(r.denom().int_length());
    };
    return std::max(rational_bits(n.real()), rational_bits(n.imag()));
}

// The size of the numeric coefficients GiNaC combines when `e` is multiplied or raised to a
// power: the number itself, a product's overall coefficient, or the largest coefficient of a sum
// (a number times a sum is distributed).
std::size_t coefficient_bits(const ex& e) {
    if (GiNaC::is_a<GiNaC::numeric>(e)) return numeric_bits(GiNaC::ex_to<GiNaC::numeric>(e));
    if (GiNaC::is_a<GiNaC::mul>(e) && e.nops() > 0 &&
        GiNaC::is_a<GiNaC::numeric>(e.op(e.nops() - 1)))
        return numeric_bits(GiNaC::ex_to<GiNaC::numeric>(e.op(e.nops() - 1)));
    if (GiNaC::is_a<GiNaC::add>(e)) {
        std::size_t bits = 0;
        for (std::size_t i = 0; i < e.nops(); ++i)
            bits = std::max(bits, coefficient_bits(e.op(i)));
        return bits;
    }
    return 0;
}

// A term of a sum as (numeric coefficient, the rest): like terms are those with the same rest.
std::pair<GiNaC::numeric, ex> split_coefficient(const ex& term) {
    if (GiNaC::is_a<GiNaC::numeric>(term)) return {GiNaC::ex_to<GiNaC::numeric>(term), 1};
    if (GiNaC::is_a<GiNaC::mul>(term) && term.nops() > 0 &&
        GiNaC::is_a<GiNaC::numeric>(term.op(term.nops() - 1))) {
        const GiNaC::numeric c = GiNaC::ex_to<GiNaC::numeric>(term.op(term.nops() - 1));
        return {c, term / c};
    }
    return {1, term};
}

// The character at s[i] for a message: 'c' if printable, else its code ('\x00'); a valid UTF-8
// sequence is shown whole ('é').
std::string describe_character(const std::string& s, std::size_t i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) return std::string("'") + static_cast<char>(c) + "'";
    const std::size_t length = c >= 0xc2 && c <= 0xdf   ? 2
                               : c >= 0xe0 && c <= 0xef ? 3
                               : c >= 0xf0 && c <= 0xf4 ? 4
                                                        : 0;
    bool valid = length > 0 && i + length <= s.size();
    for (std::size_t k = 1; valid && k < length; ++k)
        valid = (static_cast<unsigned char>(s[i + k]) & 0xc0) == 0x80;
    if (valid) return "'" + s.substr(i, length) + "'";
    static const char* hex = "0123456789abcdef";
    return std::string("'\\x") + hex[c >> 4] + hex[c & 15] + "'";
}

// An internal inconsistency of the parser (never a user error; passes through guarded()).
struct parser_bug : std::logic_error {
    using std::logic_error::logic_error;
};

struct token {
    enum kind_t { number, name, op, end } kind;
    std::string text;
    std::size_t offset; // 0-based position in the source text
};

class parser {
  public:
    parser(const std::string& text, const name_table& names, const source_location& where,
           const std::string& what)
        : m_text(text), m_names(names), m_where(where), m_what(what) {
        tokenize();
    }

    ex parse() {
        if (m_tokens.front().kind == token::end) fail(m_tokens.front(), "empty expression");
        ex e = expression();
        if (peek().kind != token::end)
            fail(peek(), "unexpected '" + peek().text + "' (expected an operator or the end)");
        return e;
    }

  private:
    [[noreturn]] void fail(std::size_t offset, const std::string& problem,
                           const std::string& hint = "") const {
        source_location at = m_where;
        // Map the offset to a line and column when the text spans several lines.
        int line_shift = 0;
        std::size_t line_start = 0;
        for (std::size_t i = 0; i < offset && i < m_text.size(); ++i)
            if (m_text[i] == '\n') {
                ++line_shift;
                line_start = i + 1;
            }
        if (line_shift > 0) {
            at.line += line_shift;
            at.column = static_cast<int>(offset - line_start) + 1;
        } else {
            at = at.shifted(static_cast<int>(offset));
        }
        throw user_error(at, problem + " in " + m_what + hint);
    }
    [[noreturn]] void fail(const token& t, const std::string& problem,
                           const std::string& hint = "") const {
        fail(t.offset, problem, hint);
    }

    void tokenize() {
        std::size_t i = 0;
        const std::string& s = m_text;
        while (i < s.size()) {
            const unsigned char c = static_cast<unsigned char>(s[i]);
            if (std::isspace(c)) {
                ++i;
            } else if (std::isdigit(c) || (c == '.' && i + 1 < s.size() &&
                                           std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
                const std::size_t start = i;
                while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
                    ++i;
                if (i < s.size() && s[i] == '.') {
                    ++i;
                    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
                        ++i;
                }
                if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
                    std::size_t j = i + 1;
                    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
                    if (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) {
                        i = j;
                        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
                            ++i;
                    }
                }
                m_tokens.push_back({token::number, s.substr(start, i - start), start});
            } else if (std::isalpha(c) || c == '_') {
                const std::size_t start = i;
                while (i < s.size() &&
                       (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_'))
                    ++i;
                m_tokens.push_back({token::name, s.substr(start, i - start), start});
            } else if (c == '*' && i + 1 < s.size() && s[i + 1] == '*') {
                m_tokens.push_back({token::op, "^", i});
                i += 2;
            } else if (std::string("+-*/^(),").find(static_cast<char>(c)) != std::string::npos) {
                m_tokens.push_back({token::op, std::string(1, static_cast<char>(c)), i});
                ++i;
            } else {
                fail(i, "unexpected character " + describe_character(s, i));
            }
        }
        m_tokens.push_back({token::end, "end of expression", s.size()});
    }

    const token& peek() const { return m_tokens[m_pos]; }
    const token& next() { return m_tokens[m_pos++]; }
    bool accept(const char* op) {
        if (peek().kind == token::op && peek().text == op) {
            ++m_pos;
            return true;
        }
        return false;
    }
    void expect(const char* op) {
        if (!accept(op))
            fail(peek(), std::string("expected '") + op + "' but found '" + peek().text + "'");
    }

    // Wraps GiNaC evaluation so that a pole or domain error becomes a user error at `at`.
    template <class F> ex guarded(const token& at, F&& f) {
        try {
            return f();
        } catch (const user_error&) {
            throw;
        } catch (const parser_bug&) {
            throw;
        } catch (const std::exception& e) {
            fail(at, std::string("cannot evaluate: ") + e.what());
        }
    }

    // A sum is built at once from all its terms (adding terms one by one copies the sum each
    // time: quadratic in its length). Like terms' coefficients are added up exactly; their size
    // is bounded first.
    ex expression() {
        const token& first = peek();
        GiNaC::exvector terms{term()};
        while (peek().kind == token::op && (peek().text == "+" || peek().text == "-")) {
            const bool minus = next().text == "-";
            ex rhs = term();
            terms.push_back(minus ? -rhs : rhs);
        }
        if (terms.size() == 1) return terms.front();
        // The coefficients of like terms, n_i / d_i, add up to a number whose numerator and
        // denominator have at most max bits(n_i) + 2 sum bits(distinct d_i) + log2(count) bits.
        struct like_terms {
            std::set<ex, GiNaC::ex_is_less> denominators;
            std::size_t denominator_bits = 0, numerator_bits = 0, count = 0;
        };
        std::map<ex, like_terms, GiNaC::ex_is_less> groups; // by the term without its coefficient
        const auto add_bits = [&](const ex& one) {
            const auto [c, rest] = split_coefficient(one);
            like_terms& g = groups[rest];
            for (const GiNaC::numeric& part : {c.real(), c.imag()}) {
                if (part.is_zero()) continue;
                if (!part.is_rational()) {
                    g.numerator_bits = std::max<std::size_t>(g.numerator_bits, 64);
                    continue;
                }
                if (g.denominators.insert(part.denom()).second)
                    g.denominator_bits += static_cast<std::size_t>(part.denom().int_length());
                g.numerator_bits = std::max<std::size_t>(
                    g.numerator_bits, static_cast<std::size_t>(part.numer().int_length()));
            }
            ++g.count;
            std::size_t count_bits = 0;
            for (std::size_t k = g.count; k > 0; k >>= 1)
                ++count_bits;
            if (g.numerator_bits + 2 * g.denominator_bits + count_bits > max_number_bits)
                fail(first, number_too_large);
        };
        for (const ex& t : terms) {
            if (GiNaC::is_a<GiNaC::add>(t))
                for (std::size_t i = 0; i < t.nops(); ++i)
                    add_bits(t.op(i));
            else
                add_bits(t);
        }
        return guarded(first, [&] { return ex(GiNaC::add(terms)); });
    }

    // A product: multiplied left to right while it is a single factor (GiNaC distributes a number
    // over a sum then), the factors after that collected and multiplied at once (a product, too,
    // is copied when one factor is added).
    ex term() {
        ex e = unary();
        GiNaC::exvector factors;
        std::size_t bits = coefficient_bits(e);
        while (peek().kind == token::op && (peek().text == "*" || peek().text == "/")) {
            const token& op = next();
            ex rhs = unary();
            if (op.text == "/") {
                if (rhs.is_zero()) fail(op, "division by zero");
                rhs = guarded(op, [&] { return GiNaC::pow(rhs, -1); });
            }
            bits += coefficient_bits(rhs);
            if (bits > max_number_bits) fail(op, number_too_large);
            if (factors.empty() && !GiNaC::is_a<GiNaC::mul>(e)) {
                e = guarded(op, [&] { return e * rhs; });
                bits = coefficient_bits(e);
            } else {
                factors.push_back(rhs);
            }
        }
        if (factors.empty()) return e;
        factors.insert(factors.begin(), e);
        const token& at = peek();
        return guarded(at, [&] { return ex(GiNaC::mul(factors)); });
    }

    // Every nesting (parentheses, a call's arguments, an exponent) passes through here.
    ex unary() {
        const token& first = peek();
        if (++m_depth > max_nesting)
            fail(first, "expression nested too deeply (more than " + std::to_string(max_nesting) +
                            " levels)");
        bool negate = false;
        while (peek().kind == token::op && (peek().text == "-" || peek().text == "+"))
            if (next().text == "-") negate = !negate;
        ex e = power();
        --m_depth;
        return negate ? -e : e;
    }

    ex power() {
        ex base = primary();
        if (peek().kind == token::op && peek().text == "^") {
            const token& op = next();
            ex exponent = unary();
            return checked_pow(op, base, exponent);
        }
        return base;
    }

    // base^exponent, refusing 0^(non-positive) and powers whose exact value would be enormous.
    ex checked_pow(const token& at, const ex& base, const ex& exponent) {
        const bool numeric_exponent = GiNaC::is_a<GiNaC::numeric>(exponent);
        // The derivation expands every expression: (a + b)^1000 would expand to a vast sum
        // (found by fuzzing: minutes and gigabytes). Sums may be raised to at most the 32nd power.
        if (numeric_exponent && GiNaC::is_a<GiNaC::add>(base) &&
            GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(exponent)) > 32)
            fail(at,
                 "a sum raised to a power above 32 is not supported (the derivation expands it)");
        if (base.is_zero() && numeric_exponent &&
            !GiNaC::ex_to<GiNaC::numeric>(exponent).is_positive())
            fail(at, "division by zero (0 raised to a non-positive power)");
        const bool trivial_base = GiNaC::is_a<GiNaC::numeric>(base) &&
                                  (base.is_zero() || base.is_equal(1) || base.is_equal(-1));
        if (numeric_exponent && GiNaC::ex_to<GiNaC::numeric>(exponent).is_rational() &&
            !trivial_base) {
            const GiNaC::numeric r = GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(exponent));
            if (r > max_exponent)
                fail(at, "exponent out of range (its magnitude must be at most " +
                             std::to_string(max_exponent) + ")");
            if (GiNaC::numeric(static_cast<long>(coefficient_bits(base))) * r >
                long(max_number_bits))
                fail(at, number_too_large);
        }
        const ex result = guarded(at, [&] { return GiNaC::pow(base, exponent); });
        // (x^a)^b is x^(a b): the limit applies to the combined exponent as well.
        if (GiNaC::is_a<GiNaC::power>(result) && GiNaC::is_a<GiNaC::numeric>(result.op(1)) &&
            GiNaC::ex_to<GiNaC::numeric>(result.op(1)).is_rational() &&
            GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(result.op(1))) > max_exponent)
            fail(at, "exponent out of range (its magnitude must be at most " +
                         std::to_string(max_exponent) + ")");
        return result;
    }

    ex number(const token& t) {
        // mantissa digits / 10^(fraction digits) * 10^exponent, exactly.
        std::string digits;
        long exponent = 0;
        std::size_t i = 0;
        const std::string& s = t.text;
        for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i)
            digits += s[i];
        if (i < s.size() && s[i] == '.') {
            for (++i; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) {
                digits += s[i];
                --exponent;
            }
        }
        if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
            try {
                exponent += std::stol(s.substr(i + 1));
            } catch (const std::exception&) {
                fail(t, "bad number '" + s + "'");
            }
        }
        if (exponent > 4000 || exponent < -4000) fail(t, "number out of range '" + s + "'");
        const auto first = digits.find_first_not_of('0');
        digits = first == std::string::npos ? "0" : digits.substr(first);
        if (digits.size() > max_digits)
            fail(t, "number with more than " + std::to_string(max_digits) + " digits");
        GiNaC::numeric value(digits.c_str());
        return value * GiNaC::numeric(10).power(GiNaC::numeric(exponent));
    }

    std::string suggestion(const std::string& word) const {
        std::vector<std::string> candidates;
        for (const auto& [name, value] : m_names)
            candidates.push_back(name);
        const std::string best = closest_name(word, candidates);
        return best.empty() ? std::string() : "; did you mean '" + best + "'?";
    }

    ex call(const token& name) {
        std::vector<ex> args;
        if (!accept(")")) {
            args.push_back(expression());
            while (accept(","))
                args.push_back(expression());
            expect(")");
        }
        const std::string& f = name.text;
        const std::size_t want = (f == "atan2" || f == "pow") ? 2 : 1;
        if (args.size() != want)
            fail(name, "function '" + f + "' takes " + std::to_string(want) + " argument" +
                           (want == 1 ? "" : "s") + ", got " + std::to_string(args.size()));
        return guarded(name, [&]() -> ex {
            const ex& a = args[0];
            if (f == "sin") return GiNaC::sin(a);
            if (f == "cos") return GiNaC::cos(a);
            if (f == "tan") return GiNaC::tan(a);
            if (f == "asin") return GiNaC::asin(a);
            if (f == "acos") return GiNaC::acos(a);
            if (f == "atan") return GiNaC::atan(a);
            if (f == "atan2") return GiNaC::atan2(a, args[1]);
            if (f == "sinh") return GiNaC::sinh(a);
            if (f == "cosh") return GiNaC::cosh(a);
            if (f == "tanh") return GiNaC::tanh(a);
            if (f == "exp") return GiNaC::exp(a);
            if (f == "log") {
                if (a.is_zero()) fail(name, "log(0) is undefined");
                return GiNaC::log(a);
            }
            if (f == "sqrt") return GiNaC::sqrt(a);
            if (f == "abs") return GiNaC::abs(a);
            if (f == "pow") return checked_pow(name, a, args[1]);
            // Unreachable from input: primary() refuses a name outside known_functions() (with
            // a suggestion) before calling call(); reaching here means the two lists disagree.
            throw parser_bug("expression parser: known function '" + f + "' has no case in call()");
        });
    }

    ex primary() {
        const token& t = next();
        switch (t.kind) {
        case token::number:
            return number(t);
        case token::name: {
            if (peek().kind == token::op && peek().text == "(") {
                next();
                const auto& funcs = known_functions();
                if (std::find(funcs.begin(), funcs.end(), t.text) == funcs.end()) {
                    const std::string best = closest_name(t.text, funcs);
                    fail(t, "unknown function '" + t.text + "'",
                         best.empty() ? "" : "; did you mean '" + best + "'?");
                }
                return call(t);
            }
            auto it = m_names.find(t.text);
            if (it != m_names.end()) return it->second;
            if (t.text == "pi") return GiNaC::Pi;
            fail(t, "unknown symbol '" + t.text + "'", suggestion(t.text));
        }
        case token::op:
            if (t.text == "(") {
                ex e = expression();
                expect(")");
                return e;
            }
            fail(t, "unexpected '" + t.text + "'");
        case token::end:
            fail(t, "unexpected end of expression");
        }
        // Unreachable: the switch covers every token kind (number, name, op, end).
        throw parser_bug("expression parser: a token of unknown kind");
    }

    const std::string& m_text;
    const name_table& m_names;
    source_location m_where;
    std::string m_what;
    std::vector<token> m_tokens;
    std::size_t m_pos = 0;
    int m_depth = 0;
    inline static const std::string number_too_large =
        "numbers too large (an exact value would have more than " +
        std::to_string(max_number_bits * 3 / 10) + " digits)";
};

} // namespace

GiNaC::ex parse_expression(const std::string& text, const name_table& names,
                           const source_location& where, const std::string& what) {
    parser p(text, names, where, what);
    return p.parse();
}

} // namespace rotgen
