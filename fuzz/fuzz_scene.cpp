// Fuzz target 3: scene files (generator/scene.cpp, and the model each names or holds inline).
// The scratch directory mirrors the repository's models/ layout: the input is written to
// DIR/scenes/scene.yaml and the shipped models are copied to DIR/*.yaml, so `model:
// ../heavy_top.yaml` (as in the shipped scenes, the seed corpus) resolves. An accepted scene must
// have finite numbers in range, and its model must evaluate to finite real numbers with the scene's
// parameter values.
#include "fuzz_support.hpp"
#include "scene/scene.hpp"

#include <sys/stat.h>

using namespace rotgen;

namespace {
const std::string& scene_path() {
    static const std::string path = [] {
        const std::string dir = fuzz::scratch_dir();
        ::mkdir((dir + "/scenes").c_str(), 0700);
        for (const char* m :
             {"heavy_top", "free_asymmetric_top", "full_tensor_top", "damped_driven_top"}) {
            const std::string text =
                fuzz::read_whole(std::string(ROTGEN_SOURCE_DIR) + "/models/" + m + ".yaml");
            fuzz::write_file(dir + "/" + m + ".yaml", text.data(), text.size());
        }
        return dir + "/scenes/scene.yaml";
    }();
    return path;
}

void check_scene(const scene_spec& s) {
    using fuzz::violation;
    for (double a : s.angles)
        if (!std::isfinite(a)) violation("non-finite initial angle");
    if (!(s.angles[1] >= 0 && s.angles[1] <= 3.141592653589793238))
        violation("initial theta outside [0, pi]");
    for (double r : s.initial_rates)
        if (!std::isfinite(r)) violation("non-finite initial rate");
    if (!std::isfinite(s.t_start) || !std::isfinite(s.t_end) || !(s.t_end > s.t_start))
        violation("bad time span");
    if (s.samples < 2) violation("fewer than 2 samples");
    const integrator_spec& ig = s.integrator;
    if (!(ig.rtol > 0 && std::isfinite(ig.rtol)) || !(ig.atol > 0 && std::isfinite(ig.atol)))
        violation("non-positive or non-finite tolerance");
    if (!(ig.step >= 0 && std::isfinite(ig.step))) violation("negative or non-finite step");
    if (ig.fixed_step() && !(ig.step > 0)) violation("fixed-step method without a step");
    if (ig.max_steps < 1) violation("max_steps < 1");
    if (s.record.empty() || s.record.size() != s.record_where.size()) violation("bad record list");
    if (s.parameters.size() != s.model.parameters.size()) violation("parameter count mismatch");
    GiNaC::exmap values;
    for (std::size_t i = 0; i < s.parameters.size(); ++i) {
        if (!std::isfinite(s.parameters[i])) violation("non-finite parameter value");
        values[s.model.parameters[i].symbol] = s.parameters[i];
    }
    fuzz::check_model(s.model, values);
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string& path = scene_path();
    fuzz::write_file(path, data, size);
    fuzz::expect_result_or_user_error([&] { check_scene(load_scene(path)); });
    return 0;
}
