#include "sweep/trajectories.hpp"

#include "support/atomic_file.hpp"
#include "support/error.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace rotgen {

namespace {

// An HDF5 identifier closed at scope exit; a negative id (a failed call) throws.
class h5_id {
  public:
    h5_id(hid_t id, herr_t (*close)(hid_t), const char* what) : m_id(id), m_close(close) {
        if (id < 0 && *what) throw std::runtime_error(std::string("HDF5: cannot create ") + what);
    }
    h5_id(const h5_id&) = delete;
    h5_id& operator=(const h5_id&) = delete;
    h5_id& operator=(h5_id&& other) noexcept {
        std::swap(m_id, other.m_id);
        std::swap(m_close, other.m_close);
        return *this;
    }
    ~h5_id() {
        if (m_id >= 0) m_close(m_id);
    }
    operator hid_t() const { return m_id; }

  private:
    hid_t m_id;
    herr_t (*m_close)(hid_t);
};

void check(herr_t status, const char* what) {
    if (status < 0) throw std::runtime_error(std::string("HDF5: cannot write ") + what);
}

// A variable-length UTF-8 string array attribute `name` on `object`.
// (scalar: one string, not an array of one)
void string_attribute(hid_t object, const char* name, const std::vector<std::string>& values,
                      bool scalar = false) {
    const h5_id type(H5Tcopy(H5T_C_S1), H5Tclose, "a string type");
    check(H5Tset_size(type, H5T_VARIABLE), "a string type");
    check(H5Tset_cset(type, H5T_CSET_UTF8), "a string type");
    const hsize_t n = values.size();
    const h5_id space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose,
                      "a dataspace");
    std::vector<const char*> pointers;
    for (const auto& v : values)
        pointers.push_back(v.c_str());
    const h5_id attribute(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                          name);
    check(H5Awrite(attribute, type, pointers.data()), name);
}

// A double dataset of `dims`, contiguous, allocated at creation, without timestamps.
hid_t double_dataset(hid_t file, const char* name, const std::vector<hsize_t>& dims) {
    const h5_id space(H5Screate_simple(int(dims.size()), dims.data(), nullptr), H5Sclose,
                      "a dataspace");
    const h5_id plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "a property list");
    check(H5Pset_obj_track_times(plist, false), "no timestamps");
    check(H5Pset_alloc_time(plist, H5D_ALLOC_TIME_EARLY), "the allocation time");
    return H5Dcreate2(file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, plist, H5P_DEFAULT);
}

// Writes `what` failing as a user error naming `path`.
[[noreturn]] void cannot_write(const std::string& path, const std::string& what) {
    throw user_error({path}, "cannot write: " + what);
}

constexpr std::size_t members_a_write = 256;

} // namespace

struct trajectory_stream::h5 {
    h5_id file, data;
    h5(hid_t f, const char* path) : file(f, H5Fclose, path), data(-1, H5Dclose, "") {}
    // rows [first, first + n) of a [members, ...] dataset from `values`
    static void write(hid_t dataset, std::size_t first, std::size_t n, const double* values,
                      const char* what) {
        const h5_id space(H5Dget_space(dataset), H5Sclose, "a dataspace");
        hsize_t dims[3] = {0, 0, 0};
        const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
        hsize_t start[3] = {first, 0, 0}, count[3] = {n, dims[1], dims[2]};
        const h5_id memory(H5Screate_simple(rank, count, nullptr), H5Sclose, "a dataspace");
        check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), "a slab");
        check(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, memory, space, H5P_DEFAULT, values), what);
    }
};

namespace {

// Opens or creates the file, failures as user errors naming `path`.
template <class Make>
std::unique_ptr<trajectory_stream::h5> opened(const std::string& path, const Make& make) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // errors are reported once, here
    try {
        return make();
    } catch (const std::runtime_error& e) {
        cannot_write(path, e.what());
    }
}

} // namespace

trajectory_stream::trajectory_stream(std::string path, trajectory_file header,
                                     const values_of_members& values)
    : m_path(std::move(path)), m_header(std::move(header)) {
    m_h5 = opened(m_path, [&] {
        const trajectory_file& f = m_header;
        auto h = std::make_unique<h5>(
            H5Fcreate(m_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), m_path.c_str());
        h->data =
            h5_id(double_dataset(h->file, "trajectories", {f.members, f.samples, f.columns.size()}),
                  H5Dclose, "/trajectories");
        string_attribute(h->data, "columns", f.columns);
        string_attribute(h->data, "varied_keys", f.keys);
        string_attribute(h->data, "scene", {f.scene_text}, true);
        string_attribute(h->data, "scene_file", {f.scene_file}, true);
        const h5_id set(double_dataset(h->file, "varied_values", {f.members, f.keys.size()}),
                        H5Dclose, "/varied_values");
        for (std::size_t first = 0; !f.keys.empty() && first < f.members; first += 65536) {
            const std::size_t n = std::min<std::size_t>(65536, f.members - first);
            h5::write(set, first, n, values(first, n).data(), "/varied_values");
        }
        string_attribute(set, "keys", f.keys);
        check(H5Fflush(h->file, H5F_SCOPE_GLOBAL), path.c_str());
        return h;
    });
}

trajectory_stream::trajectory_stream(std::string path, trajectory_file header, std::size_t next)
    : m_path(std::move(path)), m_header(std::move(header)), m_written(next) {
    m_h5 = opened(m_path, [&] {
        auto h = std::make_unique<h5>(H5Fopen(m_path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT),
                                      m_path.c_str());
        h->data = h5_id(H5Dopen2(h->file, "trajectories", H5P_DEFAULT), H5Dclose, "/trajectories");
        const h5_id space(H5Dget_space(h->data), H5Sclose, "a dataspace");
        hsize_t dims[3] = {0, 0, 0};
        const hsize_t want[3] = {m_header.members, m_header.samples, m_header.columns.size()};
        if (H5Sget_simple_extent_dims(space, dims, nullptr) != 3 ||
            !std::equal(dims, dims + 3, want))
            throw std::runtime_error("/trajectories is not of this sweep's shape");
        return h;
    });
}

trajectory_stream::~trajectory_stream() = default;

void trajectory_stream::add(const std::vector<double>& samples) {
    const std::size_t size = m_header.samples * m_header.columns.size();
    m_buffer.insert(m_buffer.end(), samples.begin(),
                    samples.begin() + std::ptrdiff_t(std::min(size, samples.size())));
    m_buffer.resize((m_buffered + 1) * size, std::numeric_limits<double>::quiet_NaN());
    if (++m_buffered == members_a_write) write_buffered();
}

void trajectory_stream::write_buffered() {
    if (m_buffered == 0) return;
    try {
        h5::write(m_h5->data, m_written, m_buffered, m_buffer.data(), "/trajectories");
    } catch (const std::runtime_error& e) {
        cannot_write(m_path, e.what());
    }
    m_written += m_buffered;
    m_buffered = 0;
    m_buffer.clear();
}

void trajectory_stream::flush() {
    write_buffered();
    if (H5Fflush(m_h5->file, H5F_SCOPE_GLOBAL) < 0) cannot_write(m_path, "HDF5: cannot flush");
}

void trajectory_stream::close() {
    write_buffered();
    m_h5.reset();
}

} // namespace rotgen
