// The wall grid (host/engine/wall_grid.h, kernels/neighbour.h walk_walls): every wall a sphere
// can take as a neighbour candidate is listed in its cell, so runs with the grid on and off give
// the same contact list and bytes on both backends; wall forces are summed per named wall.
#include <catch2/catch.hpp>
#include <glm/geometric.hpp>
#include <random>

#include "engine/step_program.h"
#include "engine/wall_grid.h"
#include "engine_test_support.h"
#include "geometry/closest_point.h"
#include "geometry/stl_shapes.h"
#include "state_file_support.h"
#include "twin_kernels.h"

using namespace repose;
using namespace repose::test;

namespace {

constexpr double kRadius = 0.004;  // the largest sphere of the rigs below

// A [[wall]] mesh from triangles `mesh` (moved by `offset`), named `name`.
WallSpec mesh_wall(const TriangleMesh& mesh, Vec3d offset, int material, const std::string& name) {
  auto m = std::make_shared<WallMesh>();
  for (const glm::dvec3& v : mesh.vertices) m->vertices.push_back({v.x + offset[0], v.y + offset[1], v.z + offset[2]});
  m->triangles = mesh.triangles;
  WallSpec w;
  w.type = WallSpec::Type::Mesh;
  w.mesh = m;
  w.material = material;
  w.name = name;
  return w;
}

// A cube's corner: three unit squares (two triangles each) meeting at the origin, scaled.
TriangleMesh cube_corner(double side) {
  TriangleMesh t;
  t.vertices = {{0, 0, 0}, {side, 0, 0}, {0, side, 0}, {0, 0, side}, {side, side, 0}, {side, 0, side}, {0, side, side}};
  t.triangles = {{0, 1, 4}, {0, 4, 2}, {0, 1, 5}, {0, 5, 3}, {0, 2, 6}, {0, 6, 3}};
  return t;
}

// Spheres of 3-4 mm radius thrown into a hopper (`sides` sides, its 10 mm outlet at z = 0.05,
// which few pass), over a cube's corner and a floor plane, with a two-triangle paddle sweeping
// under it when `paddle`.
CaseSpec hopper_rig(int sides, bool paddle, int spheres = 240) {
  CaseBuilder b;
  b.spec = seeded_cloud(1, 0, 2.0, 0.0);  // its grain and steel, gravity and time step; not its sphere and walls
  b.spec.spheres.clear();
  b.spec.walls.clear();
  const int grain = 0, steel = 1;
  b.spec.walls.push_back(mesh_wall(hopper_mesh(0.05, 0.005, 0.04, sides), {0, 0, 0.05}, steel, "hopper"));
  b.spec.walls.push_back(mesh_wall(cube_corner(0.03), {-0.015, -0.015, 0.0}, steel, "corner"));
  if (paddle) {
    TriangleMesh p;
    p.vertices = {{0.02, -0.02, 0.0}, {0.02, 0.02, 0.0}, {0.02, 0.02, 0.03}, {0.02, -0.02, 0.03}};
    p.triangles = {{0, 1, 2}, {0, 2, 3}};
    b.spec.walls.push_back(mesh_wall(p, {0, 0, 0}, steel, "paddle"));
    b.spec.walls.back().motion.velocity = {-0.2, 0, 0};
    b.spec.walls.back().motion.start_time = 0.01;
  }
  b.plane({0, 0, -0.005}, {0, 0, 1}, steel);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const double gap = 2.2 * kRadius;  // a jittered lattice in the cone, the spheres apart
  for (int layer = 0; int(b.spec.spheres.size()) < spheres; ++layer) {
    double z = 0.075 + gap * layer, cone = 0.005 + 0.045 * (std::min(z, 0.09) - 0.05) / 0.04;
    for (double x = -cone; x <= cone; x += gap)
      for (double y = -cone; y <= cone; y += gap)
        if (x * x + y * y < 0.5 * cone * cone && int(b.spec.spheres.size()) < spheres)
          b.sphere({x + 0.05 * gap * u(rng), y + 0.05 * gap * u(rng), z}, kRadius * (0.8 + 0.2 * std::abs(u(rng))), grain,
                   {0.3 * x / cone, 0.3 * y / cone, -0.5});
  }
  return b.spec;
}

// Walls the grid lists for a sphere centre in cell `c`: the walls every sphere tests and those
// of c's cell in its bucket (the layout walk_walls reads).
std::vector<uint32_t> listed(const Model& m, gpu::ivec3 c, gpu::Kernels& k) {
  const std::vector<uint32_t>& g = m.wall_grid;
  uint32_t t = m.wall_table_size;
  std::vector<uint32_t> out(g.begin() + g[t], g.begin() + g[t + 1]);
  uint32_t h = k.cell_hash(c.x, c.y, c.z, t);
  for (uint32_t s = g[h]; s < g[h + 1]; s += 4 + g[s + 3])
    if (int(g[s]) == c.x && int(g[s + 1]) == c.y && int(g[s + 2]) == c.z)
      out.insert(out.end(), g.begin() + s + 4, g.begin() + s + 4 + g[s + 3]);
  return out;
}

struct ListingCheck {
  long candidates = 0;  // (sphere, wall) pairs wall_contact takes as candidates
  long near_reach = 0;  // of those, with the wall farther than radius + skin/2 from the centre
  long missing = 0;     // of those, the wall not listed in the sphere's cell
};

// Sphere centres around the triangles of m (inside their reach and just beyond it, some on cell
// boundaries), each with the largest radius: every wall the kernels' wall_contact takes as a
// candidate must be listed in the centre's cell.
ListingCheck check_listing(const Model& m, int samples) {
  gpu::Kernels k;
  Layout l = model_layout(m, {}, 1, 64);
  k.PC = base_push(m, l, {});
  std::vector<gpu::WallState> rows;
  for (size_t w = 0; w < m.walls.size(); ++w) rows.push_back(m.wall_state(w, 0.0));
  k.B_walls = rows.data();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  double h = 1.0 / double(k.PC.inv_cell), reach = kRadius + m.skin;
  std::vector<glm::dvec4> around;  // each triangle's centroid and a radius holding it
  for (const gpu::WallState& t : rows) {
    glm::dvec3 a(k.xyz(t.p0)), b(k.xyz(t.p1)), c(k.xyz(t.p2)), mid = (a + b + c) / 3.0;
    around.push_back({mid, std::max(glm::length(a - mid), std::max(glm::length(b - mid), glm::length(c - mid)))});
  }
  ListingCheck out;
  for (int n = 0; n < samples; ++n) {
    const gpu::WallState& t = rows[size_t(u(rng) * double(rows.size())) % rows.size()];
    if (t.info.x != gpu::kWallTriangle) continue;
    glm::dvec3 a(k.xyz(t.p0)), b(k.xyz(t.p1)), c(k.xyz(t.p2)), nrm(k.xyz(t.p3));
    double s1 = 1.3 * u(rng) - 0.15, s2 = (1.3 * u(rng) - 0.15) * (1 - s1);
    glm::dvec3 x = a + (b - a) * s1 + (c - a) * s2 + nrm * ((2 * u(rng) - 1) * 1.05 * reach);
    if (n % 3 == 0) x[n % 9 / 3] = std::round(x[n % 9 / 3] / h) * h;  // on a cell boundary
    gpu::vec3 xf(x);
    std::vector<uint32_t> here = listed(m, k.cell_of_position(xf, k.PC.inv_cell), k);
    for (uint32_t w = 0; w < rows.size(); ++w) {
      bool far = rows[w].info.x == gpu::kWallTriangle &&
                 glm::length(glm::dvec3(xf) - glm::dvec3(around[w])) > around[w].w + 2 * reach;
      if (far) continue;  // wall_contact cannot take it
      gpu::vec3 normal;
      float overlap;
      if (!k.wall_contact(rows[w], xf, float(kRadius), k.PC.skin, normal, overlap)) continue;
      ++out.candidates;
      glm::dvec3 p(xf), q = closest_point_on_triangle(p, glm::dvec3(k.xyz(rows[w].p0)), glm::dvec3(k.xyz(rows[w].p1)),
                                                      glm::dvec3(k.xyz(rows[w].p2))).point;
      out.near_reach += rows[w].info.x == gpu::kWallTriangle && glm::length(p - q) > kRadius + 0.5 * m.skin;
      out.missing += std::find(here.begin(), here.end(), w) == here.end();
    }
  }
  return out;
}

}  // namespace

