// Closest point on a triangle to a point, with the feature it lies on. Written in plain double
// arithmetic (dot products and divisions, no library calls beyond glm's dot) so that the engine
// can port it line by line to GLSL for face, edge and vertex contacts with mesh walls.
#pragma once
#include <glm/vec3.hpp>

namespace repose {

enum class TriangleFeature { Face, Edge, Vertex };

struct ClosestPointOnTriangle {
  glm::dvec3 point{0.0};
  TriangleFeature feature = TriangleFeature::Face;
  // Edge: 0 = ab, 1 = bc, 2 = ca. Vertex: 0 = a, 1 = b, 2 = c. Face: 0.
  int index = 0;
};

// Ericson, Real-Time Collision Detection, 5.1.5: Voronoi regions of the vertices, then of the
// edges, else the face (barycentric projection). A degenerate triangle (zero area) falls back to
// the closest of its three edges.
ClosestPointOnTriangle closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a,
                                                 const glm::dvec3& b, const glm::dvec3& c);

}  // namespace repose
