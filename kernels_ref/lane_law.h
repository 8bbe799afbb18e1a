// The contact law's text in SIMD lanes (Highway, one copy per target: included again for each
// target, as lane_dialect.h): LaneLaw compiles shaders/kernels/contact_law.h, the text the GLSL
// and scalar kernels compile, in the lanes' dialect; lane_wall says which walls the lanes measure
// with it (contact_lanes.cpp for the contacts, walk_lanes.cpp for the neighbour walk's wall tests).
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

}  // namespace repose::gpu::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif
