// Storage order (host/engine/particle_order.h): particles stored in any slots, reordered between
// batches, give the bytes of the case's order: the state, the state file, contact forces and
// wall forces, on both backends and any thread count, for spheres with walls and for clumps; a
// reordered run's state file restarts to the bytes of a run that never stopped.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <unistd.h>

#include "engine/particle_order.h"
#include "util/parallel_each.h"
#include "engine_test_support.h"
#include "state_file_support.h"
#include "io/state_file.h"

using namespace repose;
using namespace repose::test;

namespace {

ParticleOrder scrambled(uint32_t n, uint64_t seed) {
  std::vector<uint32_t> ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  std::shuffle(ids.begin(), ids.end(), std::mt19937_64(seed));
  return ParticleOrder::from_ids(std::move(ids));
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("repose_test_" + std::to_string(::getpid()) + "_" + name)).string();
}

bool same_wall_forces(Simulation& a, Simulation& b) {
  auto fa = a.wall_forces(), fb = b.wall_forces();
  if (fa.size() != fb.size()) return false;
  for (size_t w = 0; w < fa.size(); ++w)
    if (fa[w].fx != fb[w].fx || fa[w].fy != fb[w].fy || fa[w].fz != fb[w].fz) return false;
  return true;
}

// `steps` steps of `spec` in the case's order (cpu, 1 thread) and, on `backend` with `threads`,
// stored in a scrambled order from the start, scrambled again halfway, and in cell order renewed
// after every rebuild (reorder=1): every output must be the same to the byte.
void check_orders(const CaseSpec& spec, uint64_t steps, const std::string& backend, unsigned threads) {
  KernelVariant keep = KernelVariant::parse("reorder=0");
  auto reference = simulate(spec, "cpu", 1, keep, 50);
  reference->advance(steps);
  REQUIRE(reference->contacts() > 50);
  REQUIRE(reference->particle_order().is_identity());
  uint32_t n = reference->model().n_particles;

  auto shuffled = simulate(spec, backend, threads, keep, 50);
  shuffled->store_in_order(scrambled(n, 1));
  shuffled->advance(steps / 2);
  shuffled->store_in_order(scrambled(n, 2));
  shuffled->advance(steps - steps / 2);
  auto cells = simulate(spec, backend, threads, KernelVariant::parse("reorder=1"), 50);
  cells->advance(steps);
  CHECK_FALSE(cells->particle_order().is_identity());
  RunProfile profile = cells->take_profile();  // the reorders after the first, counted and timed
  CHECK(profile.reorders >= 1);
  CHECK(profile.reorders <= profile.rebuilds);
  CHECK(profile.reorder_seconds > 0);
  // Its parts (down, into the new slots, up) each took some time, and together no more than the whole.
  const RunProfile::ReorderParts& parts = profile.reorder_parts;
  CHECK(parts.download > 0);
  CHECK(parts.order > 0);
  CHECK(parts.upload > 0);
  CHECK(parts.download + parts.order + parts.upload <= profile.reorder_seconds);
  CHECK(format_kernel_times(profile).find("(the state down ") != std::string::npos);

  std::string reference_file = state_file_bytes(*reference, "order_reference.state");
  for (Simulation* sim : {shuffled.get(), cells.get()}) {
    std::string which;
    bool same = same_state(reference->state(), sim->state(), &which);
    INFO(backend << ", " << threads << " threads, " << sim->variant().name() << ": first difference in " << which);
    CHECK(same);
    CHECK(state_file_bytes(*sim, "order_other.state") == reference_file);
    CHECK(same_bytes(reference->contact_forces(), sim->contact_forces()));
    CHECK(same_wall_forces(*reference, *sim));
  }
}

}  // namespace

TEST_CASE("particle order: spheres with walls give the same bytes in any storage order", "[engine][order]") {
  CaseSpec spec = seeded_cloud(300, 11, 2.3, 0.2);
  check_orders(spec, 400, "cpu", 1);
  check_orders(spec, 400, "cpu", 2);
  check_orders(spec, 400, "vulkan", 1);
}

