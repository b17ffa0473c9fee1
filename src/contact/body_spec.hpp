#pragma once
// Bodies from one-line text specifications, the form case files use:
//     "sphere center=0,0,0.3 radius=0.3 mu=0.4 name=ball"
// The first word is the shape; then key=value pairs, vectors as x,y,z:
//   plane     point=P (0,0,0)  normal=N (0,0,1)
//   sphere    center=C  radius=R
//   capsule   a=A  b=B  radius=R
//   cylinder  center=C (middle of the axis)  direction=D (0,0,1)  radius=R  height=H
//   disk      top=T (centre of the top face)  radius=R  thickness=H (0.01)
//             direction=D (0,0,1, the top face's normal)
//   box       center=C  size=SX,SY,SZ (full extents)  rounding=R (0)
//   mesh      file=BODY.obj (a closed triangle mesh, contact/body_obj.hpp)
//             skeleton=SKELETON.json (for garment construction; checked here)
//   mannequin (the built-in one, contact/mannequin.hpp: feet on z = 0, facing -y)
//             measurements=FILE.json (sized to them, contact/body_files.hpp)
//             pose=JOINT:DEG,... (e.g. knee_l:90,hip_l:45; contact/mannequin.hpp)
// Every body also takes
//   name=NAME (body, body2, ...: the option's name), mu=MU (static and kinetic),
//   mu_s=, mu_k= (separately; mu_k <= mu_s), pivot=P (the fixed point of
//   rotation and scaling; default the centre/point/top/midpoint above, the
//   origin for meshes),
//   translate=T:X,Y,Z;T:X,Y,Z...  rotate=T:DEG;...  rotate_axis=X,Y,Z (0,0,1)
//   scale=T:S;...  (piecewise-linear motions; no spaces inside a value)

#include "contact/body.hpp"
#include "contact/bone_intervals.hpp"
#include "contact/mannequin.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sartor::contact {

// Throws InputError naming `where` (e.g. "option --body2") and what is wrong.
Body parse_body(const std::string& spec, const std::string& where, const std::string& default_name);

// A body garment construction (TAGCON) can dress: a mesh with a skeleton
// and the distance to that mesh. From `spec`: "default" or "mannequin
// [measurements=FILE.json] [pose=...]" (other keys, e.g. mu=, are left to
// parse_body), or "mesh file=BODY.obj skeleton=SKELETON.json". Throws
// InputError naming `where` for any other body or a bad file.
struct GarmentBody {
  Mannequin mannequin; // mesh and skeleton
  std::shared_ptr<const Shape> distance;
  std::string source;      // for logs and OBJ headers
  bool is_default = false; // the built-in mannequin as it stands
  // What the user should know: measurements that kept their defaults,
  // FreeSewing names the mannequin does not use.
  std::vector<std::string> notes;
};
GarmentBody garment_body(const std::string& spec, const std::string& where);

// The bones inside the body `spec` names, in the body's own frame (before
// its motion): a capsule's and a cylinder's axis (named "axis"), the
// mannequin's skeleton (posed), a mesh body's skeleton file; none for the
// other shapes. Wrapping and surface dragging hold back cloth edges that
// would sweep across one (garment/wrap_relax.hpp). Throws InputError naming
// `where` for a bad specification.
std::vector<Bone> body_bones(const std::string& spec, const std::string& where);

// The thesis' spatial index (contact/bone_intervals.hpp) of the body `spec`
// names, for finding cloth vertices inside it before a solve: a mesh body
// with a skeleton file, its triangles filed under its bones in intervals of
// `interval` m. Null for any other body: an analytic shape, the mannequin's
// implicit surface included, answers a point faster than the index would
// (docs/sensitivity.md#penetration-handling). Throws InputError naming
// `where` for a bad specification.
std::shared_ptr<const BoneIntervals> body_bone_intervals(const std::string& spec,
                                                         const std::string& where, double interval);

// The mannequin `spec` names ("default" or "mannequin [measurements=...]
// [pose=...] ..."), sized and posed; nullopt for any other body. Throws
// InputError naming `where` for a bad measurement file or pose.
std::optional<MannequinModel> spec_mannequin(const std::string& spec, const std::string& where);

} // namespace sartor::contact
