#include "engine/cpu_backend.h"

#include <algorithm>
#include <chrono>

namespace repose {

CpuBackend::CpuBackend(unsigned threads) : pool_(threads) {}

std::string CpuBackend::describe() const {
  return "cpu (C++ twin of the shaders, " + std::to_string(pool_.size()) + " thread" +
         (pool_.size() == 1 ? "" : "s") + ")";
}

void CpuBackend::allocate(const Layout& l, const ConstantData& constants) {
  layout_ = l;
  size_t n = l.n_particles, c = l.capacity, t = l.table_size;
  auto v4 = [](std::vector<gpu::vec4>& v, size_t k) { v.assign(std::max<size_t>(k, 1), gpu::vec4(0.0f)); };
  auto u = [](std::vector<uint32_t>& v, size_t k) { v.assign(std::max<size_t>(k, 1), 0u); };
  v4(pos_, n); v4(vel_, n); v4(omega_, n); v4(force_, n); v4(torque_, n); v4(pos_at_build_, n);
  // old_history and old_partner share contact_force and trans_list (shaders/repose_shared.h).
  v4(history_, c); v4(contact_force_, c); v4(torque_i_, c); v4(torque_j_, l.lean_contacts ? 0 : c);
  v4(rolling_spring_, l.rolling_springs ? 2 * c : 0);
  v4(wall_force_, l.n_walls);
  u(control_, gpu::kControlWords); u(cell_of_, n); u(cell_start_, t + 2); u(cell_fill_, t + 1);
  u(sorted_, n); u(row_start_, n + 1); u(partner_, c); u(owner_, c); u(old_row_start_, n + 1);
  u(trans_start_, n + 1); u(trans_fill_, n); u(trans_list_, c);
  material_ = constants.material;
  pairs_ = constants.pairs;
  subs_ = constants.subs;
  if (subs_.empty()) subs_.resize(1);
  bodies_.assign(std::max<size_t>(l.n_bodies, 1), gpu::Body{});
  walls_.assign(std::max<size_t>(size_t(l.batch_steps) * l.n_walls, 1), gpu::WallState{});
  point_buffers();
}

void CpuBackend::point_buffers() {
  buf_.pos = pos_.data(); buf_.vel = vel_.data(); buf_.omega = omega_.data();
  buf_.force = force_.data(); buf_.torque = torque_.data(); buf_.pos_at_build = pos_at_build_.data();
  buf_.material = material_.data(); buf_.pairs = pairs_.data(); buf_.walls = walls_.data();
  buf_.control = control_.data(); buf_.cell_of = cell_of_.data(); buf_.cell_start = cell_start_.data();
  buf_.cell_fill = cell_fill_.data(); buf_.sorted = sorted_.data(); buf_.row_start = row_start_.data();
  buf_.partner = partner_.data(); buf_.owner = owner_.data(); buf_.history = history_.data();
  buf_.old_row_start = old_row_start_.data(); buf_.old_partner = trans_list_.data();
  buf_.old_history = contact_force_.data(); buf_.contact_force = contact_force_.data();
  buf_.torque_i = torque_i_.data(); buf_.torque_j = torque_j_.data();
  buf_.trans_start = trans_start_.data(); buf_.trans_fill = trans_fill_.data();
  buf_.trans_list = trans_list_.data(); buf_.wall_force = wall_force_.data();
  buf_.bodies = bodies_.data(); buf_.subs = subs_.data(); buf_.rolling_spring = rolling_spring_.data();
}

template <class T>
static void put(std::vector<T>& dst, const std::vector<T>& src) {
  std::copy(src.begin(), src.begin() + std::min(src.size(), dst.size()), dst.begin());
}

void CpuBackend::upload_state(const HostState& s) {
  put(pos_, s.pos); put(vel_, s.vel); put(omega_, s.omega); put(force_, s.force);
  put(torque_, s.torque); put(pos_at_build_, s.pos_at_build); put(control_, s.control);
  put(row_start_, s.row_start); put(partner_, s.partner); put(owner_, s.owner);
  put(trans_start_, s.trans_start); put(trans_list_, s.trans_list); put(history_, s.history);
  put(bodies_, s.bodies);
  if (layout_.rolling_springs) put(rolling_spring_, s.rolling_spring);
}

void CpuBackend::download_state(HostState& s) {
  size_t n = layout_.n_particles;
  size_t used = std::min<size_t>(control_[gpu::kCtlContacts], layout_.capacity);
  auto take = [](auto& dst, const auto& src, size_t k) { dst.assign(src.begin(), src.begin() + k); };
  take(s.pos, pos_, n); take(s.vel, vel_, n); take(s.omega, omega_, n); take(s.force, force_, n);
  take(s.torque, torque_, n); take(s.pos_at_build, pos_at_build_, n);
  take(s.control, control_, gpu::kControlWords);
  take(s.row_start, row_start_, n + 1); take(s.trans_start, trans_start_, n + 1);
  take(s.partner, partner_, used); take(s.owner, owner_, used); take(s.history, history_, used);
  size_t trans_used = std::min<size_t>(trans_start_[n], layout_.capacity);
  take(s.trans_list, trans_list_, trans_used);
  take(s.bodies, bodies_, layout_.n_bodies);
  if (layout_.rolling_springs) take(s.rolling_spring, rolling_spring_, used);
}

void CpuBackend::upload_walls(const std::vector<gpu::WallState>& walls) { put(walls_, walls); }

void CpuBackend::execute(const std::vector<Dispatch>& program, KernelTimes* times) {
  for (const Dispatch& d : program) {
    auto t0 = std::chrono::steady_clock::now();
    uint32_t groups = d.indirect_word >= 0 ? control_[d.indirect_word] : d.groups;
    if (d.kernel == KernelId::Scan) {
      if (groups > 0) gpu::run_scan(buf_, d.scan);
    } else {
      buf_.push = d.sim;
      gpu::run_kernel(d.kernel, buf_, uint64_t(groups) * d.sim.workgroup, pool_);
    }
    if (times)
      (*times)[kernel_shader_name(d.kernel)] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
}

std::vector<uint32_t> CpuBackend::read_control() { return control_; }

std::vector<gpu::vec4> CpuBackend::wall_forces(const gpu::SimPush& push) {
  buf_.push = push;
  gpu::run_wall_reduce(buf_, layout_.n_walls);
  return std::vector<gpu::vec4>(wall_force_.begin(), wall_force_.begin() + layout_.n_walls);
}

size_t CpuBackend::memory_bytes() const {
  size_t b = 0;
  for (auto* v : {&pos_, &vel_, &omega_, &force_, &torque_, &pos_at_build_, &history_, &rolling_spring_,
                  &contact_force_, &torque_i_, &torque_j_, &wall_force_})
    b += v->size() * sizeof(gpu::vec4);
  for (auto* v : {&material_, &control_, &cell_of_, &cell_start_, &cell_fill_, &sorted_, &row_start_,
                  &partner_, &owner_, &old_row_start_, &trans_start_, &trans_fill_,
                  &trans_list_})
    b += v->size() * sizeof(uint32_t);
  return b + pairs_.size() * sizeof(gpu::PairParams) + walls_.size() * sizeof(gpu::WallState) +
         bodies_.size() * sizeof(gpu::Body) + subs_.size() * sizeof(gpu::SubSphere);
}

}  // namespace repose
