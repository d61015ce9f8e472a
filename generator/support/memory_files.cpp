#include "support/memory_files.hpp"

#include <map>
#include <mutex>

namespace rotgen {

namespace {

std::mutex& files_mutex() {
    static std::mutex m;
    return m;
}

std::map<std::string, std::string>& files() {
    static std::map<std::string, std::string> f;
    return f;
}

} // namespace

void set_memory_file(const std::string& path, const std::string& text) {
    const std::lock_guard<std::mutex> lock(files_mutex());
    files()[path] = text;
}

void erase_memory_file(const std::string& path) {
    const std::lock_guard<std::mutex> lock(files_mutex());
    files().erase(path);
}

bool memory_file(const std::string& path, std::string& text) {
    const std::lock_guard<std::mutex> lock(files_mutex());
    const auto it = files().find(path);
    if (it == files().end()) return false;
    text = it->second;
    return true;
}

} // namespace rotgen
