// An output directory that is replaced whole or not at all.
// Everything is written into a staging directory next to DIR (DIR.partial); commit() swaps
// it in. Until then an existing DIR is untouched. A staging directory that is never committed
// is removed by the destructor, unless keep() was called: an interrupted run leaves its
// checkpoint there for `adrsph run --restart DIR`. While a run writes into DIR.partial it
// holds a lock on it, so a second run into the same DIR stops at once.
#pragma once

#include <filesystem>

namespace adrsph {

class StagedDir {
 public:
  enum class Mode {
    fresh,   // a new run: refuses a DIR.partial that holds a checkpoint
    resume,  // continue the run whose checkpoint is in DIR.partial
  };
  // Checks that `final_dir` may be replaced (absent, empty, or an earlier run's output, i.e.
  // holding run.json; never the working directory or one of its parents), creates its parent
  // directories and the staging directory. Throws std::runtime_error naming the directory
  // and what to do.
  explicit StagedDir(std::filesystem::path final_dir, Mode mode = Mode::fresh);
  ~StagedDir();
  StagedDir(const StagedDir&) = delete;
  StagedDir& operator=(const StagedDir&) = delete;

  const std::filesystem::path& path() const { return staging_; }  // write here
  const std::filesystem::path& final_path() const { return final_; }
  static std::filesystem::path staging_path(const std::filesystem::path& final_dir);
  // The checkpoint of an interrupted run into `final_dir` (DIR.partial/checkpoint.h5).
  static std::filesystem::path checkpoint_path(const std::filesystem::path& final_dir);

  // Leave the staging directory in place (an interrupted run with a checkpoint).
  void keep() { keep_ = true; }
  // A staging directory left by a run that died without a checkpoint (SIGKILL, power loss)
  // was found and removed before this run started: the caller says so.
  bool removed_stale() const { return removed_stale_; }
  // Replaces DIR by the staging directory (old DIR moved aside, then removed).
  void commit();

 private:
  void release_lock();
  std::filesystem::path final_, staging_;
  int lock_fd_ = -1;
  bool committed_ = false, keep_ = false, removed_stale_ = false;
};

}  // namespace adrsph
