// Helpers of the tests of rotgen's file contract (issue 24): scratch folders, counting what a run
// left behind, a short scene.
#pragma once

#include "support.hpp"

#include <filesystem>
#include <fstream>
#include <string>

namespace rotgen::test {

// A fresh, empty folder ROTGEN_BINARY_DIR/name (what an earlier run left there is removed).
inline std::string fresh_folder(const std::string& name) {
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/" + name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// How many entries a folder holds (to see that a run left nothing behind).
inline std::size_t entries_in(const std::string& dir) {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                                  std::filesystem::directory_iterator()));
}

// A short heavy-top scene at `path`: 11 samples of theta over t in [0, 1], then `extra` lines.
inline std::string write_top_scene(const std::string& path, const std::string& extra = "") {
    std::ofstream(path) << "model: " << model_path("heavy_top") << "\n"
                        << "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, "
                           "theta_dot: 0}\ntime: {end: 1, samples: 11}\n"
                        << "record: [theta]\n"
                        << extra;
    return path;
}

} // namespace rotgen::test
