// Analytic walls (planes, inner cylinder surfaces) seen from one sphere. A box is six planes.
#ifndef REPOSE_KERNELS_WALLS_H
#define REPOSE_KERNELS_WALLS_H

// True when the sphere (x, r) is within `margin` of touching the wall. `n` is the unit normal
// from the wall towards the sphere centre, `overlap` > 0 when touching.
FN bool wall_contact(WallState ws, vec3 x, float r, float margin, OUT(vec3) n, OUT(float) overlap) {
  n = vec3(0.0f, 0.0f, 1.0f);
  overlap = -1.0f;
  precise vec3 rel = x - xyz(ws.p0);
  vec3 dir = xyz(ws.p1);
  if (ws.info.x == kWallPlane) {
    precise float dist = dot3(rel, dir);
    n = dir;
    overlap = r - dist;
    return dist < r + margin && dist > -r;
  }
  // Cylinder: inner surface of radius p1.w, from the base along the axis for vel.w.
  precise float s = dot3(rel, dir);
  if (s < -margin || s > ws.vel.w + margin) return false;
  precise vec3 q = rel - scale3(dir, s);
  precise float d = length3(q);
  if (!(d > 0.0f)) return false;
  precise float inv_d = -1.0f / d;
  n = scale3(q, inv_d);
  overlap = r + d - ws.p1.w;
  if (margin == 0.0f && (s < 0.0f || s > ws.vel.w)) return false;
  return overlap > -margin;
}

// Velocity of the wall's surface at point p (prescribed translation and rotation).
FN vec3 wall_point_velocity(WallState ws, vec3 p) {
  precise vec3 arm = p - xyz(ws.centre);
  precise vec3 v = xyz(ws.vel) + cross3(xyz(ws.omega), arm);
  return v;
}

#endif
