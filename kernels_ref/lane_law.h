// The contact law's text in SIMD lanes (Highway, one copy per target: included again for each
// target, as lane_dialect.h): LaneLaw compiles shaders/kernels/contact_law.h, the text the GLSL
// and scalar kernels compile, in the lanes' dialect; lane_wall says which walls the lanes measure
// with it, lane_wall_contact measures them (contact_lanes.cpp for the contacts, walk_lanes.cpp for
// the neighbour walk's wall tests).
#if defined(REPOSE_LANE_LAW_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef REPOSE_LANE_LAW_H_
#undef REPOSE_LANE_LAW_H_
#else
#define REPOSE_LANE_LAW_H_
#endif

#include "lane_dialect.h"

HWY_BEFORE_NAMESPACE();
namespace repose::gpu::HWY_NAMESPACE {

// The contact law in lanes: the shared text, its types and functions as members.
struct LaneLaw {
  // Each lane's pair parameters: every row of REPOSE_PAIR_PARAMS (repose_shared.h), by name.
  struct PairParams {
#define REPOSE_LANE_PARAM(name, unit, source) real name;
    REPOSE_PAIR_PARAMS(REPOSE_LANE_PARAM)
#undef REPOSE_LANE_PARAM
  };
#include "kernels/vector3.h"
#include "kernels/contact_law.h"
};

// How the lanes take wall w for a sphere centred at x: as a plane (a plane, or a rectangle whose
// face x lies over), as a cylinder, or not (the other walls: measured one by one).
enum class LaneWall { None, Plane, Cylinder };
HWY_INLINE LaneWall lane_wall(Kernels& k, const WallState& w, vec3 x) {
  if (w.info.x == kWallPlane || (w.info.x == kWallRectangle && k.over_rectangle_face(w, x))) return LaneWall::Plane;
  return w.info.x == kWallCylinder ? LaneWall::Cylinder : LaneWall::None;
}

// A sphere per lane (x, r) against a wall per lane that lane_wall takes: plane_contact, or
// cylinder_contact in the lanes of `cylinder` (`any_cylinder`: whether it has any). A cylinder's
// rows are a plane's: base and axis in point and normal, radius normal.w, height `height`.
HWY_INLINE cond lane_wall_contact(LaneLaw& law, real3 x, real r, real3 point, const V4& normal, real height,
                                  M cylinder, bool any_cylinder, float margin, real3& n, real& overlap) {
  n = normal.xyz();
  const cond near = law.plane_contact(x, r, point, n, margin, overlap);
  if (!any_cylinder) return near;
  real3 n_c;
  real overlap_c;
  const cond near_c = law.cylinder_contact(x, r, point, normal.xyz(), real(normal.w), height, margin, n_c, overlap_c);
  const cond c{cylinder};
  n = pick(c, n_c, n);
  overlap = pick(c, overlap_c, overlap);
  return (c && near_c) || (!c && near);
}

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif
