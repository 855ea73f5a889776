// HDF5 field writer and reader (C API), see include/adrsph/io/fields_h5.hpp for the layout.
#include "adrsph/io/fields_h5.hpp"

#include <cstdio>
#include <span>
#include <type_traits>

#include "io/h5_arrays.hpp"

namespace adrsph {
namespace {

static_assert(std::is_same_v<hid_t, std::int64_t>, "hid_t is stored as std::int64_t");

constexpr const char* kDoubleFields[] = {"x", "y", "vx", "vy", "rho", "p", "c"};

}  // namespace

std::string field_frame_name(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06zu", index);
  return buf;
}

FieldsWriter::FieldsWriter(std::filesystem::path file, bool append) : file_(std::move(file)) {
  h5::silence_errors();
  const std::string name = file_.string();
  if (!append) {
    const auto f = h5::check(H5Fcreate(file_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                             H5Fclose, name, "create the file");
    return;
  }
  const auto f = h5::check(H5Fopen(file_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, name,
                           "open the file to append frames");
  // The frames written before the interruption stay in the XDMF index.
  for (std::size_t k = 0; H5Lexists(f.get(), field_frame_name(k).c_str(), H5P_DEFAULT) > 0; ++k) {
    const std::string frame = field_frame_name(k);
    const auto g = h5::check(H5Gopen2(f.get(), frame.c_str(), H5P_DEFAULT), H5Gclose, name,
                             "open group " + frame);
    const auto x = h5::check(H5Dopen2(g.get(), "x", H5P_DEFAULT), H5Dclose, name,
                             "open dataset " + frame + "/x");
    const auto space = h5::check(H5Dget_space(x.get()), H5Sclose, name, "read space of x");
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space.get(), &n, nullptr);
    frames_.push_back({h5::read_attribute<double>(g.get(), "time", name),
                       static_cast<long>(h5::read_attribute<std::int64_t>(g.get(), "step", name)),
                       static_cast<std::size_t>(n)});
  }
}

void FieldsWriter::close() {
  closed_ = true;
}

void FieldsWriter::write(const FieldFrame& f) {
  const std::string file = file_.string();
  if (closed_) throw std::runtime_error(file + ": HDF5: the file is closed");
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

  {
    // Opened for this frame only, and HDF5's free lists emptied after it: its metadata cache
    // and buffers (~0.8 MB) are not held between frames (perf/README.md, section 3.10), and
    // a run that dies between frames leaves a closed file.
    const auto fid = h5::check(H5Fopen(file_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, file,
                               "open the file to add a frame");
    write_frame(fid.get(), f);
  }
  h5::release_write_buffers();
  frames_.push_back({f.t, f.step, n});
}

void FieldsWriter::write_frame(std::int64_t id, const FieldFrame& f) {
  const std::string file = file_.string();
  const std::size_t n = f.x.size();
  const std::span<const double> arrays[] = {f.x, f.y, f.vx, f.vy, f.rho, f.p, f.c};
  const std::string name = field_frame_name(frames_.size());
  const auto group = h5::check(H5Gcreate2(id, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                               H5Gclose, file, "create group " + name);
  h5::write_attribute(group.get(), "time", f.t, file);
  h5::write_attribute(group.get(), "step", static_cast<std::int64_t>(f.step), file);
  for (std::size_t i = 0; i < std::size(arrays); ++i)
    h5::write_dataset<double>(group.get(), kDoubleFields[i], arrays[i], file);
  h5::write_dataset<std::uint8_t>(group.get(), "kind", f.kind, file);
  for (const auto& [more_name, values] : f.more_c) {
    if (values.size() != n)
      throw std::runtime_error(file + ": frame at t = " + std::to_string(f.t) + ": array " +
                               more_name + " has " + std::to_string(values.size()) +
                               " values, x has " + std::to_string(n));
    h5::write_dataset<double>(group.get(), more_name, values, file);
  }
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
  d.t = h5::read_attribute<double>(g.get(), "time", file);
  d.step = static_cast<long>(h5::read_attribute<std::int64_t>(g.get(), "step", file));
  std::vector<double>* targets[] = {&d.x, &d.y, &d.vx, &d.vy, &d.rho, &d.p, &d.c};
  for (std::size_t i = 0; i < std::size(targets); ++i)
    *targets[i] = h5::read_dataset<double>(g.get(), name, kDoubleFields[i], file);
  d.kind = h5::read_dataset<std::uint8_t>(g.get(), name, "kind", file);
  return d;
}

}  // namespace adrsph
