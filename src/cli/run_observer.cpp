// Progress line and field output for `adrsph run`.
#include "cli/run_observer.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace adrsph::cli {

std::string format_hms(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?:??:??";
  const long s = std::lround(seconds);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

std::string format_progress(const Progress& p) {
  char buf[200];
  if (p.eta_steady_s >= 0)  // the steady test cannot stop the run before t_min
    std::snprintf(buf, sizeof buf,
                  "t = %.3f/%g s  step %ld  %.0f steps/s  ETA %s (earliest steady stop), %s to "
                  "t_end",
                  p.t, p.t_end, p.step, p.steps_per_s, format_hms(p.eta_steady_s).c_str(),
                  format_hms(p.eta_s).c_str());
  else
    std::snprintf(buf, sizeof buf, "t = %.3f/%g s  step %ld  %.0f steps/s  ETA %s", p.t, p.t_end,
                  p.step, p.steps_per_s, format_hms(p.eta_s).c_str());
  return buf;
}

CliObserver::CliObserver(std::filesystem::path fields_file, ProgressMode progress, bool append)
    : fields_file_(std::move(fields_file)), progress_(progress), append_(append) {}

void CliObserver::log_line(const std::string& text) {
  if (progress_ == ProgressMode::none) return;
  end_progress();
  std::fprintf(stderr, "%s\n", text.c_str());
  std::fflush(stderr);
}

void CliObserver::on_progress(const Progress& p) {
  if (progress_ == ProgressMode::none) return;
  const auto now = std::chrono::steady_clock::now();
  if (progress_ == ProgressMode::log) {
    if (last_print_ == std::chrono::steady_clock::time_point{}) last_print_ = now;
    if (now - last_print_ < std::chrono::seconds(60)) return;
    last_print_ = now;
    std::fprintf(stderr, "progress: %s\n", format_progress(p).c_str());
    std::fflush(stderr);
    return;
  }
  if (printed_ && now - last_print_ < std::chrono::milliseconds(250)) return;
  last_print_ = now;
  // Pad to overwrite a longer previous line.
  std::fprintf(stderr, "\r%-100s", format_progress(p).c_str());
  std::fflush(stderr);
  printed_ = true;
}

void CliObserver::end_progress() {
  if (printed_) std::fprintf(stderr, "\n");
  printed_ = false;
}

void CliObserver::on_fields(const FieldFrame& f) {
  if (!writer_) writer_ = std::make_unique<FieldsWriter>(fields_file_, append_);
  writer_->write(f);
}

std::vector<FieldFrameInfo> CliObserver::close_fields() {
  // A continued run that wrote no new frame still owns the frames of its earlier segments.
  if (!writer_ && append_) writer_ = std::make_unique<FieldsWriter>(fields_file_, true);
  if (!writer_) return {};
  std::vector<FieldFrameInfo> frames = writer_->frames();
  writer_->close();
  writer_.reset();
  return frames;
}

}  // namespace adrsph::cli
