#include "io/state_validation.h"

#include <cmath>
#include <cstring>
#include <type_traits>

#include "engine/buffer_table.h"
#include "util/number_text.h"

namespace repose {

namespace {

std::string at(const char* array, size_t k) { return std::string(array) + "[" + std::to_string(k) + "]"; }
std::string num(double v) { return format_g(v, 6); }
bool finite(const gpu::vec4& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w); }

// Every float of the particle and contact arrays and of the bodies.
std::string non_finite(const HostState& s) {
  std::string problem;
  for_each_kept(s, [&](const BufferSpec& spec, const auto& v) {
    if constexpr (std::is_same_v<std::decay_t<decltype(v[0])>, gpu::vec4>)
      for (size_t k = 0; k < v.size() && problem.empty(); ++k)
        if (!finite(v[k])) problem = at(spec.name, k) + " holds a number that is not finite";
  });
  if (!problem.empty()) return problem;
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    const gpu::Body& x = s.bodies[b];
    for (const gpu::vec4* v : {&x.pos, &x.vel, &x.quat, &x.ang_mom, &x.omega, &x.inv_inertia, &x.force, &x.torque, &x.drag})
      if (!finite(*v)) return at("bodies", b) + " holds a number that is not finite";
  }
  return "";
}

// Radii > 0, and positions where a float still resolves a particle's radius (beyond 2^23 radii
// from the origin one float step exceeds it: no case means that).
std::string bad_positions(const HostState& s) {
  for (size_t i = 0; i < s.pos.size(); ++i) {
    const gpu::vec4& p = s.pos[i];
    if (!(p.w > 0)) return at("pos", i) + ": radius " + num(p.w) + " m is not positive";
    double reach = double(p.w) * 8388608.0;
    if (std::fabs(p.x) > reach || std::fabs(p.y) > reach || std::fabs(p.z) > reach)
      return at("pos", i) + " = (" + num(p.x) + ", " + num(p.y) + ", " + num(p.z) + ") m: so far out that a float "
             "cannot resolve its radius " + num(p.w) + " m";
  }
  for (size_t i = 0; i < s.history.size(); ++i)
    if (s.history[i].w < 0) return at("history", i) + ": a contact's age of " + num(s.history[i].w) + " steps";
  return "";
}

// Rows: particle i's entries row_start[i] .. row_start[i+1]-1, ascending partners, each owned by
// i. A pair belongs to the lower id, except that a sphere of the large bucket (a cabbage's core)
// leaves its pairs with small spheres to them (shaders/kernels/neighbour.h): a partner before i
// must be larger than i.
std::string bad_rows(const HostState& s) {
  size_t n = s.pos.size(), c = s.partner.size();
  if (s.row_start.size() != n + 1) return "row_start has " + std::to_string(s.row_start.size()) + " entries, not N + 1";
  if (s.row_start[0] != 0) return "row_start[0] = " + std::to_string(s.row_start[0]) + ", not 0";
  for (size_t i = 0; i < n; ++i)
    if (s.row_start[i + 1] < s.row_start[i]) return "row_start descends at " + std::to_string(i + 1);
  if (s.row_start[n] != c)
    return "row_start[N] = " + std::to_string(s.row_start[n]) + ", but the list holds " + std::to_string(c) + " contacts";
  if (!s.owner.empty() && s.owner.size() != c) return "owner has " + std::to_string(s.owner.size()) + " entries, not C";
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = s.row_start[i]; k < s.row_start[i + 1]; ++k) {
      uint32_t j = s.partner[k];
      if (j == i || (j < i && !(s.pos[j].w > s.pos[i].w)))
        return at("partner", k) + " = " + std::to_string(j) + " in the row of particle " + std::to_string(i) +
               ": a row holds partners after its owner, or larger ones";
      if (k > s.row_start[i] && s.partner[k] <= s.partner[k - 1])
        return at("partner", k) + " = " + std::to_string(s.partner[k]) + " after " + at("partner", k - 1) + " = " +
               std::to_string(s.partner[k - 1]) + ": the row of particle " + std::to_string(i) + " is not in ascending order";
      if (!s.owner.empty() && s.owner[k] != i)
        return at("owner", k) + " = " + std::to_string(s.owner[k]) + " in the row of particle " + std::to_string(i);
    }
  return "";
}

// The transposed index as transpose_fill builds it: for each particle, the contacts where it is
// the partner, ascending.
std::string bad_transposed(const HostState& s) {
  size_t n = s.pos.size();
  std::vector<uint32_t> start(n + 1, 0u), list;
  for (uint32_t p : s.partner)
    if (p < n) ++start[p + 1];
  for (size_t j = 0; j < n; ++j) start[j + 1] += start[j];
  list.resize(start[n]);
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (uint32_t c = 0; c < s.partner.size(); ++c)
    if (s.partner[c] < n) list[fill[s.partner[c]]++] = c;
  if (s.trans_start.size() != n + 1) return "trans_start has " + std::to_string(s.trans_start.size()) + " entries, not N + 1";
  for (size_t j = 0; j <= n; ++j)
    if (s.trans_start[j] != start[j])
      return at("trans_start", j) + " = " + std::to_string(s.trans_start[j]) + ", the contact list gives " + std::to_string(start[j]);
  for (size_t k = 0; k < list.size(); ++k)
    if (s.trans_list[k] != list[k])
      return at("trans_list", k) + " = " + std::to_string(s.trans_list[k]) + ", the contact list gives " + std::to_string(list[k]);
  return "";
}

