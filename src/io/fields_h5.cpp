// HDF5 field writer and reader (C API), see include/adrsph/io/fields_h5.hpp for the layout.
#include "adrsph/io/fields_h5.hpp"

#include <cstdio>
#include <span>
#include <type_traits>

#include "io/h5_handle.hpp"

namespace adrsph {
namespace {

static_assert(std::is_same_v<hid_t, std::int64_t>, "hid_t is stored as std::int64_t");

constexpr const char* kDoubleFields[] = {"x", "y", "vx", "vy", "rho", "p", "c"};

template <class T>
hid_t mem_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_NATIVE_DOUBLE;
  else
    return H5T_NATIVE_UINT8;
}

template <class T>
hid_t file_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_IEEE_F64LE;
  else
    return H5T_STD_U8LE;
}

template <class T>
void write_dataset(hid_t group, const std::string& name, std::span<const T> data,
                   const std::string& file) {
  const hsize_t n = data.size();
  const auto space = h5::check(H5Screate_simple(1, &n, nullptr), H5Sclose, file, "create space");
  const auto set = h5::check(H5Dcreate2(group, name.c_str(), file_type<T>(), space.get(),
                                        H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             H5Dclose, file, "create dataset " + name);
  if (n > 0)
    h5::check(H5Dwrite(set.get(), mem_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), file,
              "write dataset " + name);
}

template <class T>
void write_attribute(hid_t obj, const char* name, T value, hid_t ftype, hid_t mtype,
                     const std::string& file) {
  const auto space = h5::check(H5Screate(H5S_SCALAR), H5Sclose, file, "create space");
  const auto attr = h5::check(H5Acreate2(obj, name, ftype, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                              H5Aclose, file, std::string("create attribute ") + name);
  h5::check(H5Awrite(attr.get(), mtype, &value), file, std::string("write attribute ") + name);
}

template <class T>
std::vector<T> read_dataset(hid_t group, const std::string& path, const std::string& name,
                            const std::string& file) {
  const auto set = h5::check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, file,
                             "open dataset " + path + "/" + name);
  const auto space = h5::check(H5Dget_space(set.get()), H5Sclose, file, "read space of " + name);
  if (H5Sget_simple_extent_ndims(space.get()) != 1)
    throw std::runtime_error(file + ": dataset " + path + "/" + name + " is not 1-D");
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  std::vector<T> out(n);
  if (n > 0)
    h5::check(H5Dread(set.get(), mem_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), file,
              "read dataset " + path + "/" + name);
  return out;
}

template <class T>
T read_attribute(hid_t obj, const char* name, hid_t mtype, const std::string& file) {
  const auto attr = h5::check(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, file,
                              std::string("open attribute ") + name);
  T value{};
  h5::check(H5Aread(attr.get(), mtype, &value), file, std::string("read attribute ") + name);
  return value;
}

}  // namespace

std::string field_frame_name(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06zu", index);
  return buf;
}

FieldsWriter::FieldsWriter(std::filesystem::path file) : file_(std::move(file)) {
  h5::silence_errors();
  id_ = H5Fcreate(file_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (id_ < 0) throw std::runtime_error(file_.string() + ": HDF5: cannot create the file");
}

FieldsWriter::~FieldsWriter() {
  close();
}

void FieldsWriter::close() {
  if (id_ >= 0) H5Fclose(id_);
  id_ = -1;
}

void FieldsWriter::write(const FieldFrame& f) {
  const std::string file = file_.string();
  if (id_ < 0) throw std::runtime_error(file + ": HDF5: the file is closed");
  const std::span<const double> arrays[] = {f.x, f.y, f.vx, f.vy, f.rho, f.p, f.c};
  const std::size_t n = f.x.size();
  for (std::size_t i = 0; i < std::size(arrays); ++i)
    if (arrays[i].size() != n)
      throw std::runtime_error(file + ": frame at t = " + std::to_string(f.t) + ": array " +
                               kDoubleFields[i] + " has " + std::to_string(arrays[i].size()) +
                               " values, x has " + std::to_string(n));
  if (f.kind.size() != n)
    throw std::runtime_error(file + ": frame at t = " + std::to_string(f.t) + ": array kind has " +
                             std::to_string(f.kind.size()) + " values, x has " + std::to_string(n));

  const std::string name = field_frame_name(frames_.size());
  const auto group = h5::check(H5Gcreate2(id_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                               H5Gclose, file, "create group " + name);
  write_attribute(group.get(), "time", f.t, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, file);
  write_attribute(group.get(), "step", static_cast<std::int64_t>(f.step), H5T_STD_I64LE,
                  H5T_NATIVE_INT64, file);
  for (std::size_t i = 0; i < std::size(arrays); ++i)
    write_dataset<double>(group.get(), kDoubleFields[i], arrays[i], file);
  write_dataset<std::uint8_t>(group.get(), "kind", f.kind, file);
  h5::check(H5Fflush(id_, H5F_SCOPE_GLOBAL), file, "flush");
  frames_.push_back({f.t, f.step, n});
}

std::size_t count_field_frames(const std::filesystem::path& path) {
  const std::string file = path.string();
  h5::silence_errors();
  const auto f = h5::check(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, file,
                           "open the file");
  std::size_t n = 0;
  while (H5Lexists(f.get(), field_frame_name(n).c_str(), H5P_DEFAULT) > 0) ++n;
  return n;
}

FieldData read_field_frame(const std::filesystem::path& path, std::size_t index) {
  const std::string file = path.string();
  h5::silence_errors();
  const auto f = h5::check(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, file,
                           "open the file");
  const std::string name = field_frame_name(index);
  if (H5Lexists(f.get(), name.c_str(), H5P_DEFAULT) <= 0)
    throw std::runtime_error(file + ": no frame " + name);
  const auto g =
      h5::check(H5Gopen2(f.get(), name.c_str(), H5P_DEFAULT), H5Gclose, file, "open group " + name);
  FieldData d;
  d.t = read_attribute<double>(g.get(), "time", H5T_NATIVE_DOUBLE, file);
  d.step = static_cast<long>(read_attribute<std::int64_t>(g.get(), "step", H5T_NATIVE_INT64, file));
  std::vector<double>* targets[] = {&d.x, &d.y, &d.vx, &d.vy, &d.rho, &d.p, &d.c};
  for (std::size_t i = 0; i < std::size(targets); ++i)
    *targets[i] = read_dataset<double>(g.get(), name, kDoubleFields[i], file);
  d.kind = read_dataset<std::uint8_t>(g.get(), name, "kind", file);
  return d;
}

}  // namespace adrsph