TEST_CASE("particle order: clumps and spheres give the same bytes in any storage order", "[engine][order]") {
  CaseSpec spec = clump_pile();
  spec.contact.rolling = RollingModel::ElasticPlastic;
  check_orders(spec, 1000, "cpu", 2);
  check_orders(spec, 1000, "vulkan", 1);
}

TEST_CASE("particle order: a scrambled run's state file restarts to the bytes of an unbroken run", "[engine][order]") {
  CaseSpec spec = seeded_cloud(200, 5, 2.3, 0.2);
  KernelVariant keep = KernelVariant::parse("reorder=0");
  auto whole = simulate(spec, "cpu", 1, keep);
  whole->advance(300);
  auto first = simulate(spec, "cpu", 1, keep);
  first->store_in_order(scrambled(first->model().n_particles, 3));
  first->advance(120);
  std::string path = temp_path("order_restart.state");
  write_state_file(path, first->state(), first->step(), first->time());
  StateFileInfo info;
  HostState state = read_state_file(path, info);
  std::remove(path.c_str());
  auto second = simulate(spec, "cpu", 2);  // cell order by default
  second->restore(state, info.step);
  second->advance(180);
  std::string which;
  bool same = same_state(whole->state(), second->state(), &which);
  INFO("first difference in " << which);
  CHECK(same);
  CHECK(state_file_bytes(*whole, "order_whole.state") == state_file_bytes(*second, "order_second.state"));
}

TEST_CASE("particle order: a run read after every batch and one read only at its end give the same bytes",
          "[engine][order]") {
  // The state is turned to global ids when it is read (Simulation::state), so a batch nobody reads
  // stays in slots: uploads after an overflow and reorders then start from either form. The pile
  // overflows a list of 64 entries in the constructor and the grown list as it lands, inside
  // advance(); cell order is renewed after every rebuild. Both must give the bytes of the case's
  // order with an ample list.
  CaseSpec spec = wide_skin_pile();
  auto start = [&](const char* variant, uint32_t capacity) {
    KernelVariant v = KernelVariant::parse(variant);
    return std::make_unique<Simulation>(build_model(spec), make_backend("cpu", -1, 2, v.workgroup), v, 50, capacity);
  };
  auto reference = start("reorder=0", 20 * build_model(spec).n_particles), read = start("reorder=1", 64), unread = start("reorder=1", 64);
  size_t readings = 0;
  reference->advance(1100);
  read->advance(1100, [&](const Simulation& s) { readings += s.state().pos.size(); });
  unread->advance(1100);
  CHECK(readings == 22 * read->model().n_particles);
  CHECK(read->retries() > 0);
  CHECK(unread->retries() > 0);
  CHECK(reference->retries() == 0);
  CHECK_FALSE(unread->particle_order().is_identity());
  for (Simulation* sim : {read.get(), unread.get()}) {
    std::string which;
    bool same = same_state(reference->state(), sim->state(), &which);
    INFO((sim == read.get() ? "read" : "unread") << ": first difference in " << which);
    CHECK(same);
    CHECK(same_bytes(reference->contact_forces(), sim->contact_forces()));
  }
}

TEST_CASE("particle order: cell order puts neighbours in nearby slots, and refuses what is no permutation",
          "[engine][order]") {
  // A line of 8 cells along x, filled out of order: cell order sorts them along the line.
  std::vector<gpu::vec4> pos;
  for (int k : {5, 2, 7, 0, 3, 6, 1, 4}) pos.push_back(gpu::vec4(float(k) + 0.5f, 0.5f, 0.5f, 0.1f));
  ParticleOrder o = cell_order(pos, {}, 1.0);
  for (uint32_t s = 0; s < 8; ++s) CHECK(pos[o.id_of[s]].x == float(s) + 0.5f);
  for (uint32_t g = 0; g < 8; ++g) CHECK(o.id_of[o.slot_of[g]] == g);
  CHECK_THROWS(ParticleOrder::from_ids({0, 2, 2}));
  CHECK_THROWS(ParticleOrder::from_ids({0, 3, 1}));
}