// The neighbour list's counters as a finished batch leaves them (shaders/repose_shared.h kCtl*).
std::string bad_control(const HostState& s, uint64_t step) {
  const auto& ctl = s.control;
  auto word = [&](uint32_t k) { return "control word " + std::to_string(k) + " = " + std::to_string(ctl[k]); };
  if (ctl[gpu::kCtlOverflow] != 0) return word(gpu::kCtlOverflow) + ": the list's overflow flag, which no finished batch leaves set";
  for (uint32_t k : {gpu::kCtlNeedRebuild, gpu::kCtlRebuilding})
    if (ctl[k] > 1) return word(k) + ": a flag, 0 or 1";
  if (ctl[gpu::kCtlContacts] != s.partner.size())
    return word(gpu::kCtlContacts) + ": the list's size, but it holds " + std::to_string(s.partner.size()) + " contacts";
  if (ctl[gpu::kCtlMaxContacts] < ctl[gpu::kCtlContacts] || ctl[gpu::kCtlOldContacts] > ctl[gpu::kCtlMaxContacts])
    return word(gpu::kCtlMaxContacts) + ": the largest list so far, below the list's size " +
           std::to_string(ctl[gpu::kCtlContacts]) + " or the previous list's " + std::to_string(ctl[gpu::kCtlOldContacts]);
  // At most one rebuild per step, and one before the first (velocity Verlet's initial forces).
  if (ctl[gpu::kCtlRebuildCount] > step + 1 || ctl[gpu::kCtlStepsSinceBuild] > step)
    return "control words 4 and 5 count " + std::to_string(ctl[gpu::kCtlStepsSinceBuild]) + " steps since a rebuild and " +
           std::to_string(ctl[gpu::kCtlRebuildCount]) + " rebuilds, more than the " + std::to_string(step) + " steps taken";
  return "";
}

// With bodies, every particle is a sub-sphere of exactly one: bodies' spheres contiguous, in order.
std::string bad_bodies(const HostState& s) {
  uint64_t next = 0;
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    const gpu::uvec4& sp = s.bodies[b].spheres;
    if (sp.x != next || sp.y == 0 || next + sp.y > s.pos.size())
      return at("bodies", b) + ": sub-spheres " + std::to_string(sp.x) + " + " + std::to_string(sp.y) +
             " do not follow the previous body's within the " + std::to_string(s.pos.size()) + " particles";
    next += sp.y;
  }
  if (!s.bodies.empty() && next != s.pos.size())
    return "the bodies hold " + std::to_string(next) + " of the " + std::to_string(s.pos.size()) + " particles";
  return "";
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

std::string state_problem(const HostState& s, uint64_t step, double time) {
  if (!std::isfinite(time) || time < 0) return "the time " + num(time) + " s";
  std::string problem = non_finite(s);
  if (problem.empty()) problem = bad_positions(s);
  if (problem.empty()) problem = bad_rows(s);
  if (problem.empty()) problem = bad_bodies(s);
  if (problem.empty() && !s.control.empty()) problem = bad_control(s, step);
  if (problem.empty() && !s.control.empty()) problem = bad_transposed(s);
  return problem;
}

std::string state_misfit(const HostState& s, const Model& m) {
  size_t n = m.n_particles, walls = m.walls.size();
  if (s.pos.size() != n) return std::to_string(s.pos.size()) + " particles in the state, " + std::to_string(n) + " in the case";
  if (s.bodies.size() != m.bodies.size())
    return std::to_string(s.bodies.size()) + " bodies in the state, " + std::to_string(m.bodies.size()) + " in the case";
  bool springs = (m.flags & gpu::kFlagRollingSpring) != 0;
  if (springs != !s.rolling_spring.empty() && !s.partner.empty())
    return springs ? "the case has EPSD rolling springs, the state none" : "the state has EPSD rolling springs, the case none";
  for (size_t k = 0; k < s.partner.size(); ++k)
    if (s.partner[k] >= n + walls)
      return at("partner", k) + " = " + std::to_string(s.partner[k]) + " is beyond the case's " + std::to_string(n) +
             " particles and " + std::to_string(walls) + " walls";
  // Entries within the skin: a few dozen neighbours per particle, plus the walls near it.
  uint64_t most = s.partner.size() + uint64_t(n) * (64 + walls);
  if (!s.control.empty() && s.control[gpu::kCtlMaxContacts] > most)
    return "control word 6 = " + std::to_string(s.control[gpu::kCtlMaxContacts]) + ": a list larger than " +
           std::to_string(most) + " entries cannot be needed by " + std::to_string(n) + " particles";
  const char* names[3] = {"radius", "1/mass", "1/moment of inertia"};
  for (size_t i = 0; i < n; ++i) {
    const gpu::vec4* state[3] = {&s.pos[i], &s.vel[i], &s.omega[i]};
    const gpu::vec4* model[3] = {&m.pos[i], &m.vel[i], &m.omega[i]};
    for (int q = 0; q < 3; ++q)
      if (!same_bits(state[q]->w, model[q]->w))
        return "particle " + std::to_string(i) + "'s " + names[q] + " is " + num(state[q]->w) + " in the state, " +
               num(model[q]->w) + " in the case";
  }
  for (size_t b = 0; b < m.bodies.size(); ++b) {
    const gpu::Body &x = s.bodies[b], &y = m.bodies[b];
    bool same = same_bits(x.pos.w, y.pos.w) && std::memcmp(&x.inv_inertia, &y.inv_inertia, sizeof x.inv_inertia) == 0 &&
                std::memcmp(&x.spheres, &y.spheres, sizeof x.spheres) == 0 && std::memcmp(&x.drag, &y.drag, sizeof x.drag) == 0;
    if (!same) return "body " + std::to_string(b) + "'s mass, inertia, sub-spheres or drag areas differ from the case's";
  }
  return "";
}

}  // namespace repose
