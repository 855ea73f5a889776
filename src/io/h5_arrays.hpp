// Typed 1-D datasets and scalar attributes over the HDF5 C API (internal to src/io): the few
// shapes the field files and the checkpoints need, with errors that name the file.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "io/h5_handle.hpp"

namespace adrsph::h5 {

// Native (memory) and little-endian file types of the element types we store.
template <class T>
hid_t mem_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<T, float>)
    return H5T_NATIVE_FLOAT;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return H5T_NATIVE_INT64;
  else {
    static_assert(std::is_same_v<T, std::uint8_t>, "unsupported HDF5 element type");
    return H5T_NATIVE_UINT8;
  }
}

template <class T>
hid_t file_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_IEEE_F64LE;
  else if constexpr (std::is_same_v<T, float>)
    return H5T_IEEE_F32LE;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return H5T_STD_I64LE;
  else
    return H5T_STD_U8LE;
}

// With `checksum`, the data is stored in chunks with HDF5's Fletcher-32 filter: a read of a
// damaged chunk fails (H5Dread) instead of returning wrong numbers.
template <class T>
void write_dataset(hid_t group, const std::string& name, std::span<const T> data,
                   const std::string& file, bool checksum = false) {
  const hsize_t n = data.size();
  const auto space = check(H5Screate_simple(1, &n, nullptr), H5Sclose, file, "create space");
  const auto props =
      check(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, file, "create dataset properties");
  if (checksum && n > 0) {
    const hsize_t chunk = std::min<hsize_t>(n, hsize_t{1} << 16);
    check(H5Pset_chunk(props.get(), 1, &chunk), file, "chunk dataset " + name);
    check(H5Pset_fletcher32(props.get()), file, "checksum dataset " + name);
  }
  // No chunk cache: each chunk goes through the filter once, straight to the file, instead
  // of being held (up to 1 MB per dataset) until the dataset is closed.
  const auto access =
      check(H5Pcreate(H5P_DATASET_ACCESS), H5Pclose, file, "create dataset access properties");
  if (checksum && n > 0)
    check(H5Pset_chunk_cache(access.get(), 0, 0, H5D_CHUNK_CACHE_W0_DEFAULT), file,
          "chunk cache of " + name);
  const auto set = check(H5Dcreate2(group, name.c_str(), file_type<T>(), space.get(), H5P_DEFAULT,
                                    props.get(), access.get()),
                         H5Dclose, file, "create dataset " + name);
  if (n > 0)
    check(H5Dwrite(set.get(), mem_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), file,
          "write dataset " + name);
}

template <class T>
std::vector<T> read_dataset(hid_t group, const std::string& path, const std::string& name,
                            const std::string& file) {
  const auto set = check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, file,
                         "open dataset " + path + "/" + name);
  const auto space = check(H5Dget_space(set.get()), H5Sclose, file, "read space of " + name);
  if (H5Sget_simple_extent_ndims(space.get()) != 1)
    throw std::runtime_error(file + ": dataset " + path + "/" + name + " is not 1-D");
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  std::vector<T> out(n);
  if (n > 0)
    check(H5Dread(set.get(), mem_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), file,
          "read dataset " + path + "/" + name);
  return out;
}

template <class T>
void write_attribute(hid_t obj, const char* name, T value, const std::string& file) {
  const auto space = check(H5Screate(H5S_SCALAR), H5Sclose, file, "create space");
  const auto attr =
      check(H5Acreate2(obj, name, file_type<T>(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
            file, std::string("create attribute ") + name);
  check(H5Awrite(attr.get(), mem_type<T>(), &value), file, std::string("write attribute ") + name);
}

template <class T>
T read_attribute(hid_t obj, const char* name, const std::string& file) {
  const auto attr =
      check(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, file, std::string("open attribute ") + name);
  T value{};
  check(H5Aread(attr.get(), mem_type<T>(), &value), file, std::string("read attribute ") + name);
  return value;
}

}  // namespace adrsph::h5
