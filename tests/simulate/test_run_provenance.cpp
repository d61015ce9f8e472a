// Issue 46, item 6: "--from takes another model's run". Every CSV holding a run's rows starts with
// the provenance line (run/provenance.hpp)
//   # rotgen VERSION model NAME sha256 HASH form FORM
// HASH the SHA-256 of the model file's bytes, as sha256sum prints it (an independent route: the
// test asks sha256sum), the same however the path is spelt. `simulate --from` refuses a run of
// another model or form at the CSV's line 1, naming both; `view` refuses another model's run.
#include "files_support.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <regex>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

// `sha256sum FILE`'s hash.
std::string sha256sum(const std::string& file) {
    std::string out;
    if (FILE* p = ::popen(("sha256sum '" + file + "'").c_str(), "r")) {
        char buf[128];
        while (std::fgets(buf, sizeof buf, p))
            out += buf;
        ::pclose(p);
    }
    return out.substr(0, 64);
}

std::string first_line(const std::string& file) {
    const auto lines = text_lines(read_file(file));
    return lines.empty() ? "" : lines[0];
}

const std::string six = "record: [phi, theta, psi, phi_dot, theta_dot, psi_dot]\n";

// A heavy top's run recording the Lagrangian state, in dir/heavy_top_run.csv.
void heavy_top_run(const std::string& dir) {
    std::ofstream(dir + "/top.yaml")
        << "model: " << model_path("heavy_top") << "\n"
        << "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0}\n"
        << "time: {end: 1, samples: 11}\n"
        << six;
    REQUIRE(run_rotgen("simulate top.yaml -o heavy_top_run.csv -q", dir).status == 0);
}

// A satellite in z-y-z angles (named phi, theta, psi like the heavy top's), dir/sc_zyz.yaml.
void satellite_scene(const std::string& dir) {
    std::ofstream(dir + "/sat_zyz.yaml") << "name: sat_zyz\nangles: {sequence: zyz}\n"
                                         << "parameters: {A: 2.0, B: 3.0, C: 4.0}\n"
                                         << "inertia: [A, B, C]\npotential: 0\n";
    std::ofstream(dir + "/sc_zyz.yaml")
        << "model: sat_zyz.yaml\n"
        << "initial: {theta: 0.5, psi_dot: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0}\n"
        << "time: {end: 3, samples: 4}\n"
        << six;
}

} // namespace

TEST_CASE("every CSV of a run starts with the provenance line: model, sha256 of its file, form",
          "[simulate][provenance]") {
    const std::string dir = fresh_folder("provenance_line");
    const std::string model = model_path("heavy_top");
    const std::string hash = sha256sum(model);
    REQUIRE(hash.size() == 64);
    // the model named by an absolute path, and by a relative one spelt with ./ and ..
    std::ofstream(dir + "/abs.yaml")
        << "model: " << model << "\n"
        << "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0}\n"
        << "time: {end: 1, samples: 11}\nform: hamiltonian\nrecord: [theta]\n"
        << "events: [{name: half, when: t - 0.5}]\n";
    fs::create_directories(dir + "/sub");
    fs::copy_file(model, dir + "/sub/heavy_top.yaml");
    std::string rel = read_file(dir + "/abs.yaml");
    rel.replace(rel.find(model), model.size(), "./sub/../sub/heavy_top.yaml");
    std::ofstream(dir + "/rel.yaml") << rel;
    const std::string version = run_rotgen("--version").out; // "rotgen 0.1.0\n"
    const std::string line = "# rotgen " + version.substr(7, version.size() - 8) +
                             " model heavy_top sha256 " + hash + " form hamiltonian";
    for (const std::string scene : {"abs", "rel"}) {
        INFO(scene);
        const run_result r = run_rotgen("simulate " + scene + ".yaml -o " + scene +
                                            ".csv -q --plot-axis " + scene + ".png",
                                        dir);
        REQUIRE(r.status == 0);
        CHECK(first_line(dir + "/" + scene + ".csv") == line);
        CHECK(first_line(dir + "/" + scene + ".events.csv") == line);
        CHECK(first_line(dir + "/" + scene + ".axis.csv") == line);
        CHECK(text_lines(read_file(dir + "/" + scene + ".csv"))[1] == "t,theta");
        CHECK(read_csv(dir + "/" + scene + ".csv").rows.size() == 11); // the reader skips it
    }
    // a run that cannot finish: its partial rows carry the line too
    std::ofstream(dir + "/stop.yaml")
        << read_file(dir + "/abs.yaml")
        << "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 5}\n";
    CHECK(run_rotgen("simulate stop.yaml -o stop.csv -q", dir).status == 3);
    CHECK(first_line(dir + "/stop.partial.csv") == line);
    CHECK(first_line(dir + "/stop.partial.events.csv") == line);
}