TEST_CASE("particle order: cell order on several threads is the order of one, from global ids and from slots",
          "[engine][order]") {
  // 300,000 spheres at random in 40 x 40 x 40 cells (~4.7 a cell: many equal cells, ordered by
  // id): keyed in five blocks, sorted in up to four parts and merged.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> at(-2.0f, 2.0f);
  std::vector<gpu::vec4> pos(300000);
  for (auto& p : pos) p = gpu::vec4(at(rng), at(rng), at(rng), 0.01f);
  const ParticleOrder one = cell_order(pos, {}, 0.1, 1);
  std::vector<uint32_t> row_ids(pos.size());  // the same positions held in a scrambled order
  std::iota(row_ids.begin(), row_ids.end(), 0u);
  std::shuffle(row_ids.begin(), row_ids.end(), rng);
  std::vector<gpu::vec4> rows(pos.size());
  for (size_t r = 0; r < rows.size(); ++r) rows[r] = pos[row_ids[r]];
  for (unsigned threads : {2u, 3u, 4u, 8u}) {
    INFO(threads << " threads");
    CHECK((cell_order(pos, {}, 0.1, threads).id_of == one.id_of));  // a bool: no 300,000 ids printed
    CHECK((cell_order(rows, row_ids, {}, 0.1, threads).id_of == one.id_of));
  }
  // Neighbours in nearby slots: consecutive slots lie in the same or the next cell along x mostly.
  size_t near = 0;
  for (size_t s = 1; s < one.size(); ++s) near += std::abs(pos[one.id_of[s]].x - pos[one.id_of[s - 1]].x) < 0.2f;
  CHECK(near > one.size() * 9 / 10);
}

TEST_CASE("parallel_sort gives std::sort's order in parts merged on several threads", "[engine][order]") {
  std::mt19937 rng(5);
  std::vector<std::pair<uint64_t, uint32_t>> v(200003);
  for (size_t i = 0; i < v.size(); ++i) v[i] = {rng() % 1000, uint32_t(i)};  // equal keys, told apart by the second
  auto sorted = v;
  std::sort(sorted.begin(), sorted.end());
  for (unsigned threads : {1u, 2u, 3u, 4u, 8u})
    for (size_t least : {size_t(1), size_t(1000), size_t(1) << 16}) {
      INFO(threads << " threads, parts of at least " << least);
      auto w = v;
      parallel_sort(w, threads, least);
      CHECK((w == sorted));
    }
  std::vector<std::pair<uint64_t, uint32_t>> none;
  parallel_sort(none, 4, 1);
  CHECK(none.empty());
}

TEST_CASE("particle order: cell order moves a body's sub-spheres as one run, by global id", "[engine][order]") {
  // Three bodies of 3, 1 and 2 sub-spheres whose centres lie in cells 4, 0 and 2 along x; the
  // sub-spheres themselves spread over other cells, which must not split a body.
  std::vector<gpu::vec4> pos;
  for (float x : {4.5f, 0.5f, 7.5f, 0.5f, 2.5f, 1.5f}) pos.push_back(gpu::vec4(x, 0.5f, 0.5f, 0.1f));
  std::vector<gpu::Body> bodies(3);
  bodies[0].pos = gpu::vec4(4.5f, 0.5f, 0.5f, 1.0f);
  bodies[0].spheres = gpu::uvec4(0, 3, 0, 0);
  bodies[1].pos = gpu::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  bodies[1].spheres = gpu::uvec4(3, 1, 0, 0);
  bodies[2].pos = gpu::vec4(2.5f, 0.5f, 0.5f, 1.0f);
  bodies[2].spheres = gpu::uvec4(4, 2, 0, 0);
  ParticleOrder o = cell_order(pos, bodies, 1.0);
  CHECK(o.id_of == std::vector<uint32_t>{3, 4, 5, 0, 1, 2});
}

