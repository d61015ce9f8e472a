#include "sweep/trajectories.hpp"

#include "support/atomic_file.hpp"
#include "support/error.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>

namespace rotgen {

namespace {

// An HDF5 identifier closed at scope exit; a negative id (a failed call) throws.
class h5_id {
  public:
    h5_id(hid_t id, herr_t (*close)(hid_t), const char* what) : m_id(id), m_close(close) {
        if (id < 0) throw std::runtime_error(std::string("HDF5: cannot create ") + what);
    }
    h5_id(const h5_id&) = delete;
    h5_id& operator=(const h5_id&) = delete;
    ~h5_id() { m_close(m_id); }
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

void write_file(const std::string& path, const trajectory_file& f) {
    const h5_id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                     path.c_str());
    const hsize_t width = f.columns.size();
    const h5_id data(double_dataset(file, "trajectories", {f.members, f.samples, width}), H5Dclose,
                     "/trajectories");
    const hsize_t row[3] = {1, f.samples, width};
    const h5_id memory(H5Screate_simple(3, row, nullptr), H5Sclose, "a dataspace");
    for (hsize_t m = 0; m < f.members; ++m) { // one member at a time: a hyperslab of the file
        const h5_id space(H5Dget_space(data), H5Sclose, "a dataspace");
        const hsize_t start[3] = {m, 0, 0};
        check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, row, nullptr), "a slab");
        check(H5Dwrite(data, H5T_NATIVE_DOUBLE, memory, space, H5P_DEFAULT, f.data[m]->data()),
              "/trajectories");
    }
    string_attribute(data, "columns", f.columns);
    string_attribute(data, "varied_keys", f.keys);
    string_attribute(data, "scene", {f.scene_text}, true);
    string_attribute(data, "scene_file", {f.scene_file}, true);
    const hsize_t nk = f.keys.size();
    const h5_id values(double_dataset(file, "varied_values", {f.members, nk}), H5Dclose,
                       "/varied_values");
    std::vector<double> flat;
    for (const auto& r : *f.values)
        flat.insert(flat.end(), r.begin(), r.end());
    if (!flat.empty())
        check(H5Dwrite(values, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, flat.data()),
              "/varied_values");
    string_attribute(values, "keys", f.keys);
}

} // namespace

void write_trajectories(const std::string& path, const trajectory_file& f) {
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    register_temporary(tmp);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // errors are reported once, here
    try {
        write_file(tmp, f);
    } catch (const std::runtime_error& e) {
        std::remove(tmp.c_str());
        forget_temporary(tmp);
        throw user_error({path}, std::string("cannot write: ") + e.what());
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        forget_temporary(tmp);
        throw user_error({path}, "cannot write: the rename failed");
    }
    forget_temporary(tmp);
}

} // namespace rotgen
