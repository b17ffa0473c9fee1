#include "contact/body_spec.hpp"

#include "common/error.hpp"
#include "contact/analytic_shapes.hpp"
#include "contact/body_files.hpp"
#include "contact/body_obj.hpp"
#include "contact/mannequin_surface.hpp"
#include "contact/mesh_shape.hpp"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

namespace sartor::contact {

namespace {

// m: the default smoothing of a mesh body with a skeleton (mesh_shape.hpp).
constexpr double default_garment_body_smoothing = 1e-4;

using Eigen::Vector3d;

// The key=value pairs of a spec, each used at most once and every one
// required to be consumed by the shape it describes.
class Fields {
public:
  Fields(const std::string& spec, std::string where) : where_(std::move(where)) {
    std::istringstream words(spec);
    if (!(words >> kind_)) fail("empty body specification (expected e.g. 'sphere radius=0.3')");
    std::string word;
    while (words >> word) {
      const auto equals = word.find('=');
      if (equals == std::string::npos || equals == 0 || equals + 1 == word.size()) {
        fail("'" + word + "' is not key=value");
      }
      const std::string key = word.substr(0, equals);
      if (!values_.emplace(key, word.substr(equals + 1)).second) {
        fail("key '" + key + "' is given twice");
      }
    }
  }

  const std::string& kind() const { return kind_; }
  bool has(const std::string& key) const { return values_.count(key) != 0; }

  std::string text(const std::string& key) {
    used_.insert(key);
    return values_.at(key);
  }

  std::string text_required(const std::string& key) {
    if (!has(key)) fail(kind_ + " needs " + key + "=");
    return text(key);
  }

  double number(const std::string& key, std::optional<double> fallback = std::nullopt) {
    if (!has(key)) {
      if (!fallback) fail(kind_ + " needs " + key + "=");
      return *fallback;
    }
    return parse_number(key, text(key));
  }

  double positive(const std::string& key, std::optional<double> fallback = std::nullopt) {
    const double value = number(key, fallback);
    if (!(value > 0.0)) fail(key + " must be > 0, got " + format(value));
    return value;
  }

  Vector3d vector(const std::string& key, std::optional<Vector3d> fallback = std::nullopt) {
    if (!has(key)) {
      if (!fallback) fail(kind_ + " needs " + key + "=X,Y,Z");
      return *fallback;
    }
    return parse_vector(key, text(key));
  }

  // "T:VALUE;T:VALUE;..." with VALUE read by `parse`.
  template <typename Value, typename Parse>
  void history(const std::string& key, PiecewiseLinear<Value>& target, const Parse& parse) {
    if (!has(key)) return;
    std::istringstream samples(text(key));
    std::string sample;
    while (std::getline(samples, sample, ';')) {
      const auto colon = sample.find(':');
      if (colon == std::string::npos) {
        fail(key + ": sample '" + sample + "' is not TIME:VALUE");
      }
      const double time = parse_number(key, sample.substr(0, colon));
      try {
        target.add(time, parse(sample.substr(colon + 1)));
      } catch (const InputError& error) {
        fail(key + ": " + error.what());
      }
    }
  }

  // Every key given must have been used.
  void finish() const {
    for (const auto& [key, value] : values_) {
      if (used_.count(key) == 0) fail("unknown key '" + key + "' for a " + kind_);
    }
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(where_ + ": " + message);
  }

  double parse_number(const std::string& key, const std::string& text) const {
    try {
      std::size_t used = 0;
      const double value = std::stod(text, &used);
      if (used == text.size() && std::isfinite(value)) return value;
    } catch (const std::exception&) {
    }
    fail(key + ": '" + text + "' is not a number");
  }

  Vector3d parse_vector(const std::string& key, const std::string& text) const {
    std::istringstream items(text);
    std::string item;
    std::vector<double> values;
    while (std::getline(items, item, ','))
      values.push_back(parse_number(key, item));
    if (values.size() != 3) fail(key + ": expected X,Y,Z, got '" + text + "'");
    return {values[0], values[1], values[2]};
  }

