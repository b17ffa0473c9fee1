#include "fem/checkpoint.hpp"

#include "common/checksum.hpp"
#include "common/error.hpp"
#include "fem/h5_handle.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <unistd.h>

namespace sartor {

namespace {

constexpr const char* format_tag = "sartor-checkpoint 3";

void write_set(hid_t file, const char* name, hid_t type, const void* data,
               const std::vector<hsize_t>& dims, const std::string& path) {
  const H5Handle space(H5Screate_simple(int(dims.size()), dims.data(), nullptr), H5Sclose);
  const H5Handle set(
      H5Dcreate2(file, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (set.get() < 0 || H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    throw InputError(path + ": cannot write " + name);
  }
}

void write_rows(hid_t file, const char* name, const std::vector<double>& values,
                std::size_t columns, const std::string& path) {
  write_set(file, name, H5T_NATIVE_DOUBLE, values.data(), {values.size() / columns, columns}, path);
}

std::size_t file_bytes(hid_t file) {
  hsize_t size = 0;
  H5Fget_filesize(file, &size);
  return std::size_t(size);
}

// The dataset's values and its dimensions; `required` false: empty when absent.
std::vector<double> read_rows(hid_t file, const char* name, std::size_t columns,
                              const std::string& path, bool required = true) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) {
    if (!required) return {};
    throw InputError(path + ": not a complete checkpoint (no dataset " + name + ")");
  }
  const H5Handle set(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  const H5Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(std::size_t(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  std::size_t count = 1;
  for (hsize_t d : dims)
    count *= std::size_t(d);
  const bool shaped = (columns == 1 && rank <= 1) || (rank == 2 && dims[1] == columns);
  if (set.get() < 0 || !shaped) {
    throw InputError(path + ": dataset " + name + " does not have " + std::to_string(columns) +
                     " column(s)");
  }
  if (count > file_bytes(file) / sizeof(double)) {
    throw InputError(path + ": dataset " + name + " claims more values than the file holds");
  }
  std::vector<double> values(count);
  if (count > 0 &&
      H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    throw InputError(path + ": cannot read dataset " + name);
  }
  return values;
}

double read_scalar(hid_t file, const char* name, const std::string& path) {
  const auto values = read_rows(file, name, 1, path);
  if (values.size() != 1) throw InputError(path + ": dataset " + name + " is not a scalar");
  return values.front();
}

// The format attribute, or "" when there is none.
std::string read_format(hid_t file) {
  if (H5Aexists(file, "format") <= 0) return "";
  const H5Handle attribute(H5Aopen(file, "format", H5P_DEFAULT), H5Aclose);
  const H5Handle type(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) return "";
  std::string text(H5Tget_size(type.get()), '\0');
  if (H5Aread(attribute.get(), type.get(), text.data()) < 0) return "";
  return text.substr(0, text.find('\0'));
}

// A character dataset; `required` false: "" when absent.
std::string read_text(hid_t file, const char* name, const std::string& path, bool required) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) {
    if (!required) return "";
    throw InputError(path + ": not a complete checkpoint (no " + name + ")");
  }
  const H5Handle set(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
  if (set.get() < 0) throw InputError(path + ": cannot open " + name);
  const H5Handle space(H5Dget_space(set.get()), H5Sclose);
  const hssize_t characters = H5Sget_simple_extent_npoints(space.get());
  if (characters < 0 || std::size_t(characters) > file_bytes(file)) {
    throw InputError(path + ": dataset " + name + " claims more characters than the file holds");
  }
  std::string text(std::size_t(characters), '\0');
  if (!text.empty() &&
      H5Dread(set.get(), H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()) < 0) {
    throw InputError(path + ": cannot read " + name);
  }
  return text;
}

std::uint64_t read_checksum(hid_t file, const std::string& name, const std::string& path) {
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) {
    throw InputError(path + ": not a complete checkpoint (no dataset " + name + ")");
  }
  const H5Handle set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  const H5Handle space(H5Dget_space(set.get()), H5Sclose);
  unsigned long long sum = 0;
  if (set.get() < 0 || H5Sget_simple_extent_npoints(space.get()) != 1 ||
      H5Dread(set.get(), H5T_NATIVE_ULLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &sum) < 0) {
    throw InputError(path + ": cannot read dataset " + name);
  }
  return sum;
}

// The file's data reach the disk before the rename makes it the checkpoint.
void flush_to_disk(const std::string& path) {
  const int descriptor = ::open(path.c_str(), O_RDONLY);
  if (descriptor < 0) throw InputError(path + ": cannot reopen to flush");
  const int status = ::fsync(descriptor);
  ::close(descriptor);
  if (status != 0) throw InputError(path + ": cannot flush to disk");
}

// The rename reaches the disk: the folder's entry is flushed too (a failure
// here leaves the new checkpoint in place, so it is not an error).
void flush_directory(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const int descriptor = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (descriptor < 0) return;
  ::fsync(descriptor);
  ::close(descriptor);
}

std::vector<double> anchor_rows(const std::vector<AnchorRow>& anchors) {
  std::vector<double> values;
  for (const auto& row : anchors)
    values.insert(values.end(), row.begin(), row.end());
  return values;
}

// The sum of everything a checkpoint holds, in the order it is written.
std::uint64_t checksum(const RunCheckpoint& checkpoint) { // NOLINT(misc-no-recursion)
  Checksum sum;
  sum.add(checkpoint.time);
  sum.add(checkpoint.next_step);
  sum.add(checkpoint.load_factor);
  const long long step = checkpoint.step;
  sum.add(&step, sizeof step);
  sum.add(position_rows(checkpoint.positions));
  sum.add(position_rows(checkpoint.velocities));
  sum.add(creep_rows(checkpoint.creep));
  sum.add(anchor_rows(checkpoint.anchors));
  sum.add(checkpoint.history.data(), checkpoint.history.size());
  sum.add(checkpoint.state.data(), checkpoint.state.size());
  // Summed only when present, so that files without them sum as before.
  if (!checkpoint.start_positions.empty()) sum.add(position_rows(checkpoint.start_positions));
  if (checkpoint.before) {
    const std::uint64_t before = checksum(*checkpoint.before);
    sum.add(&before, sizeof before);
  }
  return sum.value();
}

// The checkpoint's datasets in `group` ("" for the file's root).
void write_contents(hid_t f, const std::string& group, const RunCheckpoint& checkpoint,
                    const std::string& path) {
  const auto name = [&group](const char* set) { return group + set; };
  write_set(f, name("/time").c_str(), H5T_NATIVE_DOUBLE, &checkpoint.time, {1}, path);
  write_set(f, name("/next_step").c_str(), H5T_NATIVE_DOUBLE, &checkpoint.next_step, {1}, path);
  write_set(f, name("/load_factor").c_str(), H5T_NATIVE_DOUBLE, &checkpoint.load_factor, {1}, path);
  const long long step = checkpoint.step;
  write_set(f, name("/step").c_str(), H5T_NATIVE_LLONG, &step, {1}, path);
  write_rows(f, name("/positions").c_str(), position_rows(checkpoint.positions), 3, path);
  if (!checkpoint.velocities.empty()) {
    write_rows(f, name("/velocities").c_str(), position_rows(checkpoint.velocities), 3, path);
  }
  if (!checkpoint.start_positions.empty()) {
    write_rows(f, name("/start_positions").c_str(), position_rows(checkpoint.start_positions), 3,
               path);
  }
  write_rows(f, name("/creep").c_str(), creep_rows(checkpoint.creep), 6, path);
  write_rows(f, name("/anchors").c_str(), anchor_rows(checkpoint.anchors), 10, path);
  const unsigned long long sum = checksum(checkpoint);
  write_set(f, name("/checksum").c_str(), H5T_NATIVE_ULLONG, &sum, {1}, path);
  write_set(f, name("/history").c_str(), H5T_NATIVE_CHAR, checkpoint.history.data(),
            {checkpoint.history.size()}, path);
  if (!checkpoint.state.empty()) {
    write_set(f, name("/state").c_str(), H5T_NATIVE_CHAR, checkpoint.state.data(),
              {checkpoint.state.size()}, path);
  }
  if (checkpoint.before) {
    if (checkpoint.before->before) throw InputError(path + ": a checkpoint nests one phase only");
    const H5Handle before(
        H5Gcreate2(f, name("/before").c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (before.get() < 0) throw InputError(path + ": cannot write /before");
    write_contents(f, name("/before"), *checkpoint.before, path);
  }
}

// The checkpoint in `group` ("" for the file's root), its checksum verified.
RunCheckpoint read_contents(hid_t f, const std::string& group, // NOLINT(misc-no-recursion)
                            const std::string& path) {
  const auto name = [&group](const char* set) { return group + set; };
  RunCheckpoint checkpoint;
  checkpoint.time = read_scalar(f, name("/time").c_str(), path);
  checkpoint.next_step = read_scalar(f, name("/next_step").c_str(), path);
  checkpoint.load_factor = read_scalar(f, name("/load_factor").c_str(), path);
  const double step = read_scalar(f, name("/step").c_str(), path);
  if (!(step >= 0.0 && step <= 1e15)) throw InputError(path + ": the step count is not valid");
  checkpoint.step = long(step);
  checkpoint.positions = positions_from_rows(read_rows(f, name("/positions").c_str(), 3, path));
  checkpoint.velocities =
      positions_from_rows(read_rows(f, name("/velocities").c_str(), 3, path, false));
  checkpoint.start_positions =
      positions_from_rows(read_rows(f, name("/start_positions").c_str(), 3, path, false));
  checkpoint.creep = creep_from_rows(read_rows(f, name("/creep").c_str(), 6, path));
  const auto anchors = read_rows(f, name("/anchors").c_str(), 10, path);
  for (std::size_t i = 0; i + 10 <= anchors.size(); i += 10) {
    AnchorRow row;
    std::copy_n(anchors.begin() + long(i), 10, row.begin());
    checkpoint.anchors.push_back(row);
  }
  checkpoint.history = read_text(f, name("/history").c_str(), path, true);
  checkpoint.state = read_text(f, name("/state").c_str(), path, false);
  // Only the file's root may hold the phase before (a group, not a dataset).
  if (group.empty() && H5Lexists(f, "/before", H5P_DEFAULT) > 0) {
    if (H5Lexists(f, "/before/before", H5P_DEFAULT) > 0)
      throw InputError(path + ": a checkpoint nests one phase only (/before/before)");
    checkpoint.before = std::make_shared<const RunCheckpoint>(read_contents(f, "/before", path));
  }
  if (checksum(checkpoint) != read_checksum(f, name("/checksum"), path)) {
    throw InputError(path + ": the checkpoint is corrupted (its checksum does not match its "
                            "contents); resume from another checkpoint or start again");
  }
  if (!(checkpoint.time >= 0.0) || !std::isfinite(checkpoint.time) ||
      !(checkpoint.next_step > 0.0) || !std::isfinite(checkpoint.next_step)) {
    throw InputError(path + ": time or next step size is not valid");
  }
  return checkpoint;
}

} // namespace

void write_checkpoint(const std::string& path, const RunCheckpoint& checkpoint) {
  const std::string temporary = path + ".tmp";
  {
    const H5Handle file(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                        H5Fclose);
    if (file.get() < 0) throw InputError(path + ": cannot create checkpoint file " + temporary);
    const hid_t f = file.get();
    write_contents(f, "", checkpoint, path);
    const H5Handle string_type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(string_type.get(), std::strlen(format_tag));
    const H5Handle scalar(H5Screate(H5S_SCALAR), H5Sclose);
    const H5Handle attribute(
        H5Acreate2(f, "format", string_type.get(), scalar.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    if (attribute.get() < 0 || H5Awrite(attribute.get(), string_type.get(), format_tag) < 0) {
      throw InputError(path + ": cannot write the format tag");
    }
  }
  flush_to_disk(temporary);
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    throw InputError(path + ": cannot replace the checkpoint with " + temporary);
  }
  flush_directory(path);
}

RunCheckpoint read_checkpoint(const std::string& path) {
  // HDF5 would print its own error stack for a file that is not HDF5.
  H5E_auto2_t handler = nullptr;
  void* handler_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &handler, &handler_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  struct RestoreHandler {
    H5E_auto2_t handler;
    void* data;
    ~RestoreHandler() { H5Eset_auto2(H5E_DEFAULT, handler, data); }
  } restore{handler, handler_data};

  const H5Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (file.get() < 0) throw InputError(path + ": cannot open as an HDF5 checkpoint");
  const hid_t f = file.get();
  if (read_format(f) != format_tag) {
    throw InputError(path + ": not a Sartor checkpoint (its format is not '" +
                     std::string(format_tag) + "')");
  }
  return read_contents(f, "", path);
}

const RunCheckpoint& first_phase(const RunCheckpoint& checkpoint) {
  return checkpoint.before ? *checkpoint.before : checkpoint;
}

std::vector<double> position_rows(const std::vector<Eigen::Vector3d>& positions) {
  std::vector<double> values;
  values.reserve(3 * positions.size());
  for (const Eigen::Vector3d& p : positions)
    values.insert(values.end(), {p.x(), p.y(), p.z()});
  return values;
}

std::vector<Eigen::Vector3d> positions_from_rows(const std::vector<double>& values) {
  if (values.size() % 3 != 0) throw std::invalid_argument("positions are not triples");
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(values.size() / 3);
  for (std::size_t i = 0; i < values.size(); i += 3)
    positions.emplace_back(values[i], values[i + 1], values[i + 2]);
  return positions;
}

std::vector<double> creep_rows(const std::vector<ElementCreep>& states) {
  std::vector<double> values;
  values.reserve(6 * states.size());
  for (const ElementCreep& c : states)
    values.insert(values.end(), {c.warp.viscoelastic, c.warp.permanent, c.weft.viscoelastic,
                                 c.weft.permanent, c.tension_warp, c.tension_weft});
  return values;
}

std::vector<ElementCreep> creep_from_rows(const std::vector<double>& values) {
  if (values.size() % 6 != 0) throw std::invalid_argument("creep states are not of 6 values");
  std::vector<ElementCreep> states;
  states.reserve(values.size() / 6);
  for (std::size_t i = 0; i < values.size(); i += 6)
    states.push_back(
        {{values[i], values[i + 1]}, {values[i + 2], values[i + 3]}, values[i + 4], values[i + 5]});
  return states;
}

} // namespace sartor
