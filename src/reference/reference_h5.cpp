// DIR/reference.h5 (output of docs/benchmark.md, section 5; issue 4): datasets x (nx),
// y (ny), C (ny x nx, C[j][i] at (x_i, y_j)); scalar attributes D, k, u_bulk, c_in, length,
// half_width (double) and nx, ny (int) on the root group. HDF5 C API.
#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "adrsph/reference.hpp"

namespace adrsph::reference {
namespace {

// Closes an HDF5 handle on scope exit.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5: " + what + " failed");
  }
  ~Handle() { close_(id_); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void write_dataset(hid_t file, const char* name, const std::vector<hsize_t>& dims,
                   const double* data) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               std::string("dataspace ") + name);
  Handle set(H5Dcreate2(file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose, std::string("create dataset ") + name);
  if (H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw std::runtime_error(std::string("HDF5: write dataset ") + name + " failed");
}

template <class T>
void write_attribute(hid_t file, const char* name, hid_t file_type, hid_t mem_type, T value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar dataspace");
  Handle attr(H5Acreate2(file, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  if (H5Awrite(attr, mem_type, &value) < 0)
    throw std::runtime_error(std::string("HDF5: write attribute ") + name + " failed");
}

std::vector<double> read_dataset(hid_t file, const std::string& where, const char* name,
                                 std::size_t expected) {
  Handle set(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose, where + ": open dataset " + name);
  Handle space(H5Dget_space(set), H5Sclose, where + ": dataspace of " + name);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 0 || static_cast<std::size_t>(n) != expected)
    throw std::runtime_error(where + ": dataset " + name + " has " + std::to_string(n) +
                             " values, expected " + std::to_string(expected));
  std::vector<double> v(expected);
  if (H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    throw std::runtime_error(where + ": read dataset " + name + " failed");
  return v;
}

template <class T>
T read_attribute(hid_t file, const std::string& where, const char* name, hid_t mem_type) {
  Handle attr(H5Aopen(file, name, H5P_DEFAULT), H5Aclose, where + ": open attribute " + name);
  T value{};
  if (H5Aread(attr, mem_type, &value) < 0)
    throw std::runtime_error(where + ": read attribute " + name + " failed");
  return value;
}

}  // namespace

ReferenceField read_reference_h5(const std::filesystem::path& path) {
  const std::string where = path.string();
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(where + ": no such file");
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + where);
  ReferenceField f;
  f.nx = read_attribute<int>(file, where, "nx", H5T_NATIVE_INT);
  f.ny = read_attribute<int>(file, where, "ny", H5T_NATIVE_INT);
  if (f.nx < 1 || f.ny < 1) throw std::runtime_error(where + ": bad nx, ny attributes");
  const hid_t d = H5T_NATIVE_DOUBLE;
  f.D = read_attribute<double>(file, where, "D", d);
  f.k = read_attribute<double>(file, where, "k", d);
  f.u_bulk = read_attribute<double>(file, where, "u_bulk", d);
  f.c_in = read_attribute<double>(file, where, "c_in", d);
  f.length = read_attribute<double>(file, where, "length", d);
  f.half_width = read_attribute<double>(file, where, "half_width", d);
  f.x = read_dataset(file, where, "x", static_cast<std::size_t>(f.nx));
  f.y = read_dataset(file, where, "y", static_cast<std::size_t>(f.ny));
  f.c = read_dataset(file, where, "C", static_cast<std::size_t>(f.nx) * f.ny);
  return f;
}

void write_reference_h5(const std::filesystem::path& path, const Solution& s, const Problem& p) {
  const Grid& g = s.grid;
  std::vector<double> x(g.nx), y(g.ny), c(static_cast<std::size_t>(g.cells()));
  for (int i = 0; i < g.nx; ++i) x[i] = g.xc(i);
  for (int j = 0; j < g.ny; ++j) y[j] = g.yc(j);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) c[static_cast<std::size_t>(j) * g.nx + i] = s.at(i, j);

  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
              "create " + path.string());
  write_dataset(file, "x", {static_cast<hsize_t>(g.nx)}, x.data());
  write_dataset(file, "y", {static_cast<hsize_t>(g.ny)}, y.data());
  write_dataset(file, "C", {static_cast<hsize_t>(g.ny), static_cast<hsize_t>(g.nx)}, c.data());
  const hid_t f64 = H5T_IEEE_F64LE, d = H5T_NATIVE_DOUBLE;
  write_attribute(file, "D", f64, d, p.D);
  write_attribute(file, "k", f64, d, p.k);
  write_attribute(file, "u_bulk", f64, d, p.u_bulk);
  write_attribute(file, "c_in", f64, d, p.c_in);
  write_attribute(file, "length", f64, d, p.length);
  write_attribute(file, "half_width", f64, d, p.half_width);
  write_attribute(file, "nx", H5T_STD_I32LE, H5T_NATIVE_INT, g.nx);
  write_attribute(file, "ny", H5T_STD_I32LE, H5T_NATIVE_INT, g.ny);
}

}  // namespace adrsph::reference