TEST_CASE("wall grid: every wall a sphere can take as a candidate is listed in its cell", "[walls][grid]") {
  for (int sides : {24, 1000}) {  // facets of a few mm, and slivers 0.1-0.3 mm wide
    CaseSpec spec = hopper_rig(sides, false, 40);
    spec.neighbour.skin = 0.002;
    spec.neighbour.wall_grid = true;
    Model m = build_model(spec);
    REQUIRE(m.wall_table_size > 0);
    INFO(sides << " sides: " << describe_wall_grid(m));
    ListingCheck c = check_listing(m, 60000);
    CHECK(c.candidates > 20000);
    CHECK(c.near_reach > 2000);  // the reach's edge is sampled: a reach cut by the radius fails here
    CHECK(c.missing == 0);
  }
}

TEST_CASE("wall grid: on by default from a few still triangles, never for moving walls", "[walls][grid]") {
  CaseSpec spec = hopper_rig(24, true, 40);
  Model m = build_model(spec);
  CHECK(m.wall_table_size > 0);
  for (size_t w = 0; w < m.walls.size(); ++w)
    CHECK(wall_in_grid(m, w) == (m.walls[w].kind == gpu::kWallTriangle && m.walls[w].name != "paddle"));
  REQUIRE(m.moving_walls.size() == 2);
  CHECK(m.walls[m.moving_walls[0]].moving_row == 1);
  spec.neighbour.wall_grid = false;
  CHECK(build_model(spec).wall_grid.empty());
}