  static std::string format(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
  }

private:
  std::string where_;
  std::string kind_;
  std::map<std::string, std::string> values_;
  std::set<std::string> used_;
};

// Sizing takes a few tenths of a second; a process asks for the same
// measurement file for contact and for garment construction.
MannequinModel sized_mannequin(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, MannequinModel> sized;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto found = sized.find(path);
  if (found != sized.end()) return found->second;
  return sized.emplace(path, MannequinModel(read_measurement_file(path).measurements))
      .first->second;
}

std::vector<std::string> measurement_notes(const std::string& path) {
  const MeasurementFile file = read_measurement_file(path);
  std::vector<std::string> notes;
  const auto listed = [](const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names)
      text += (text.empty() ? "" : ", ") + name;
    return text;
  };
  if (!file.defaulted.empty())
    notes.push_back(path + " lacks " + listed(file.defaulted) +
                    ": the default mannequin's values are used");
  if (!file.unused.empty())
    notes.push_back(path + ": " + listed(file.unused) + " not used by the mannequin");
  return notes;
}

// mannequin [measurements=FILE.json] [pose=JOINT:DEG,...]
MannequinModel mannequin_model(Fields& fields) {
  MannequinModel model;
  if (fields.has("measurements")) model = sized_mannequin(fields.text("measurements"));
  if (fields.has("pose")) {
    try {
      model = model.posed(parse_pose(fields.text("pose")));
    } catch (const InputError& error) {
      fields.fail(error.what());
    }
  }
  return model;
}

// capsule a=X,Y,Z b=X,Y,Z radius=R: the shape and its bone read the same fields.
struct CapsuleFields {
  Vector3d a, b;
  double radius;
};
CapsuleFields capsule_fields(Fields& fields) {
  const Vector3d a = fields.vector("a"), b = fields.vector("b");
  return {a, b, fields.positive("radius")};
}

// cylinder [center=X,Y,Z] [direction=X,Y,Z] radius=R height=H
struct CylinderFields {
  Vector3d center, direction;
  double radius, height;
};
CylinderFields cylinder_fields(Fields& fields) {
  const Vector3d center = fields.vector("center", Vector3d::Zero());
  const Vector3d direction = fields.vector("direction", Vector3d::UnitZ());
  if (!(direction.norm() > 0.0)) fields.fail("direction must be a non-zero vector");
  const double radius = fields.positive("radius");
  return {center, direction, radius, fields.positive("height")};
}

// The shape a spec names and its pivot (the point motions turn and scale about).
std::pair<std::shared_ptr<const Shape>, Vector3d> make_shape(Fields& fields) {
  const std::string& kind = fields.kind();
  const Vector3d origin = Vector3d::Zero();
  const Vector3d up = Vector3d::UnitZ();
  if (kind == "plane") {
    const Vector3d point = fields.vector("point", origin);
    return {std::make_shared<Plane>(point, fields.vector("normal", up)), point};
  }
  if (kind == "sphere") {
    const Vector3d center = fields.vector("center", origin);
    return {std::make_shared<Sphere>(center, fields.positive("radius")), center};
  }
  if (kind == "capsule") {
    const CapsuleFields c = capsule_fields(fields);
    return {std::make_shared<Capsule>(c.a, c.b, c.radius), 0.5 * (c.a + c.b)};
  }
  if (kind == "cylinder") {
    const CylinderFields c = cylinder_fields(fields);
    return {std::make_shared<Cylinder>(c.center, c.direction, c.radius, c.height), c.center};
  }
  if (kind == "disk") {
    const Vector3d top = fields.vector("top", origin);
    const Vector3d direction = fields.vector("direction", up);
    const double radius = fields.positive("radius");
    const double thickness = fields.positive("thickness", 0.01);
    if (!(direction.norm() > 0.0)) fields.fail("direction must be a non-zero vector");
    const Vector3d center = top - 0.5 * thickness * direction.normalized();
    return {std::make_shared<Cylinder>(center, direction, radius, thickness), top};
  }
  if (kind == "box") {
    const Vector3d center = fields.vector("center", origin);
    const Vector3d size = fields.vector("size");
    if (size.minCoeff() <= 0.0) fields.fail("size must be positive in x, y and z");
    const double rounding = fields.number("rounding", 0.0);
    if (rounding < 0.0 || rounding > 0.5 * size.minCoeff()) {
      fields.fail("rounding must lie in [0, smallest size / 2], got " + Fields::format(rounding));
    }
    return {std::make_shared<Box>(center, size, rounding), center};
  }
  if (kind == "mesh") {
    // A body with a skeleton is one garments drape on: its distance is
    // smoothed by default (edge contact samples settle on the creases of an
    // exact polygonal distance and stall the minimiser; docs/bodies.md).
    const double smoothing =
        fields.number("smoothing", fields.has("skeleton") ? default_garment_body_smoothing : 0.0);
    if (!(smoothing >= 0.0 && smoothing <= 0.01))
      fields.fail("smoothing must lie in [0, 0.01] m, got " + Fields::format(smoothing));
    std::shared_ptr<const Shape> shape = load_mesh_shape(fields.text_required("file"), smoothing);
    // Garment construction reads it (garment_body); contact checks it only.
    if (fields.has("skeleton"))
      read_skeleton_file(fields.text("skeleton"), read_body_obj(fields.text("file")));
    return {shape, origin};
  }
  if (kind == "mannequin") {
    const MannequinModel model = mannequin_model(fields);
    return {std::shared_ptr<const Shape>(make_posed_mannequin_shape(model, model.pose())), origin};
  }
  fields.fail("unknown body '" + kind +
              "' (plane, sphere, capsule, cylinder, disk, box, mesh, mannequin)");
}

} // namespace

