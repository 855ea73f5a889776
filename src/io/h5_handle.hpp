// RAII ownership of an HDF5 identifier (internal to src/io).
#pragma once

#include <hdf5.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <stdexcept>
#include <string>
#include <utility>

namespace adrsph::h5 {

class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      close_ = o.close_;
    }
    return *this;
  }
  ~Handle() { reset(); }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = -1;
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

// Throws when `id` is negative; `what` says what failed, `file` where.
inline Handle check(hid_t id, Handle::Closer close, const std::string& file,
                    const std::string& what) {
  if (id < 0) throw std::runtime_error(file + ": HDF5: cannot " + what);
  return Handle(id, close);
}

inline void check(herr_t status, const std::string& file, const std::string& what) {
  if (status < 0) throw std::runtime_error(file + ": HDF5: cannot " + what);
}

// HDF5 prints its error stack to stderr by default; we report errors ourselves.
inline void silence_errors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

// After a write: HDF5's free lists emptied, then the heap pages they held given back to the
// system (glibc keeps freed pages below the top of the heap resident until trimmed), so that
// what a write used is not held while the run steps on to the next one.
inline void release_write_buffers() {
  H5garbage_collect();
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

}  // namespace adrsph::h5
