// Issue 46, item 4: "messages that hide the value". A refused value is printed so that it shows
// why it was refused: `|A A^T - 1| = 1e-08` (not printf's %f, "0.000000"), `norm 1.01`, a norm
// off 1 by 1.1e-6 with its digits, an angle just past pi with enough digits to see it.
#include "error_sites.hpp"
#include "files_support.hpp"

#include <catch2/catch.hpp>

using namespace rotgen::test;

TEST_CASE("refused initial values are printed with the digits that show why", "[cli][messages]") {
    const std::string dir = fresh_folder("value_messages");
    const std::string head = "model: " + model_path("heavy_top") + "\nform: body\ninitial: {";
    const std::string tail = "}\ntime: {end: 1, samples: 3}\n";
    const std::string omega = ", omega1: 0, omega2: 0, omega3: 1";
    using row = std::tuple<std::string, std::string>;
    const auto [initial, message] = GENERATE_COPY(table<std::string, std::string>({
        row{"A: [[1, 0, 0], [0, 1, 0.00000001], [0, 0, 1]]" + omega,
            "s.yaml:3:14: initial A is not a rotation (|A A^T - 1| = 1e-08, det A = 1; it must "
            "be orthonormal to 1e-9 with det +1)"},
        row{"q0: 1.01, q1: 0, q2: 0, q3: 0" + omega,
            "s.yaml:3:15: the initial quaternion (q0, q1, q2, q3) has norm 1.01, not 1 (to "
            "1e-6): give a unit quaternion"},
        row{"q0: 1.0000011, q1: 0, q2: 0, q3: 0" + omega,
            "s.yaml:3:15: the initial quaternion (q0, q1, q2, q3) has norm 1.0000011, not 1 (to "
            "1e-6): give a unit quaternion"},
        row{"phi: 0, theta: 3.1415927, psi: 0" + omega,
            "s.yaml:3:26: initial theta = 3.1415927 is outside [0, pi] (z-x-z Euler angles)"},
    }));
    std::ofstream(dir + "/s.yaml") << head << initial << tail;
    check_error_line(run_rotgen("simulate s.yaml -o s.csv", dir), message);
    CHECK(entries_in(dir) == 1);
}
