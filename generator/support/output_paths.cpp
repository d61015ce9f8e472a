#include "support/output_paths.hpp"

#include "support/error.hpp"

#include <sys/stat.h>

#include <filesystem>

namespace rotgen {

namespace {

namespace fs = std::filesystem;

// What a path resolves to: an existing file's inode, or the path a new file would get.
struct identity {
    bool exists = false, char_device = false;
    dev_t dev = 0;
    ino_t ino = 0;
    std::string path;
};

identity identity_of(const std::string& path) {
    identity id;
    struct stat st {};
    const int found = path == "-" ? ::fstat(1, &st) : ::stat(path.c_str(), &st);
    if (found == 0) {
        id.exists = true;
        id.char_device = S_ISCHR(st.st_mode);
        id.dev = st.st_dev;
        id.ino = st.st_ino;
        return id;
    }
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(follow_links(path), ec), ec);
    id.path = p.lexically_normal().string();
    return id;
}

bool same(const identity& a, const identity& b) {
    if (a.exists != b.exists) return false;
    return a.exists ? a.dev == b.dev && a.ino == b.ino : a.path == b.path;
}

} // namespace

bool is_standard_output(const std::string& path) {
    return path == "-" || same(identity_of(path), identity_of("-"));
}

std::string follow_links(const std::string& path) {
    fs::path p = path;
    std::error_code ec;
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        const fs::path target = fs::read_symlink(p, ec);
        if (ec) break;
        p = target.is_absolute() ? target : p.parent_path() / target;
    }
    return p.string();
}

void check_distinct_files(const std::vector<named_file>& outputs,
                          const std::vector<named_file>& inputs) {
    std::vector<identity> ids;
    for (const auto& o : outputs)
        ids.push_back(identity_of(o.path));
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        for (const auto& in : inputs)
            if (same(ids[i], identity_of(in.path)))
                throw user_error({outputs[i].path}, outputs[i].role + " would write over " +
                                                        in.role + " '" + in.path +
                                                        "', a file this command reads");
        for (std::size_t j = 0; j < i; ++j)
            if (!ids[i].char_device && same(ids[i], ids[j]))
                throw user_error({outputs[i].path}, outputs[j].role + " and " + outputs[i].role +
                                                        " name the same file; give each its "
                                                        "own name");
    }
}

bool is_stream_output(const std::string& path) {
    if (path == "-") return true;
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

} // namespace rotgen
