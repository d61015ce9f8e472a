// rotgen — deterministic printers for GiNaC expressions.
//
// GiNaC's own output order depends on hash seeds that change from run to run; these printers order
// the terms of every sum and the factors of every product by their printed text, so the same
// expression prints the same way in every run. One method per node type; a node type a printer
// does not know throws (never prints something plausible but wrong).
//
//   text  — SymPy-parsable: `**` for powers, `*` everywhere, pi, standard function names.
//   latex — for documents: \frac, \sin, \dot{\theta}, I_{1}.
//   (C++ is printed from lowered programs by emit/printer.hpp, the one C++ printer.)
#pragma once

#include "expr/angles.hpp"    // angle_convention: the names the coordinates are shown by
#include "support/format.hpp" // format_double

#include <ginac/ginac.h>

#include <functional>
#include <map>
#include <string>

namespace rotgen {

// A printer shows the coordinate, rate and momentum symbols by the names of the model's angle
// convention (expr/angles.hpp's display_name), which it is built with.
class expression_printer {
  public:
    explicit expression_printer(angle_convention angles) : m_angles(std::move(angles)) {}
    virtual ~expression_printer() = default;
    std::string operator()(const GiNaC::ex& e) const { return print(e, 0); }

  protected:
    // Binding strength of the surrounding context: 0 top, 1 sum, 2 product, 3 power base/exponent.
    std::string print(const GiNaC::ex& e, int context) const;

    virtual std::string number(const GiNaC::numeric& n, int context) const;
    virtual std::string symbol(const GiNaC::symbol& s) const;
    virtual std::string constant(const GiNaC::constant& c) const;
    // `negate` prints the sum of the negated terms (for denominators whose sign is chosen here).
    virtual std::string sum(const GiNaC::ex& e, int context, bool negate = false) const;
    virtual std::string product(const GiNaC::ex& e, int context) const;
    virtual std::string power(const GiNaC::ex& base, const GiNaC::ex& exponent, int context) const;
    virtual std::string function(const std::string& name,
                                 const std::vector<std::string>& args) const;

    // Pieces the styles differ in.
    virtual std::string times() const { return "*"; }
    // base (already printed and parenthesised) to a positive integer power.
    virtual std::string integer_power(const std::string& base, int n) const;
    virtual std::string fraction(const std::string& num, const std::string& den) const;
    virtual std::string function_name(const std::string& ginac_name) const { return ginac_name; }

    static std::string parenthesise(const std::string& s) { return "(" + s + ")"; }

    const angle_convention& angles() const { return m_angles; }

  private:
    angle_convention m_angles;
};

class text_printer : public expression_printer {
  public:
    using expression_printer::expression_printer;
};

class latex_printer : public expression_printer {
  public:
    using expression_printer::expression_printer;

  protected:
    std::string number(const GiNaC::numeric& n, int context) const override;
    std::string symbol(const GiNaC::symbol& s) const override;
    std::string constant(const GiNaC::constant& c) const override;
    std::string power(const GiNaC::ex& base, const GiNaC::ex& exponent, int context) const override;
    std::string function(const std::string& name,
                         const std::vector<std::string>& args) const override;
    std::string times() const override { return " "; }
    std::string integer_power(const std::string& base, int n) const override;
    std::string fraction(const std::string& num, const std::string& den) const override;
};

// e printed with the coordinates named by `angles` (the model's convention).
std::string to_text(const GiNaC::ex& e, const angle_convention& angles);
std::string to_latex(const GiNaC::ex& e, const angle_convention& angles);

} // namespace rotgen
