// Bad `events:` in scene files (generator/scene/events.cpp, run/event_kernels.cpp): exit status 2,
// one line "rotgen: error: FILE:LINE:COL: problem", and neither the samples nor the events written.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <tuple>

using namespace rotgen::test;

TEST_CASE("bad events: exit 2, one located line, nothing written", "[scene][events][errors]") {
    const std::string head = "model: " + model_path("heavy_top") +
                             "\ninitial: {phi: 0, theta: 1, psi: 0, phi_dot: 0, theta_dot: 0, "
                             "psi_dot: 0}\ntime: {end: 1}\n";
    using row = std::tuple<std::string, std::string>;
    const auto [text, line] = GENERATE_COPY(table<std::string, std::string>({
        row{"events: [{name: a, when: thta - 1}]",
            "4:26: unknown symbol 'thta' in event 'a'; did you mean 'theta'?"},
        row{"events: [{name: a, when: ''}]", "4:27: event 'a': 'when' is an empty expression"},
        row{"events: [{name: a, when: theta, direction: up}]",
            "4:44: event 'a': unknown direction 'up' (expected rising, falling or both)"},
        row{"events: [{name: a, when: theta}, {name: a, when: psi}]",
            "4:41: event name 'a' is used twice"},
        row{"events: [{name: a, when: theta, action: halt}]",
            "4:41: event 'a': unknown action 'halt' (expected stop, record, {impulse: [..]}, "
            "{impulse_space: [..]} or {set: {name: value}})"},
        row{"events: [{when: theta}]", "4:10: an event needs 'name'"},
        row{"events: [{name: '1a', when: theta}]",
            "4:18: event name '1a' must be a name: letters, digits and '_', not starting with a "
            "digit"},
        row{"events: []", "4:9: 'events' must be a list of {name, when, direction, action}"},
        row{"events: [{name: a}]",
            "4:10: event 'a' needs 'when' (an expression) or 'every' (a period)"},
        row{"events: [{name: a, when: theta, colour: red}]",
            "4:33: unknown field 'colour' in an event"},
        row{"form: reduced\nevents: [{name: a, when: phi}]",
            "5:26: event 'a': the reduced form does not give 'phi'"},
    }));
    INFO(text);
    const scratch_file scene("bad_events.yaml", head + text + "\n");
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/bad_events.csv";
    const std::string events = std::string(ROTGEN_BINARY_DIR) + "/bad_events.events.csv";
    std::remove(csv.c_str());
    std::remove(events.c_str());
    const run_result r = run_rotgen("simulate bad_events.yaml -o '" + csv + "'", ROTGEN_BINARY_DIR);
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: bad_events.yaml:" + line + "\n");
    CHECK(read_file(csv).empty());
    CHECK(read_file(events).empty());
}
