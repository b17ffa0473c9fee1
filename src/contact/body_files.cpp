#include "contact/body_files.hpp"

#include "common/error.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace sartor {

namespace {

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(path + ": not valid JSON: " + error.what());
  }
}

double positive_number(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() <= 0.0)
    throw InputError(where + " must be a positive number, got " + value.dump());
  return value.get<double>();
}

Eigen::Vector3d point(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array() || value.size() != 3 ||
      !std::all_of(value.begin(), value.end(), [](const nlohmann::json& v) {
        return v.is_number() && std::isfinite(v.get<double>());
      }))
    throw InputError(where + " must be [x, y, z] in metres, got " + value.dump());
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

// The mean distance from the segment of the vertices nearer to it than to
// 1.5 times the segment's length: a rough radius of the flesh around it.
double flesh_radius(const BodyMesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    bool at_start) {
  const Eigen::Vector3d axis = b - a;
  const double length2 = std::max(axis.squaredNorm(), 1e-12);
  const Eigen::Vector3d end = at_start ? a : b;
  double nearest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : mesh.vertices) {
    const double t = std::clamp((v - a).dot(axis) / length2, 0.0, 1.0);
    if (std::abs(t - (at_start ? 0.0 : 1.0)) > 0.25) continue;
    nearest = std::min(nearest, (v - (a + t * axis)).norm());
  }
  return std::isfinite(nearest) ? nearest : 0.5 * (end - a).norm();
}

} // namespace

MeasurementFile read_measurement_file(const std::string& path) {
  const nlohmann::json file = read_json(path);
  if (!file.is_object() || !file.contains("measurements") || !file["measurements"].is_object())
    throw InputError(path + ": expected {\"name\": ..., \"units\": \"mm\", \"measurements\": "
                            "{...}}");
  for (const auto& [key, value] : file.items())
    if (key != "name" && key != "units" && key != "measurements")
      throw InputError(path + ": unknown key '" + key + "' (name, units, measurements)");
  if (!file.contains("units") || file["units"] != "mm")
    throw InputError(path + ": \"units\" must be \"mm\"");
  MeasurementFile result;
  if (file.contains("name")) {
    if (!file["name"].is_string()) throw InputError(path + ": \"name\" must be a string");
    result.name = file["name"].get<std::string>();
  }
  for (const auto& [key, value] : file["measurements"].items()) {
    const std::string where = path + ": measurements." + key;
    if (!is_known_measurement(key))
      throw InputError(where + ": unknown measurement name (FreeSewing's names, e.g. waist, "
                               "seat, hips, chest, neck, inseam, waistToFloor; docs/bodies.md)");
    const double mm = positive_number(value, where);
    if (default_measurements().count(key)) {
      result.measurements[key] = mm;
    } else {
      result.unused.push_back(key);
    }
  }
  for (const MeasurementUse& use : mannequin_measurements())
    if (!result.measurements.count(use.name)) result.defaulted.push_back(use.name);
  return result;
}

std::vector<Bone> read_skeleton_file(const std::string& path, const BodyMesh& mesh) {
  const nlohmann::json file = read_json(path);
  if (!file.is_object() || !file.contains("bones") || !file["bones"].is_array())
    throw InputError(path + ": expected {\"format\": \"sartor-skeleton\", \"bones\": [...]}");
  if (file.contains("units") && file["units"] != "m")
    throw InputError(path + ": \"units\" must be \"m\"");
  std::vector<Bone> bones;
  for (std::size_t i = 0; i < file["bones"].size(); ++i) {
    const nlohmann::json& entry = file["bones"][i];
    const std::string where = path + ": bones[" + std::to_string(i) + "]";
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string())
      throw InputError(where + ": a bone needs \"name\", \"start\" and \"end\"");
    Bone bone;
    bone.name = entry["name"].get<std::string>();
    const std::string named = where + " (" + bone.name + ")";
    if (entry.contains("parent") && entry["parent"].is_string())
      bone.parent = entry["parent"].get<std::string>();
    if (!entry.contains("start") || !entry.contains("end"))
      throw InputError(named + ": needs \"start\" and \"end\"");
    bone.start = point(entry["start"], named + ".start");
    bone.end = point(entry["end"], named + ".end");
    if ((bone.end - bone.start).norm() < 1e-6) throw InputError(named + ": start and end coincide");
    bone.start_radius = entry.contains("start_radius")
                            ? positive_number(entry["start_radius"], named + ".start_radius")
                            : flesh_radius(mesh, bone.start, bone.end, true);
    bone.end_radius = entry.contains("end_radius")
                          ? positive_number(entry["end_radius"], named + ".end_radius")
                          : flesh_radius(mesh, bone.start, bone.end, false);
    if (std::any_of(bones.begin(), bones.end(), [&](const Bone& b) { return b.name == bone.name; }))
      throw InputError(named + ": a bone of this name comes earlier");
    if (!bone.parent.empty() && std::none_of(bones.begin(), bones.end(),
                                             [&](const Bone& b) { return b.name == bone.parent; }))
      throw InputError(named + ": parent '" + bone.parent + "' is not listed before it");
    bones.push_back(bone);
  }
  return bones;
}

} // namespace sartor
