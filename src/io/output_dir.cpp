// StagedDir: write next to DIR, then swap it in with renames.
#include "adrsph/io/output_dir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace adrsph {
namespace fs = std::filesystem;
namespace {

constexpr const char* kLockFile = ".lock";

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

// An exclusive lock on DIR.partial/.lock, or -1 when another process holds it.
int try_lock(const fs::path& staging) {
  const int fd = ::open((staging / kLockFile).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return -1;
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace

fs::path StagedDir::staging_path(const fs::path& final_dir) {
  fs::path p = normalised(final_dir);
  p += ".partial";
  return p;
}

fs::path StagedDir::checkpoint_path(const fs::path& final_dir) {
  return staging_path(final_dir) / "checkpoint.h5";
}

StagedDir::StagedDir(fs::path final_dir, Mode mode)
    : final_(normalised(std::move(final_dir))), staging_(staging_path(final_)) {
  check_replaceable(final_);
  std::error_code ec;
  if (final_.has_parent_path()) {
    fs::create_directories(final_.parent_path(), ec);
    if (ec) fail(final_, "cannot create the parent directory: " + ec.message());
  }
  const bool has_checkpoint = fs::exists(staging_ / "checkpoint.h5", ec);
  if (mode == Mode::resume && !has_checkpoint)
    fail(final_, "nothing to continue: " + (staging_ / "checkpoint.h5").string() +
                     " does not exist (was the run interrupted, and is DIR the --out it had?)");
  if (fs::exists(staging_, ec)) {
    lock_fd_ = try_lock(staging_);
    if (lock_fd_ < 0)
      fail(final_, "another adrsph run is writing into " + staging_.string() +
                       " (its lock is held); wait for it or choose another --out");
    if (mode == Mode::fresh) {
      if (has_checkpoint) {
        release_lock();
        fail(final_, staging_.string() +
                         " holds an interrupted run (checkpoint.h5): continue it with `adrsph run "
                         "--restart " +
                         final_.string() + "`, or remove " + staging_.string() + " to start over");
      }
      // Left by a run that died without a checkpoint: nothing in it is worth keeping.
      release_lock();
      fs::remove_all(staging_, ec);
      removed_stale_ = true;
    }
  }
  if (mode == Mode::fresh) {
    if (!fs::create_directory(staging_, ec) || ec)
      fail(final_, "cannot create the staging directory " + staging_.string() + ": " +
                       (ec ? ec.message() : std::string("it already exists")));
    lock_fd_ = try_lock(staging_);
    if (lock_fd_ < 0)
      fail(final_, "cannot lock the staging directory " + staging_.string() +
                       " (another run started into it)");
  }
}

StagedDir::~StagedDir() {
  const bool remove = !committed_ && !keep_;
  release_lock();
  if (!remove) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

void StagedDir::release_lock() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // closing drops the flock
  lock_fd_ = -1;
}

void StagedDir::commit() {
  std::error_code ec;
  fs::remove(staging_ / kLockFile, ec);
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
  release_lock();
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace adrsph
