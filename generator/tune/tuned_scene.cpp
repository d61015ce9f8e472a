// rotgen tune: the tuned scene (tuned_scene.hpp).
#include "tune/tuned_scene.hpp"

#include "spec/spec.hpp"
#include "support/format.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>

namespace rotgen {

std::string integrator_line(const integrator_spec& ig) {
    if (ig.fixed_step())
        return "integrator: {method: " + ig.method + ", step: " + short_number(ig.step, 17) + "}";
    return "integrator: {method: " + ig.method + ", rtol: " + short_number(ig.rtol) +
           ", atol: " + short_number(ig.atol) + "}";
}

std::string tuned_scene_text(const scene_spec& scene, const std::string& out_dir, bool with_form) {
    namespace fs = std::filesystem;
    std::string source;
    YAML::Node root = load_yaml_file(scene.file, &source);
    if (root["model"] && root["model"].IsScalar()) {
        const fs::path model = root["model"].Scalar();
        if (model.is_relative()) {
            const fs::path from = fs::absolute(fs::path(scene.file).parent_path() / model);
            root["model"] = fs::path(from.lexically_normal())
                                .lexically_relative(fs::absolute(out_dir))
                                .generic_string();
        }
    }
    if (with_form) root["form"] = std::string(to_string(scene.form));
    YAML::Node ig(YAML::NodeType::Map);
    ig.SetStyle(YAML::EmitterStyle::Flow);
    ig["method"] = scene.integrator.method;
    if (scene.integrator.step > 0) {
        ig["step"] = short_number(scene.integrator.step, 17);
    } else {
        ig["rtol"] = short_number(scene.integrator.rtol);
        ig["atol"] = short_number(scene.integrator.atol);
    }
    root["integrator"] = ig;
    YAML::Emitter out;
    out << root;
    return std::string("# tuned by rotgen tune (method auto, error ") +
           short_number(scene.integrator.error) + "): " + scene.integrator.auto_choice + "\n" +
           out.c_str() + "\n";
}

} // namespace rotgen
