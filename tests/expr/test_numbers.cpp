// GiNaC numbers from doubles: exact, and no CLN underflow on subnormal values.
#include "expr/numbers.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

using namespace rotgen;
using GiNaC::numeric;

TEST_CASE("a double becomes the rational it is, exactly", "[numbers]") {
    CHECK(exact_rational(0.0) == 0);
    CHECK(exact_rational(-3.0) == -3);
    CHECK(exact_rational(0.1) == numeric(3602879701896397LL) / numeric(36028797018963968LL));
    CHECK(exact_rational(std::ldexp(1.0, 1000)) == numeric(2).power(1000));
    CHECK(exact_rational(std::numeric_limits<double>::max()) ==
          (numeric(2).power(53) - 1) * numeric(2).power(971));
    CHECK(exact_rational(3.0 * (1 + std::ldexp(1.0, -45))) == 3 + 3 * numeric(2).power(-45));
}

TEST_CASE("a subnormal double converts without CLN's underflow", "[numbers]") {
    // GiNaC::numeric(double) throws "floating point underflow" here: CLN has no subnormal floats.
    const double tiny = std::numeric_limits<double>::denorm_min(); // 2^-1074
    REQUIRE(std::fpclassify(tiny) == FP_SUBNORMAL);
    CHECK(exact_rational(tiny) == numeric(2).power(-1074));
    CHECK(exact_rational(-3 * tiny) == -3 * numeric(2).power(-1074));
    const double x = 1e-310; // subnormal, with a mantissa of 43 significant bits
    const numeric r = exact_rational(x);
    CHECK(r * numeric(2).power(1074) == numeric(static_cast<long long>(std::ldexp(x, 1074))));
    // As a float: the same value, compared exactly as rationals.
    CHECK(float_numeric(tiny).is_real());
    CHECK(!float_numeric(tiny).is_rational());
    CHECK(float_numeric(tiny) == numeric(2).power(-1074));
    CHECK(float_numeric(x) == r);
}

TEST_CASE("float_numeric gives what GiNaC::numeric(double) gives for a normal double",
          "[numbers]") {
    for (double x :
         {0.1, -9.81, 1e300, 2.2250738585072014e-308, 3.0 * (1 + std::ldexp(1.0, -45))}) {
        INFO(x);
        CHECK(float_numeric(x) == numeric(x));
        CHECK(float_numeric(x).to_double() == x);
    }
}

TEST_CASE("an infinity or a NaN is no number", "[numbers]") {
    CHECK_THROWS_AS(exact_rational(std::numeric_limits<double>::infinity()), std::domain_error);
    CHECK_THROWS_AS(exact_rational(std::nan("")), std::domain_error);
}
