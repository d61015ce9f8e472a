// `rotgen simulate SCENE --from RUN.csv` (issue 31): a run continued from the last row of an
// earlier one. Two chained halves equal the whole run to the method's tolerance, and bit for bit
// for a fixed-step method when the CSV holds the form's whole state, the split point lies on the
// step grid (times exact in binary) and the model is autonomous; the CSV's numbers have 17
// significant digits; a row without a complete state of the scene's form is refused, naming what
// is missing.
#include "run/provenance.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

run_result simulate(const std::string& name, const std::string& text,
                    const std::string& more = "") {
    const scratch_file scene(name + ".yaml", text);
    return run_rotgen("simulate '" + scene.path + "' -o '" + scratch(name + ".csv") + "' " + more);
}

const std::string top = "model: " + model_path("heavy_top") +
                        "\ninitial: {phi: 0.3, theta: 0.5, psi: 0.2, phi_dot: 1, theta_dot: 0.4, "
                        "psi_dot: 30}\n";

// The whole run 0 -> 4 and its two halves 0 -> 2, 2 -> 4 (the second --from the first), each
// sampled every 0.25; returns the CSV texts' lines: whole, then the second half.
std::pair<std::vector<std::string>, std::vector<std::string>>
whole_and_halves(const std::string& name, const std::string& rest) {
    const run_result w = simulate(name + "_whole", top + rest + "time: {end: 4, samples: 17}\n");
    const run_result a = simulate(name + "_a", top + rest + "time: {end: 2, samples: 9}\n");
    const run_result b = simulate(name + "_b", top + rest + "time: {end: 4, samples: 9}\n",
                                  "--from '" + scratch(name + "_a.csv") + "'");
    INFO(w.err << a.err << b.out << b.err);
    REQUIRE(w.status == 0);
    REQUIRE(a.status == 0);
    REQUIRE(b.status == 0);
    CHECK(b.out.find("start   from the last row of " + scratch(name + "_a.csv") +
                     " (line 11), t = 2.0") != std::string::npos);
    return {text_lines(read_file(scratch(name + "_whole.csv"))),
            text_lines(read_file(scratch(name + "_b.csv")))};
}

} // namespace

TEST_CASE("two chained halves of a fixed-step run equal the whole run bit for bit",
          "[simulate][continue]") {
    // The heavy top (autonomous) in its Lagrangian and Hamiltonian forms, the CSV holding the
    // form's whole state; a step of 2^-6, so that every grid time, and the split point 2, is exact;
    // explicit methods (dop853 given a step takes fixed steps). The implicit midpoint rule is not
    // among them: its Newton iteration starts from what the previous step left (observed: the
    // halves differ from the whole run in the last 2-3 digits).
    using row = std::tuple<std::string, std::string>;
    const auto [form, record] = GENERATE(table<std::string, std::string>({
        row{"lagrangian", "[phi, theta, psi, phi_dot, theta_dot, psi_dot, energy]"},
        row{"hamiltonian", "[phi, theta, psi, p_phi, p_theta, p_psi, energy]"},
    }));
    const std::string method = GENERATE(as<std::string>{}, "rk4", "dop853");
    INFO(form << " " << method);
    const auto [whole, half] = whole_and_halves(
        "chain_" + form + "_" + method, "form: " + form + "\nintegrator: {method: " + method +
                                            ", step: 0.015625}\nrecord: " + record + "\n");
    REQUIRE(whole.size() == 19); // provenance line, header and 17 rows
    REQUIRE(half.size() == 11);
    CHECK(half[0] == whole[0]);
    CHECK(half[1] == whole[1]);
    for (std::size_t i = 2; i < half.size(); ++i)
        CHECK(half[i] == whole[i + 8]); // the same text: every digit of every number
}