Body parse_body(const std::string& spec, const std::string& where,
                const std::string& default_name) {
  Fields fields(spec, where);
  auto [shape, pivot] = [&] {
    try {
      return make_shape(fields);
    } catch (const InputError& error) {
      const std::string message = error.what();
      if (message.rfind(where, 0) == 0) throw;
      fields.fail(message); // a shape's own check: say which option it came from
    }
  }();
  Body body(fields.has("name") ? fields.text("name") : default_name, shape,
            fields.vector("pivot", pivot));

  const double mu = fields.number("mu", 0.0);
  body.friction.static_coefficient = fields.number("mu_s", mu);
  body.friction.kinetic_coefficient =
      fields.number("mu_k", fields.has("mu_s") ? body.friction.static_coefficient : mu);
  if (body.friction.kinetic_coefficient < 0.0 ||
      body.friction.kinetic_coefficient > body.friction.static_coefficient) {
    fields.fail("friction coefficients must satisfy 0 <= mu_k <= mu_s, got mu_s=" +
                Fields::format(body.friction.static_coefficient) +
                " mu_k=" + Fields::format(body.friction.kinetic_coefficient));
  }

  const Vector3d axis = fields.vector("rotate_axis", Vector3d::UnitZ());
  if (!(axis.norm() > 0.0)) fields.fail("rotate_axis must be a non-zero vector");
  body.motion.rotation_axis = axis.normalized();
  fields.history("translate", body.motion.translation,
                 [&](const std::string& v) { return fields.parse_vector("translate", v); });
  fields.history("rotate", body.motion.angle, [&](const std::string& v) {
    return fields.parse_number("rotate", v) * M_PI / 180.0;
  });
  fields.history("scale", body.motion.scale, [&](const std::string& v) {
    const double s = fields.parse_number("scale", v);
    if (!(s > 0.0)) fields.fail("scale: factors must be > 0, got " + Fields::format(s));
    return s;
  });
  fields.finish();
  return body;
}

std::optional<MannequinModel> spec_mannequin(const std::string& spec, const std::string& where) {
  if (spec == "default") return MannequinModel();
  Fields fields(spec, where);
  if (fields.kind() != "mannequin") return std::nullopt;
  try {
    return mannequin_model(fields);
  } catch (const InputError& error) {
    const std::string message = error.what();
    if (message.rfind(where, 0) == 0) throw;
    fields.fail(message);
  }
}

std::vector<Bone> body_bones(const std::string& spec, const std::string& where) {
  if (const std::optional<MannequinModel> model = spec_mannequin(spec, where))
    return model->skeleton();
  Fields fields(spec, where);
  const auto axis = [](const Vector3d& start, const Vector3d& end, double radius) {
    return std::vector<Bone>{{"axis", "", start, end, radius, radius}};
  };
  if (fields.kind() == "capsule") {
    const CapsuleFields c = capsule_fields(fields);
    return axis(c.a, c.b, c.radius);
  }
  if (fields.kind() == "cylinder") {
    const CylinderFields c = cylinder_fields(fields);
    const Vector3d half = 0.5 * c.height * c.direction.normalized();
    return axis(c.center - half, c.center + half, c.radius);
  }
  if (fields.kind() == "mesh" && fields.has("skeleton"))
    return read_skeleton_file(fields.text("skeleton"), read_body_obj(fields.text("file")));
  return {};
}

std::shared_ptr<const BoneIntervals>
body_bone_intervals(const std::string& spec, const std::string& where, double interval) {
  if (spec == "default") return nullptr;
  Fields fields(spec, where);
  if (fields.kind() != "mesh" || !fields.has("skeleton")) return nullptr;
  try {
    const BodyMesh mesh = read_body_obj(fields.text("file"));
    return std::make_shared<const BoneIntervals>(
        mesh, read_skeleton_file(fields.text("skeleton"), mesh), interval);
  } catch (const InputError& error) {
    fields.fail(error.what());
  }
}

GarmentBody garment_body(const std::string& spec, const std::string& where) {
  if (spec == "default") return garment_body("mannequin", where);
  Fields fields(spec, where);
  GarmentBody body;
  try {
    if (fields.kind() == "mannequin") {
      const MannequinModel model = mannequin_model(fields);
      if (model.is_default()) {
        body.mannequin = default_mannequin();
        body.distance = make_mannequin_shape();
        body.source = "built-in mannequin, generated procedurally by Sartor";
        body.is_default = true;
        return body;
      }
      body.mannequin = model.generate();
      if (fields.has("measurements")) body.notes = measurement_notes(fields.text("measurements"));
      body.source = "built-in mannequin sized and posed by Sartor (" + spec + ")";
    } else if (fields.kind() == "mesh") {
      const std::string file = fields.text_required("file");
      body.mannequin.mesh = read_body_obj(file);
      body.mannequin.skeleton =
          read_skeleton_file(fields.text_required("skeleton"), body.mannequin.mesh);
      body.source = "file " + file + " with skeleton " + fields.text("skeleton");
    } else {
      fields.fail("garment construction needs a body with a skeleton: 'mannequin "
                  "[measurements=FILE.json] [pose=...]' or 'mesh file=BODY.obj "
                  "skeleton=SKELETON.json', got '" +
                  fields.kind() + "'");
    }
  } catch (const InputError& error) {
    const std::string message = error.what();
    if (message.rfind(where, 0) == 0) throw;
    fields.fail(message);
  }
  body.distance =
      make_mesh_shape(body.mannequin.mesh.vertices, body.mannequin.mesh.faces, fields.kind());
  return body;
}

} // namespace sartor::contact