TEST_CASE("particle order: a large state turns between slots and global ids in blocks on several threads, "
          "to the bytes of one thread",
          "[engine][order]") {
  // 100,000 particles and ~300,000 contacts: rows of several 64K blocks (for_blocks in
  // particle_order.cpp), which the simulations of the other tests are too small to reach.
  const uint32_t n = 100000, walls = 3;
  HostState by_id;
  by_id.row_start.push_back(0);
  for (uint32_t i = 0; i < n; ++i) {
    by_id.pos.push_back(gpu::vec4(float(i), 1.0f, 2.0f, 0.5f));
    by_id.vel.push_back(gpu::vec4(0.0f, float(i), 0.0f, 1.0f));
    for (uint32_t j = 0; j < i % 7; ++j) {  // partners above i, and a wall now and then
      uint32_t partner = j == 6 ? n + i % walls : (i + 1 + 37 * j) % n;
      by_id.partner.push_back(partner);
      by_id.owner.push_back(i);
      by_id.history.push_back(gpu::vec4(float(i), float(j), 0.0f, 0.0f));
    }
    by_id.row_start.push_back(uint32_t(by_id.partner.size()));
  }
  // The transposed list: each particle's contacts as the partner, by contact index.
  std::vector<std::vector<uint32_t>> as_partner(n);
  for (uint32_t c = 0; c < by_id.partner.size(); ++c)
    if (by_id.partner[c] < n) as_partner[by_id.partner[c]].push_back(c);
  by_id.trans_start.push_back(0);
  for (const auto& row : as_partner) {
    by_id.trans_list.insert(by_id.trans_list.end(), row.begin(), row.end());
    by_id.trans_start.push_back(uint32_t(by_id.trans_list.size()));
  }
  ParticleOrder order = scrambled(n, 11);

  HostState one = by_id, several = by_id;
  to_stored(one, order, 1);
  to_stored(several, order, 3);
  std::string which;
  bool same = same_state(one, several, &which);
  INFO("first difference in " << which);
  CHECK(same);
  // Slot s holds particle id_of[s], its contacts in their order, partners and owners as slots.
  for (uint32_t s : {0u, 1u, 65535u, 65536u, n - 1}) {
    uint32_t g = order.id_of[s];
    CHECK(one.pos[s].x == float(g));
    REQUIRE(one.row_start[s + 1] - one.row_start[s] == by_id.row_start[g + 1] - by_id.row_start[g]);
    for (uint32_t k = 0; k < one.row_start[s + 1] - one.row_start[s]; ++k) {
      uint32_t c = one.row_start[s] + k, c_id = by_id.row_start[g] + k;
      CHECK(one.owner[c] == s);
      CHECK(one.history[c].y == by_id.history[c_id].y);
      uint32_t p = by_id.partner[c_id];
      CHECK(one.partner[c] == (p < n ? order.slot_of[p] : p));
    }
  }
  to_global(several, order, 3);
  bool back = same_state(several, by_id, &which);
  INFO("back by global id; first difference in " << which);
  CHECK(back);
}

TEST_CASE("particle order: a reorder from the device's slots gives the order and the state of one from global ids",
          "[engine][order]") {
  // The settled clump pile (bodies) and the spheres of a cloud: cell order computed from the
  // positions in scrambled slots, and the state moved straight from those slots into the new ones.
  for (const CaseSpec& spec : {clump_pile(), seeded_cloud(300, 5, 0.02, 0.3)}) {
    auto sim = simulate(spec, "cpu", 1, KernelVariant::parse("reorder=0"));
    sim->advance(300);
    const HostState& by_id = sim->state();
    const double cell = sim->model().cell;
    ParticleOrder before = scrambled(uint32_t(by_id.pos.size()), 7);
    HostState in_slots = by_id;
    to_stored(in_slots, before);
    ParticleOrder from_ids = cell_order(by_id.pos, by_id.bodies, cell);
    ParticleOrder from_slots = cell_order(in_slots.pos, before.id_of, in_slots.bodies, cell);
    CHECK(from_slots.id_of == from_ids.id_of);
    HostState straight = in_slots, through_ids = by_id;
    to_other_slots(straight, before, from_slots, 2);
    to_stored(through_ids, from_ids);
    std::string which;
    bool same = same_state(straight, through_ids, &which);
    INFO("first difference in " << which);
    CHECK(same);
  }
}
