// StagedDir: write next to DIR, then swap it in with renames.
#include "adrsph/io/output_dir.hpp"

#include <unistd.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace adrsph {
namespace fs = std::filesystem;
namespace {

fs::path normalised(fs::path p) {
  p = p.lexically_normal();
  if (!p.empty() && p.filename().empty()) p = p.parent_path();  // "dir/" -> "dir"
  return p;
}

[[noreturn]] void fail(const fs::path& dir, const std::string& why) {
  throw std::runtime_error("output directory " + dir.string() + ": " + why);
}

// DIR must not be the working directory or contain it: replacing it would delete the caller's
// files.
void check_replaceable(const fs::path& dir) {
  std::error_code ec;
  if (dir.empty() || dir.filename() == "." || dir.filename() == "..")
    fail(dir, "expected a directory name, not '.', '..' or empty");
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec)) fail(dir, "exists and is not a directory");
  const fs::path abs = fs::weakly_canonical(dir, ec);
  const fs::path cwd = fs::current_path(ec);
  const auto [a, c] = std::mismatch(abs.begin(), abs.end(), cwd.begin(), cwd.end());
  if (a == abs.end()) fail(dir, "is the working directory or one of its parents");
  if (fs::is_empty(dir, ec)) return;
  if (!fs::exists(dir / "run.json", ec))
    fail(dir,
         "exists and is not an adrsph output directory (no run.json); refusing to replace "
         "it: remove it or choose another --out");
}

}  // namespace

StagedDir::StagedDir(fs::path final_dir) : final_(normalised(std::move(final_dir))) {
  check_replaceable(final_);
  std::error_code ec;
  if (final_.has_parent_path()) {
    fs::create_directories(final_.parent_path(), ec);
    if (ec) fail(final_, "cannot create the parent directory: " + ec.message());
  }
  staging_ = final_;
  staging_ += ".partial-" + std::to_string(::getpid());
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec)
    fail(final_, "cannot create the staging directory " + staging_.string() + ": " +
                     (ec ? ec.message() : std::string("it already exists")));
}

StagedDir::~StagedDir() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

void StagedDir::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(final_, ec)) {
    old = final_;
    old += ".old-" + std::to_string(::getpid());
    fs::remove_all(old, ec);
    fs::rename(final_, old, ec);
    if (ec) fail(final_, "cannot move the old directory aside: " + ec.message());
  }
  fs::rename(staging_, final_, ec);
  if (ec) {
    std::error_code ignore;
    if (!old.empty()) fs::rename(old, final_, ignore);  // put the old one back
    fail(final_, "cannot rename " + staging_.string() + " into place: " + ec.message());
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace adrsph
