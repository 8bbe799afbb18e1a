// Walls seen from one sphere: planes, inner cylinder surfaces, rectangles (bounded plates) and
// triangles of STL meshes. A box is six planes; a mesh is one triangle row per facet.
#ifndef REPOSE_KERNELS_WALLS_H
#define REPOSE_KERNELS_WALLS_H

// Wall w's state at this step. The first n_walls rows of B_walls hold every wall as it stands
// (uploaded once: a wall without motion never changes); a wall with a prescribed motion
// (topo.w = 1 + its place among them) has a row per step of the batch after those, uploaded with
// each batch, so a 20,000-triangle mesh is not sent again for every step a gate slides.
uint wall_row(uint w) {
  uint moving = B_walls[w].topo.w;
  if (moving == 0u) return w;
  return PC.n_walls + PC.wall_slot * PC.n_moving_walls + (moving - 1u);
}
WallState wall_at(uint w) { return B_walls[wall_row(w)]; }

// Closest point to p on triangle (a, b, c) and its feature (kFeatureFace/Edge/Vertex): Ericson,
// Real-Time Collision Detection 5.1.5, the float twin of host/geometry/closest_point.cpp.
vec3 closest_on_triangle(vec3 p, vec3 a, vec3 b, vec3 c, OUT(uint) feature) {
  precise vec3 ab = b - a;
  precise vec3 ac = c - a;
  precise vec3 ap = p - a;
  precise float d1 = dot3(ab, ap);
  precise float d2 = dot3(ac, ap);
  feature = kFeatureVertex;
  if (d1 <= 0.0f && d2 <= 0.0f) return a;
  precise vec3 bp = p - b;
  precise float d3 = dot3(ab, bp);
  precise float d4 = dot3(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  precise float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f && d1 - d3 > 0.0f) {
    feature = kFeatureEdge;
    precise float v = div_rn(d1, d1 - d3);
    precise vec3 q = a + scale3(ab, v);
    return q;
  }
  precise vec3 cp = p - c;
  precise float d5 = dot3(ab, cp);
  precise float d6 = dot3(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  feature = kFeatureEdge;
  precise float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f && d2 - d6 > 0.0f) {
    precise float w = div_rn(d2, d2 - d6);
    precise vec3 q = a + scale3(ac, w);
    return q;
  }
  precise float va = d3 * d6 - d5 * d4;
  precise float e43 = d4 - d3;
  precise float e56 = d5 - d6;
  precise float e_sum = e43 + e56;
  if (va <= 0.0f && e43 >= 0.0f && e56 >= 0.0f && e_sum > 0.0f) {
    precise float w = div_rn(e43, e_sum);
    precise vec3 q = b + scale3(c - b, w);
    return q;
  }
  feature = kFeatureFace;
  precise float denominator = va + vb + vc;
  precise float v = div_rn(vb, denominator);
  precise float w = div_rn(vc, denominator);
  precise vec3 q = a + scale3(ab, v) + scale3(ac, w);
  return q;
}

// Whether x lies over rectangle ws's face (within its half extents along u and v): there the
// rectangle is the plane through its centre (plane_contact), as the contact lanes take it.
bool over_rectangle_face(WallState ws, vec3 x) {
  precise vec3 rel = x - xyz(ws.p0);
  precise float su = dot3(rel, xyz(ws.p2));
  precise float sv = dot3(rel, xyz(ws.p3));
  return abs(su) <= ws.p2.w && abs(sv) <= ws.p3.w;
}

// Contact with a point q of a wall's edge or corner: normal from q to the centre.
bool point_contact(vec3 x, vec3 q, float r, float margin, OUT(vec3) n, OUT(float) overlap) {
  precise vec3 d = x - q;
  precise float dist = length3(d);
  if (!(dist > 0.0f)) return false;
  n = vec3(div_rn(d.x, dist), div_rn(d.y, dist), div_rn(d.z, dist));
  overlap = r - dist;
  return overlap > -margin;
}