TEST_CASE("simulate --from refuses another model's run: sc_zyz.yaml --from heavy_top_run.csv",
          "[simulate][provenance][continue]") {
    const std::string dir = fresh_folder("provenance_from");
    heavy_top_run(dir);
    satellite_scene(dir);
    const std::string top = sha256sum(model_path("heavy_top")).substr(0, 12),
                      sat = sha256sum(dir + "/sat_zyz.yaml").substr(0, 12);
    run_result r = run_rotgen("simulate sc_zyz.yaml --from heavy_top_run.csv -o sat.csv", dir);
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: heavy_top_run.csv:1:1: the run is of model 'heavy_top' "
                   "(sha256 " +
                       top +
                       ", lagrangian form), not of this scene's model 'sat_zyz' "
                       "(sha256 " +
                       sat +
                       ", lagrangian form): --from continues a run of the same "
                       "model and form\n");
    CHECK_FALSE(fs::exists(dir + "/sat.csv"));
    // the same model in another form
    std::ofstream(dir + "/ham.yaml") << read_file(dir + "/top.yaml") << "form: hamiltonian\n";
    r = run_rotgen("simulate ham.yaml --from heavy_top_run.csv -o ham.csv", dir);
    CHECK(r.status == 2);
    CHECK(r.err.find("heavy_top_run.csv:1:1: the run is of model 'heavy_top' (sha256 " + top +
                     ", lagrangian form), not of this scene's model 'heavy_top' (sha256 " + top +
                     ", hamiltonian form)") != std::string::npos);
    // the same model and form: continued
    std::string later = read_file(dir + "/top.yaml");
    later.replace(later.find("end: 1"), 6, "end: 2");
    std::ofstream(dir + "/later.yaml") << later;
    r = run_rotgen("simulate later.yaml --from heavy_top_run.csv -o more.csv -q", dir);
    CHECK(r.status == 0);
    // a CSV without the line (edited by hand, or from elsewhere)
    std::string body = read_file(dir + "/heavy_top_run.csv");
    std::ofstream(dir + "/bare.csv") << body.substr(body.find('\n') + 1);
    r = run_rotgen("simulate top.yaml --from bare.csv -o bare_more.csv", dir);
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: bare.csv:1:1: line 1 is not rotgen's provenance line "
                   "('# rotgen VERSION model NAME sha256 HASH form FORM'): --from continues only "
                   "a run that rotgen simulate wrote\n");
}

TEST_CASE("view refuses a run of another model, draws its own", "[simulate][provenance][view]") {
    const std::string dir = fresh_folder("provenance_view");
    heavy_top_run(dir);
    satellite_scene(dir);
    run_result r = run_rotgen("view heavy_top_run.csv --model sat_zyz.yaml -o page.html", dir);
    CHECK(r.status == 2);
    CHECK(r.err.find("heavy_top_run.csv:1:1: the run is of model 'heavy_top' (sha256 ") !=
          std::string::npos);
    CHECK(r.err.find("not of the model 'sat_zyz' (sha256 ") != std::string::npos);
    CHECK_FALSE(fs::exists(dir + "/page.html"));
    r = run_rotgen("view heavy_top_run.csv --scene top.yaml -o page.html", dir);
    CHECK(r.status == 0);
    CHECK(fs::exists(dir + "/page.html"));
}
