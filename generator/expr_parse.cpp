#include "expr_parse.hpp"

#include "symbols.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

namespace rotgen {

namespace {

using GiNaC::ex;

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
                while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
                if (i < s.size() && s[i] == '.') {
                    ++i;
                    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
                }
                if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
                    std::size_t j = i + 1;
                    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
                    if (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) {
                        i = j;
                        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
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
                fail(i, std::string("unexpected character '") + static_cast<char>(c) + "'");
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
        } catch (const std::exception& e) {
            fail(at, std::string("cannot evaluate: ") + e.what());
        }
    }

    ex expression() {
        ex e = term();
        while (peek().kind == token::op && (peek().text == "+" || peek().text == "-")) {
            const bool minus = next().text == "-";
            ex rhs = term();
            e = minus ? e - rhs : e + rhs;
        }
        return e;
    }

    ex term() {
        ex e = unary();
        while (peek().kind == token::op && (peek().text == "*" || peek().text == "/")) {
            const token& op = next();
            ex rhs = unary();
            if (op.text == "*") {
                e = e * rhs;
            } else {
                if (rhs.is_zero()) fail(op, "division by zero");
                e = guarded(op, [&] { return e / rhs; });
            }
        }
        return e;
    }

    ex unary() {
        if (accept("-")) return -unary();
        if (accept("+")) return unary();
        return power();
    }

    ex power() {
        ex base = primary();
        if (peek().kind == token::op && peek().text == "^") {
            const token& op = next();
            ex exponent = unary();
            if (base.is_zero() && GiNaC::is_a<GiNaC::numeric>(exponent) &&
                !GiNaC::ex_to<GiNaC::numeric>(exponent).is_positive())
                fail(op, "division by zero (0 raised to a non-positive power)");
            return guarded(op, [&] { return GiNaC::pow(base, exponent); });
        }
        return base;
    }

    ex number(const token& t) {
        // mantissa digits / 10^(fraction digits) * 10^exponent, exactly.
        std::string digits;
        long exponent = 0;
        std::size_t i = 0;
        const std::string& s = t.text;
        for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) digits += s[i];
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
        GiNaC::numeric value(digits.c_str());
        return value * GiNaC::numeric(10).power(GiNaC::numeric(exponent));
    }

    std::string suggestion(const std::string& word) const {
        std::vector<std::string> candidates;
        for (const auto& [name, value] : m_names) candidates.push_back(name);
        const std::string best = closest_name(word, candidates);
        return best.empty() ? std::string() : "; did you mean '" + best + "'?";
    }

    ex call(const token& name) {
        std::vector<ex> args;
        if (!accept(")")) {
            args.push_back(expression());
            while (accept(",")) args.push_back(expression());
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
            if (f == "pow") {
                if (a.is_zero() && GiNaC::is_a<GiNaC::numeric>(args[1]) &&
                    !GiNaC::ex_to<GiNaC::numeric>(args[1]).is_positive())
                    fail(name, "division by zero (0 raised to a non-positive power)");
                return GiNaC::pow(a, args[1]);
            }
            fail(name, "unknown function '" + f + "'");
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
        fail(t, "unexpected token");
    }

    const std::string& m_text;
    const name_table& m_names;
    source_location m_where;
    std::string m_what;
    std::vector<token> m_tokens;
    std::size_t m_pos = 0;
};

} // namespace

GiNaC::ex parse_expression(const std::string& text, const name_table& names,
                           const source_location& where, const std::string& what) {
    parser p(text, names, where, what);
    return p.parse();
}

} // namespace rotgen
