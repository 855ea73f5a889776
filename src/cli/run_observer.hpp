// The run command's observer: the progress line on a terminal, and field frames to HDF5.
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>

#include "adrsph/io/fields_h5.hpp"
#include "adrsph/simulation.hpp"

namespace adrsph::cli {

class CliObserver : public RunObserver {
 public:
  enum class ProgressMode {
    none,
    terminal,  // one line rewritten in place (\r) every 0.25 s
    log,       // a new line every minute: stderr redirected to a file (batch runs)
  };
  // `fields_file` is created on the first frame (with `append`, the frames of an interrupted
  // run in it are kept and the new ones added).
  CliObserver(std::filesystem::path fields_file, ProgressMode progress, bool append = false);

  void on_progress(const Progress& p) override;
  void on_fields(const FieldFrame& f) override;

  // Ends the progress line (newline) if one was printed.
  void end_progress();
  // A line of its own on stderr (not with --quiet), e.g. "checkpoint at t = ...".
  void log_line(const std::string& text);
  // Closes fields.h5; returns the frames written (empty when none).
  std::vector<FieldFrameInfo> close_fields();

 private:
  std::filesystem::path fields_file_;
  ProgressMode progress_;
  bool append_ = false;
  bool printed_ = false;
  std::chrono::steady_clock::time_point last_print_{};
  std::unique_ptr<FieldsWriter> writer_;
};

// "t = 1.234/10 s  step 12345  1234 steps/s  ETA 0:12:34"
std::string format_progress(const Progress& p);
// 754 s -> "0:12:34"
std::string format_hms(double seconds);

}  // namespace adrsph::cli
