// Fuzz target 2: model files (generator/spec.cpp, via load_model on a scratch file, so that the
// file reading and YAML error handling of load_yaml_file are covered as well).
// An accepted model must evaluate to finite real numbers at its defaults (fuzz_support.hpp).
#include "fuzz_support.hpp"

using namespace rotgen;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string path = fuzz::scratch_dir() + "/model.yaml";
    fuzz::write_file(path, data, size);
    fuzz::expect_result_or_user_error([&] {
        const model_spec spec = load_model(path);
        fuzz::check_model(spec, spec.parameter_defaults());
    });
    return 0;
}
