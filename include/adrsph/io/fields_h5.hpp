// Particle fields in HDF5 (DIR/fields.h5) with an XDMF sidecar (DIR/fields.xmf) for ParaView.
// Layout: one group per frame, /frame_000000, /frame_000001, ... with attributes `time` (s,
// double) and `step` (int64), and 1-D datasets x, y, vx, vy, rho, p, c (double) and kind
// (uint8, values of adrsph::Kind), all of the frame's particle count.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "adrsph/simulation.hpp"

namespace adrsph {

struct FieldFrameInfo {
  double t = 0.0;
  long step = 0;
  std::size_t n = 0;  // particles in the frame
};

// Appends frames to an HDF5 file: a new one (an existing file is replaced), or, with
// `append`, the file of an interrupted run that is continued (its frames are kept). The file
// is open only while a frame is written: a run that dies later keeps its frames, and HDF5
// holds no memory between frames. Errors throw std::runtime_error naming the file.
class FieldsWriter {
 public:
  explicit FieldsWriter(std::filesystem::path file, bool append = false);
  FieldsWriter(const FieldsWriter&) = delete;
  FieldsWriter& operator=(const FieldsWriter&) = delete;

  void write(const FieldFrame& frame);
  void close();  // no frame is written after it (the file itself is closed after each frame)
  const std::vector<FieldFrameInfo>& frames() const { return frames_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  void write_frame(std::int64_t file_id, const FieldFrame& frame);  // file_id: a hid_t
  bool closed_ = false;
  std::vector<FieldFrameInfo> frames_;
};

// Writes the XDMF 2 sidecar: a temporal collection of Polyvertex grids with X_Y geometry,
// pointing into `h5_name` (a path relative to the .xmf file, normally "fields.h5").
// `more_c`: the datasets of the second and later species in every frame ("c_<name>").
void write_fields_xdmf(const std::filesystem::path& xmf, const std::string& h5_name,
                       const std::vector<FieldFrameInfo>& frames,
                       const std::vector<std::string>& more_c = {});

// One frame read back (for tests, post-processing and restarts).
struct FieldData {
  double t = 0.0;
  long step = 0;
  std::vector<double> x, y, vx, vy, rho, p, c;
  std::vector<std::uint8_t> kind;
};

std::size_t count_field_frames(const std::filesystem::path& file);
FieldData read_field_frame(const std::filesystem::path& file, std::size_t index);

// "frame_000042"
std::string field_frame_name(std::size_t index);

}  // namespace adrsph