// True when the sphere (x, r) is within `margin` of touching the wall. `n` is the unit normal
// from the wall towards the sphere centre, `overlap` > 0 when touching, `feature` which part of a
// rectangle or triangle is closest (kFeatureFace for planes and cylinders).
bool wall_contact_feature(WallState ws, vec3 x, float r, float margin, OUT(vec3) n, OUT(float) overlap,
                          OUT(uint) feature) {
  n = vec3(0.0f, 0.0f, 1.0f);
  overlap = -1.0f;
  feature = kFeatureFace;
  precise vec3 rel = x - xyz(ws.p0);
  vec3 dir = xyz(ws.p1);
  uint type = ws.info.x;
  if (type == kWallPlane) {
    n = dir;
    return plane_contact(x, r, xyz(ws.p0), dir, margin, overlap);
  }
  if (wall_kind_possible(kWallRectangle) && type == kWallRectangle) {
    // One-sided like a plane inside the rectangle; beyond it the nearest boundary point (edge or
    // corner), seen from the front side only, so a sphere rolls off the plate's edge.
    if (over_rectangle_face(ws, x)) {
      n = dir;
      return plane_contact(x, r, xyz(ws.p0), dir, margin, overlap);
    }
    precise float h = dot3(rel, dir);
    precise float su = dot3(rel, xyz(ws.p2));
    precise float sv = dot3(rel, xyz(ws.p3));
    // A candidate (margin > 0) just beyond the edge but behind the plane can move over the face
    // before the next rebuild and touch it there: keep it, or results would depend on the skin.
    bool near_face = abs(su) <= ws.p2.w + margin && abs(sv) <= ws.p3.w + margin;
    if (margin > 0.0f && near_face && h < r + margin && h > -r - margin) return true;
    // Edges touch from the front only, but a candidate behind the plane may come round the edge.
    if (!(h > 0.0f) && !(margin > 0.0f)) return false;
    feature = (abs(su) > ws.p2.w && abs(sv) > ws.p3.w) ? kFeatureVertex : kFeatureEdge;
    precise float cu = min(max(su, -ws.p2.w), ws.p2.w);
    precise float cv = min(max(sv, -ws.p3.w), ws.p3.w);
    precise vec3 q = xyz(ws.p0) + scale3(xyz(ws.p2), cu) + scale3(xyz(ws.p3), cv);
    return point_contact(x, q, r, margin, n, overlap);
  }
  if (wall_kind_possible(kWallTriangle) && type == kWallTriangle) {
    // Two-sided (STL windings are often inconsistent): the face pushes to the side of the centre.
    precise vec3 q = closest_on_triangle(x, xyz(ws.p0), xyz(ws.p1), xyz(ws.p2), feature);
    if (feature != kFeatureFace) return point_contact(x, q, r, margin, n, overlap);
    vec3 nrm = xyz(ws.p3);
    precise float h = dot3(rel, nrm);
    precise float ah = abs(h);
    n = h >= 0.0f ? nrm : -nrm;
    overlap = r - ah;
    return ah < r + margin;
  }
  if (!wall_kind_possible(kWallCylinder)) return false;
  // Cylinder: inner surface of radius p1.w, from the base along the axis for vel.w. It holds
  // the spheres whose centres are inside; one outside (d >= R) never touches the inner surface.
  return cylinder_contact(x, r, xyz(ws.p0), dir, ws.p1.w, ws.vel.w, margin, n, overlap);
}

bool wall_contact(WallState ws, vec3 x, float r, float margin, OUT(vec3) n, OUT(float) overlap) {
  uint feature = kFeatureFace;
  return wall_contact_feature(ws, x, r, margin, n, overlap, feature);
}

// The neighbour walk's test of wall w for sphere i at pi: within the skin of touching it. The cpu
// backend's walk answers it for a run of spheres at once where it can (kernels_ref/walk_lanes.cpp).
bool wall_within_skin(uint i, vec4 pi, uint w) {
  vec3 n;
  float overlap;
  return wall_contact(wall_at(w), xyz(pi), pi.w, PC.skin, n, overlap);
}

bool shares_vertex(uvec4 a, uvec4 b) {
  return a.x == b.x || a.x == b.y || a.x == b.z || a.y == b.x || a.y == b.y || a.y == b.z ||
         a.z == b.x || a.z == b.y || a.z == b.z;
}

// One contact per touching point of a mesh (docs/case-format.md, "mesh walls"). Neighbouring
// triangles (sharing a vertex) of the same mesh that both touch sphere i can describe the same
// contact: over a shared edge or vertex, or one triangle's edge next to its neighbour's face.
// Triangle w's contact is shadowed by a touching neighbour w2 of i's row when
//   - the two are coplanar (normals within kCoplanarCos) or w's contact is an edge or vertex, and
//   - w2 overlaps more, or as much with a lower index.
// So a flat patch keeps exactly its deepest triangle (the union's closest point), and a fold
// keeps both face contacts but no edge or corner contact next to a neighbour's face.
bool mesh_contact_shadowed(uint i, uint c, WallState ws, uint w, vec3 x, float r, float overlap,
                           uint feature) {
  uint limit = B_control[kCtlContacts];
  uint end = min(B_row_start[i + 1u], limit);
  for (uint c2 = min(B_row_start[i], limit); c2 < end; ++c2) {
    uint p2 = B_partner[c2];
    if (c2 == c || p2 < PC.n_particles) continue;
    uint w2 = p2 - PC.n_particles;
    WallState other = wall_at(w2);
    if (other.info.x != kWallTriangle || other.info.z != ws.info.z) continue;
    if (!shares_vertex(ws.topo, other.topo)) continue;
    vec3 n2;
    float overlap2;
    uint feature2 = kFeatureFace;
    if (!wall_contact_feature(other, x, r, 0.0f, n2, overlap2, feature2) || !(overlap2 > 0.0f)) continue;
    precise float align = abs(dot3(xyz(ws.p3), xyz(other.p3)));
    if (align < kCoplanarCos && feature == kFeatureFace) continue;
    if (overlap2 > overlap || (overlap2 == overlap && w2 < w)) return true;
  }
  return false;
}

#endif