TEST_CASE("wall grid: the same contact list and bytes with it on and off, lavapipe and the CPU twin",
          "[walls][grid]") {
  for (bool moving : {false, true}) {
    INFO((moving ? "with a moving paddle" : "still walls"));
    CaseSpec off = hopper_rig(48, moving), on = off;
    off.neighbour.wall_grid = false;
    on.neighbour.wall_grid = true;
    auto reference = simulate(off, "cpu", 1, {}, 50);
    auto cpu = simulate(on, "cpu", 2, {}, 7);  // short batches: the paddle's rows at every slot
    auto gpu = simulate(on, "vulkan", 1, {}, 50);
    REQUIRE(reference->model().wall_grid.empty());
    REQUIRE(cpu->model().wall_table_size > 0);
    for (auto* s : {reference.get(), cpu.get(), gpu.get()}) s->advance(700);
    CHECK(reference->rebuilds() > 5);
    auto wall_contacts = [](const HostState& s) {
      return std::count_if(s.partner.begin(), s.partner.end(), [&](uint32_t p) { return p >= s.pos.size(); });
    };
    CHECK(wall_contacts(reference->state()) > 50);
    for (auto* s : {cpu.get(), gpu.get()}) {
      std::string which;
      bool same = same_state(reference->state(), s->state(), &which);
      INFO(s->backend().describe() << " differs in " << which);
      CHECK(same);
      CHECK(state_file_bytes(*s, "grid_on.state") == state_file_bytes(*reference, "grid_off.state"));
      auto fa = reference->wall_forces(), fb = s->wall_forces();
      REQUIRE(fa.size() == fb.size());
      for (size_t w = 0; w < fa.size(); ++w) CHECK((fa[w].fx == fb[w].fx && fa[w].fy == fb[w].fy && fa[w].fz == fb[w].fz));
    }
  }
}