TEST_CASE("two chained halves of an adaptive run equal the whole run to its tolerance",
          "[simulate][continue]") {
    // DOP853 at rtol 1e-10: the second half starts with a fresh step-size choice, so the runs
    // differ by the method's error, not by rounding.
    const auto [whole, half] = whole_and_halves(
        "chain_dop853", "form: lagrangian\nintegrator: {method: dop853, rtol: 1e-10, atol: "
                        "1e-12}\nrecord: [phi, theta, psi, phi_dot, theta_dot, psi_dot]\n");
    double worst = 0;
    for (std::size_t i = 2; i < half.size(); ++i) { // after the provenance line and the header
        std::istringstream a(half[i]), b(whole[i + 8]);
        std::string x, y;
        while (std::getline(a, x, ',') && std::getline(b, y, ','))
            worst = std::max(worst, std::abs(std::stod(x) - std::stod(y)));
    }
    INFO(worst);
    CHECK(worst > 0);      // not the same computation
    CHECK(worst < 1.5e-9); // observed 1.4e-10
}

TEST_CASE("the CSV's numbers have 17 significant digits: enough to restart exactly",
          "[simulate][continue]") {
    const run_result r = simulate("digits", top + "form: lagrangian\ntime: {end: 1, samples: 11}\n"
                                                  "record: [theta, energy]\n");
    REQUIRE(r.status == 0);
    std::size_t most = 0;
    const auto lines = text_lines(read_file(scratch("digits.csv")));
    for (std::size_t i = 1; i < lines.size(); ++i) {
        std::istringstream in(lines[i]);
        std::string cell;
        while (std::getline(in, cell, ',')) {
            std::size_t digits = 0;
            for (char c : cell.substr(0, cell.find('e')))
                digits += std::isdigit(static_cast<unsigned char>(c)) ? 1 : 0;
            // a mantissa without its leading zeros ("0.0012" has 2 significant digits)
            const std::size_t lead = cell.find_first_of("123456789");
            const std::size_t zeros =
                lead == std::string::npos
                    ? 0
                    : std::count(cell.begin(), cell.begin() + static_cast<long>(lead), '0');
            most = std::max(most, digits - zeros);
            CHECK(digits - zeros <= 17);
        }
    }
    CHECK(most == 17);
}

