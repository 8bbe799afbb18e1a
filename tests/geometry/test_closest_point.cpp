// Closest point on a triangle: each Voronoi region, and agreement with brute-force sampling.
#include <catch2/catch.hpp>

#include <cstdint>
#include <glm/geometric.hpp>

#include "geometry/closest_point.h"

using namespace repose;

namespace {

const glm::dvec3 A(0, 0, 0), B(2, 0, 0), C(0, 2, 0);

void check_region(glm::dvec3 p, glm::dvec3 expected, TriangleFeature feature, int index) {
  const ClosestPointOnTriangle r = closest_point_on_triangle(p, A, B, C);
  INFO("p = " << p.x << " " << p.y << " " << p.z);
  CHECK(glm::length(r.point - expected) < 1e-15);
  CHECK(r.feature == feature);
  CHECK(r.index == index);
}

// Deterministic uniform numbers in [0, 1) (SplitMix64).
double uniform(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

}  // namespace

TEST_CASE("closest point: face, three edges, three vertices", "[closest]") {
  check_region({0.5, 0.5, 3}, {0.5, 0.5, 0}, TriangleFeature::Face, 0);
  check_region({1, -1, 1}, {1, 0, 0}, TriangleFeature::Edge, 0);    // ab
  check_region({2, 2, -1}, {1, 1, 0}, TriangleFeature::Edge, 1);    // bc
  check_region({-1, 1, 0.5}, {0, 1, 0}, TriangleFeature::Edge, 2);  // ca
  check_region({-1, -1, 0}, A, TriangleFeature::Vertex, 0);
  check_region({3, -0.5, 2}, B, TriangleFeature::Vertex, 1);
  check_region({-0.5, 3, -2}, C, TriangleFeature::Vertex, 2);
}

TEST_CASE("closest point agrees with brute-force sampling of the triangle", "[closest]") {
  uint64_t state = 12345;
  for (int trial = 0; trial < 200; ++trial) {
    glm::dvec3 a, b, c, p;
    for (glm::dvec3* v : {&a, &b, &c, &p})
      *v = glm::dvec3(uniform(state), uniform(state), uniform(state)) * 2.0 - 1.0;
    const ClosestPointOnTriangle r = closest_point_on_triangle(p, a, b, c);
    const double d = glm::length(p - r.point);
    double brute = HUGE_VAL;
    const int n = 200;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const glm::dvec3 q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
        brute = std::min(brute, glm::length(p - q));
      }
    // The exact distance is never above the sampled one, and the sampling spacing bounds the gap.
    CHECK(d <= brute + 1e-12);
    CHECK(d >= brute - 2.0 * glm::length(glm::dvec3(4.0)) / n);
    // The point lies in the triangle's plane.
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    CHECK(std::abs(glm::dot(r.point - a, normal)) < 1e-12 * glm::length(normal));
  }
}

TEST_CASE("closest point on a zero-area triangle falls back to its edges", "[closest]") {
  const ClosestPointOnTriangle r = closest_point_on_triangle({1, 1, 0}, {0, 0, 0}, {2, 0, 0}, {4, 0, 0});
  CHECK(glm::length(r.point - glm::dvec3(1, 0, 0)) < 1e-15);
  CHECK(r.feature == TriangleFeature::Edge);
  const ClosestPointOnTriangle same = closest_point_on_triangle({1, 1, 1}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0});
  CHECK(same.point == glm::dvec3(0.0));
  CHECK(same.feature == TriangleFeature::Vertex);
}