namespace {

// The force on each named wall as wall_reduce sums it: 256 partial sums, partial t over the
// particles of global id t, t + 256, ... in order and each row's contacts with the wall's rows in
// row order, then a fixed tree (shaders/wall_reduce.comp). `one_row`: only that wall row's contacts.
std::vector<gpu::vec3> reduced(Simulation& sim, int one_row = -1) {
  const HostState& s = sim.state();
  std::vector<gpu::vec4> f = sim.contact_forces();
  const Model& m = sim.model();
  uint32_t n = m.n_particles;
  std::vector<gpu::vec3> out;
  for (uint32_t g = 0; g < m.n_wall_groups; ++g) {
    std::vector<gpu::vec3> part(256, gpu::vec3(0.0f));
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t c = s.row_start[i]; c < s.row_start[i + 1]; ++c) {
        uint32_t p = s.partner[c];
        bool take = p >= n && (one_row < 0 ? m.walls[p - n].group == g : p - n == uint32_t(one_row));
        if (take) part[i % 256] = part[i % 256] - gpu::vec3(f[c].x, f[c].y, f[c].z);
      }
    for (uint32_t half = 128; half > 0; half /= 2)
      for (uint32_t t = 0; t < half; ++t) part[t] = part[t] + part[t + half];
    out.push_back(part[0]);
  }
  return out;
}

}  // namespace

TEST_CASE("wall forces: one sum per named wall in wall_reduce's order, on both backends", "[walls][grid]") {
  CaseSpec spec = hopper_rig(24, false);
  for (const std::string& backend : {"cpu", "vulkan"}) {
    INFO(backend);
    auto sim = simulate(spec, backend, 1, KernelVariant::parse("reorder=1"), 50);
    sim->advance(900);
    std::vector<WallForce> f = sim->wall_forces();
    std::vector<gpu::vec3> expected = reduced(*sim);
    REQUIRE(f.size() == 3);  // hopper, corner, the floor plane
    double mesh_total = 0;
    for (size_t g = 0; g < f.size(); ++g) {
      INFO(f[g].name);
      CHECK(f[g].fx == double(expected[g].x));
      CHECK(f[g].fy == double(expected[g].y));
      CHECK(f[g].fz == double(expected[g].z));
      if (g < 2) mesh_total += std::abs(f[g].fz);
    }
    CHECK(mesh_total > 0.0);  // spheres rest on the meshes
    // Summed per triangle first (as before the sums per named wall), a mesh's force differs only
    // by float rounding: within 1e-5 of the sum of the triangles' magnitudes.
    double by_rows = 0, magnitudes = 0;
    const Model& m = sim->model();
    for (size_t w = 0; w < m.walls.size(); ++w) {
      if (m.walls[w].group != 0) continue;
      gpu::vec3 one = reduced(*sim, int(w))[0];
      by_rows += double(one.z);
      magnitudes += std::abs(double(one.z));
    }
    CHECK(f[0].fz == Approx(by_rows).margin(1e-5 * magnitudes));
  }
}

// Clumps with the body-level broad phase, whose parts test only the first 32 walls their spheres
// may meet (part_walls), poured into a hopper of 48 triangles (walls 2 to 49): the grid and the
// parts' masks together keep the list, on both backends.
TEST_CASE("wall grid: clumps with walls per part give the same bytes with it on and off", "[walls][grid]") {
  CaseSpec pile = clump_pile();
  pile.walls.push_back(mesh_wall(hopper_mesh(0.15, 0.11, 0.05, 24), {0.06, 0.06, -0.012}, 1, "hopper"));
  pile.neighbour.body_broad_phase = true;
  for (const char* backend : {"cpu", "vulkan"}) {
    INFO(backend);
    CaseSpec off = pile;
    off.neighbour.wall_grid = false;
    auto a = simulate(pile, backend, 2, {}, 25);
    auto b = simulate(off, backend, 2, {}, 25);
    REQUIRE(a->model().wall_table_size > 0);
    REQUIRE((a->model().flags & gpu::kFlagBodyBroadPhase) != 0);
    a->advance(1500);
    b->advance(1500);
    const HostState& s = a->state();
    auto on_hopper = std::count_if(s.partner.begin(), s.partner.end(), [&](uint32_t p) { return p >= s.pos.size() + 2; });
    CHECK(on_hopper > 5);
    std::string which;
    bool same = same_state(s, b->state(), &which);
    INFO("first difference in " << which);
    CHECK(same);
  }
}
