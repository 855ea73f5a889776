// An output directory that is replaced whole or not at all.
// Everything is written into a staging directory next to DIR (DIR.partial-<pid>); commit()
// swaps it in. Until then an existing DIR is untouched, and a staging directory that is never
// committed is removed by the destructor.
#pragma once

#include <filesystem>

namespace adrsph {

class StagedDir {
 public:
  // Checks that `final_dir` may be replaced (absent, empty, or an earlier run's output, i.e.
  // holding run.json; never the working directory or one of its parents), creates its parent
  // directories and the staging directory. Throws std::runtime_error naming the directory.
  explicit StagedDir(std::filesystem::path final_dir);
  ~StagedDir();
  StagedDir(const StagedDir&) = delete;
  StagedDir& operator=(const StagedDir&) = delete;

  const std::filesystem::path& path() const { return staging_; }  // write here
  const std::filesystem::path& final_path() const { return final_; }

  // Replaces DIR by the staging directory (old DIR moved aside, then removed).
  void commit();

 private:
  std::filesystem::path final_, staging_;
  bool committed_ = false;
};

}  // namespace adrsph
