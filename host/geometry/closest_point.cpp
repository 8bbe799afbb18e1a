#include "geometry/closest_point.h"

#include <glm/geometric.hpp>

namespace repose {
namespace {

// Closest point on segment [a, b] to p; t = 0 at a, 1 at b.
glm::dvec3 closest_on_segment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, double& t) {
  const glm::dvec3 ab = b - a;
  const double length2 = glm::dot(ab, ab);
  t = length2 > 0 ? glm::dot(p - a, ab) / length2 : 0.0;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return a + t * ab;
}

ClosestPointOnTriangle closest_on_edges(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                        const glm::dvec3& c) {
  const glm::dvec3* corners[3] = {&a, &b, &c};
  ClosestPointOnTriangle best;
  double best_distance2 = -1;
  for (int edge = 0; edge < 3; ++edge) {
    double t;
    glm::dvec3 q = closest_on_segment(p, *corners[edge], *corners[(edge + 1) % 3], t);
    double d2 = glm::dot(p - q, p - q);
    if (best_distance2 < 0 || d2 < best_distance2) {
      best_distance2 = d2;
      best.point = q;
      if (t == 0) {
        best.feature = TriangleFeature::Vertex;
        best.index = edge;
      } else if (t == 1) {
        best.feature = TriangleFeature::Vertex;
        best.index = (edge + 1) % 3;
      } else {
        best.feature = TriangleFeature::Edge;
        best.index = edge;
      }
    }
  }
  return best;
}

}  // namespace

ClosestPointOnTriangle closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a,
                                                 const glm::dvec3& b, const glm::dvec3& c) {
  // The "> 0" guards on the divisions only fail for zero-length edges; such triangles end at
  // the zero-denominator fallback below.
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, TriangleFeature::Vertex, 0};

  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, TriangleFeature::Vertex, 1};

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, TriangleFeature::Edge, 0};
  }

  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, TriangleFeature::Vertex, 2};

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, TriangleFeature::Edge, 2};
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), TriangleFeature::Edge, 1};
  }

  const double denominator = va + vb + vc;
  if (!(denominator > 0)) return closest_on_edges(p, a, b, c);  // zero-area triangle
  const double v = vb / denominator, w = vc / denominator;
  return {a + v * ab + w * ac, TriangleFeature::Face, 0};
}

}  // namespace repose
