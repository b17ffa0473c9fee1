#pragma once
// Owns an HDF5 identifier and closes it with its own close function
// (H5Fclose, H5Dclose, ...) when it goes out of scope.

#include <hdf5.h>

namespace sartor {

class H5Handle {
public:
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~H5Handle() {
    if (id_ >= 0) close_(id_);
  }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  hid_t get() const { return id_; }

private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

} // namespace sartor