TEST_CASE("simulate --from refuses a row that is not a complete state of the scene's form, naming "
          "what is "
          "missing, and writes nothing",
          "[simulate][continue][errors]") {
    using row = std::tuple<std::string, std::string>;
    const auto [form, expected] = GENERATE(table<std::string, std::string>({
        row{"lagrangian", ":2:1: the last row (line 5) is not a complete state of the "
                          "lagrangian form: it lacks theta_dot, psi_dot (record phi, theta, "
                          "psi, phi_dot, theta_dot, psi_dot in the run to continue)"},
        row{"hamiltonian", ":2:1: the last row (line 5) is not a complete state of the "
                           "hamiltonian form: it lacks p_phi, p_theta, p_psi (record phi, "
                           "theta, psi, p_phi, p_theta, p_psi in the run to continue)"},
        row{"body", ":2:1: the last row (line 5) is not a complete state of the body form: "
                    "it lacks q0, q1, q2, q3 (record q0, q1, q2, q3, omega1, omega2, omega3 "
                    "in the run to continue)"},
    }));
    INFO(form);
    // the earlier run: a heavy top in the same form (--from refuses another) recording some of
    // its state
    const run_result first = simulate(
        "from_partial", top + "form: " + form +
                            "\ntime: {end: 1, samples: 3}\n"
                            "record: [phi, theta, psi, phi_dot, omega1, omega2, omega3]\n");
    REQUIRE(first.status == 0);
    const std::string csv = scratch("from_partial.csv");
    const run_result r =
        simulate("from_refused", top + "form: " + form + "\ntime: {end: 2, samples: 3}\n",
                 "--from '" + csv + "'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + csv + expected + "\n");
    CHECK_FALSE(std::ifstream(scratch("from_refused.csv")).good());
}

TEST_CASE(
    "simulate --from refuses what cannot be continued: the reduced form's angle, a value, the file",
    "[simulate][continue][errors]") {
    // The reduced free asymmetric top keeps psi (I1 != I2): a row without it cannot start it.
    const std::string asym = "model: " + model_path("free_asymmetric_top") +
                             "\ninitial: {phi: 0, theta: 1, psi: 0.3, omega1: 0.1, omega2: 0.5, "
                             "omega3: 1}\nform: reduced\n";
    // each starts with the provenance line of a run of that model in the reduced form
    const std::string line =
        rotgen::provenance_line(rotgen::provenance_of(
            rotgen::load_model(model_path("free_asymmetric_top")), rotgen::form_kind::reduced)) +
        "\n";
    const scratch_file no_psi("from_no_psi.csv",
                              line + "t,theta,p_phi,p_theta,p_psi\n0,1,0.5,0.1,0.2\n"
                                     "1,1.1,0.5,0.2,0.2\n");
    const scratch_file bad("from_bad.csv", line + "t,theta,p_phi,p_theta,p_psi\n0,1,0.5,0.1,0.2\n"
                                                  "1,1.1,0.5,nan,0.2\n");
    const scratch_file short_row("from_short.csv",
                                 line + "t,theta,p_phi,p_theta,p_psi\n0,1,0.5,0.1,0.2\n1,1.1\n");
    const scratch_file header("from_header.csv", line + "theta,t\n1,0\n");
    const scratch_file empty("from_empty.csv", line + "t,theta,p_phi,p_theta,p_psi\n");
    const scratch_file tilted("from_theta.csv",
                              line + "t,theta,psi,p_phi,p_theta,p_psi\n1,4,0,1,0,1\n");
    const scratch_file at_end("from_at_end.csv",
                              line + "t,theta,psi,p_phi,p_theta,p_psi\n2,1,0,1,0,1\n");
    // paths, not the files: GENERATE_COPY copies what it uses, and a copied scratch_file removes
    // its file when the copy goes
    const std::string no_psi_csv = no_psi.path, bad_csv = bad.path, short_csv = short_row.path,
                      header_csv = header.path, empty_csv = empty.path, at_end_csv = at_end.path,
                      theta_csv = tilted.path, none_csv = scratch("from_none.csv");
    using row = std::tuple<std::string, std::string>;
    const auto [file, expected] = GENERATE_COPY(table<std::string, std::string>({
        row{no_psi_csv, no_psi_csv + ":2:1: the last row (line 4) is not a complete state of the "
                                     "reduced form: it lacks psi (record theta, psi, p_theta, "
                                     "p_psi, p_phi in the run to continue)"},
        row{bad_csv, bad_csv + ":4:11: p_theta = 'nan' is not a finite number: this row cannot "
                               "start a run"},
        row{short_csv, short_csv + ":4:1: the last row has 2 values for the header's 5 columns"},
        row{header_csv, header_csv + ":2:1: not a CSV written by rotgen simulate (its header "
                                     "does not start with t): nothing to continue from"},
        row{empty_csv, empty_csv + ":2:1: the run has no rows to continue from"},
        row{theta_csv, theta_csv + ":3:1: theta = 4 is outside [0, pi] (z-x-z Euler angles)"},
        row{none_csv, none_csv + ": cannot read the run to continue from: No such file or "
                                 "directory"},
        row{at_end_csv, "SCENE:4:13: the run in " + at_end_csv +
                            " ends at t = 2.0, this scene's end time: nothing to continue "
                            "(change time end)"},
    }));
    const scratch_file scene("from_refused2.yaml", asym + "time: {end: 2, samples: 3}\n");
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" +
                                    scratch("from_refused2.csv") + "' --from '" + file + "'");
    std::string want = expected;
    if (want.rfind("SCENE", 0) == 0) want.replace(0, 5, scene.path);
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + want + "\n");
    CHECK_FALSE(std::ifstream(scratch("from_refused2.csv")).good());
}
