#include "engine/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "engine/buffer_table.h"

namespace repose {

uint32_t first_contact_capacity(const Model& m) {
  return 6 * m.n_particles + 4 * static_cast<uint32_t>(m.walls.size()) + 64;
}

uint32_t grown_capacity(uint32_t needed) { return needed + needed / 4 + 64; }

uint32_t restored_capacity(const Model& m, const HostState& s) {
  uint32_t needed = s.control.size() == gpu::kControlWords
                        ? std::max(s.control[gpu::kCtlContacts], s.control[gpu::kCtlMaxContacts])
                        : 0u;
  return std::max(first_contact_capacity(m), grown_capacity(needed));
}

Simulation::Simulation(Model model, std::unique_ptr<Backend> backend, KernelVariant variant,
                       uint32_t max_batch_steps, uint32_t first_capacity)
    : model_(std::move(model)), backend_(std::move(backend)), variant_(variant),
      reorder_(variant.reorder, variant.reorder_capped) {
  layout_ = model_layout(model_, variant_, max_batch_steps);
  // Cell order from the start (one sort), so the first batch need not store the particles anew.
  order_ = variant_.reorder ? cell_order(model_.pos, model_.bodies, model_.cell, backend_->host_threads())
                            : ParticleOrder::identity(model_.n_particles);
  stored_by_id_ = order_.is_identity();

  // Initial host state: particles as given, empty contact list (the first step builds it).
  state_.pos = model_.pos;
  state_.vel = model_.vel;
  state_.omega = model_.omega;
  state_.force.assign(model_.n_particles, gpu::vec4(0.0f));
  state_.torque.assign(model_.n_particles, gpu::vec4(0.0f));
  state_.pos_at_build = model_.pos;
  state_.control.assign(gpu::kControlWords, 0u);
  state_.row_start.assign(model_.n_particles + 1, 0u);
  state_.trans_start.assign(model_.n_particles + 1, 0u);
  state_.bodies = model_.bodies;
  allocate(first_capacity ? first_capacity : first_contact_capacity(model_));
  backend_->prepare(dispatches_of_run());
  if (layout_.n_bodies) {
    backend_->execute(body_place_program(model_, layout_, variant_));
    download();
    state_.pos_at_build = state_.pos;
    upload();
  }

  // Velocity Verlet needs F(0) before its first half kick.
  if (model_.integrator == Integrator::VelocityVerlet) {
    for (int attempt = 0;; ++attempt) {
      upload_walls(0, 0.0, 1);  // at t = 0; again after a retry's allocate(), which zeroes every buffer
      backend_->execute(initial_forces_program(model_, layout_, variant_, 0));
      auto ctl = backend_->read_control();
      if (!ctl[gpu::kCtlOverflow]) break;
      if (attempt > 8) throw std::runtime_error("contact list keeps overflowing");
      grow(ctl[gpu::kCtlMaxContacts]);
    }
    download();  // once: a retry of the first batch starts from here
    control_ = state_.control;
  }
  if (variant_.reorder) reorder_.reordered(rebuilds(), 0.0);
}

void Simulation::allocate(uint32_t capacity) {
  layout_.capacity = capacity;
  backend_->allocate(layout_, stored_constants(model_, order_));
  upload();
  // Every wall's row (walls.h wall_at): a wall without motion keeps it for the whole run.
  std::vector<gpu::WallState> rows;
  rows.reserve(model_.walls.size());
  for (size_t w = 0; w < model_.walls.size(); ++w) rows.push_back(model_.wall_state(w, 0.0));
  if (!rows.empty()) backend_->upload_walls(rows, 0);
}

// In cell order the state moves into its slots in place (no second copy of it) and stays there
// until someone reads it: the batch that follows makes it old anyway.
void Simulation::upload() {
  if (!stored_by_id_ && !state_in_slots_) {
    to_stored(state_, order_, backend_->host_threads());
    state_in_slots_ = true;
  }
  backend_->upload_state(state_);
  unread_batches_.clear();
  control_ = state_.control;
  rows_current_.reset();
}

void Simulation::download() const {
  rows_ = HostState();  // state_ holds them from now on
  rows_current_.reset();
  backend_->download_state(state_);
  state_in_slots_ = !stored_by_id_;
  unread_batches_.clear();
}

const HostState& Simulation::state() const {
  if (!unread_batches_.empty()) download();
  if (state_in_slots_) {
    to_global(state_, order_, backend_->host_threads());
    state_in_slots_ = false;
  }
  return state_;
}

template <class T>
const std::vector<T>& Simulation::rows_in_any_order(std::vector<T> HostState::*row) const {
  if (unread_batches_.empty()) return state_.*row;
  std::vector<T>& rows = rows_.*row;
  const BufferSpec* spec = nullptr;
  for_each_kept(rows_, [&](const BufferSpec& b, const auto& v) {
    if (static_cast<const void*>(&v) == static_cast<const void*>(&rows)) spec = &b;
  });
  // A contact list's rows mean nothing without the rest of it.
  if (spec->count != BufferCount::Particles && spec->count != BufferCount::Bodies)
    throw std::logic_error(std::string("rows_in_any_order: ") + spec->name + " is not a row of every particle or body");
  if (!rows_current_[spec->binding]) {
    rows.resize(buffer_elements(*spec, layout_));
    backend_->read_binding(spec->binding, rows.data(), rows.size() * sizeof(T));
    rows_current_.set(spec->binding);
  }
  return rows;
}
template const std::vector<gpu::vec4>& Simulation::rows_in_any_order(std::vector<gpu::vec4> HostState::*) const;
template const std::vector<gpu::Body>& Simulation::rows_in_any_order(std::vector<gpu::Body> HostState::*) const;

void Simulation::store_in_order(ParticleOrder order) {
  if (order.size() != model_.n_particles)
    throw std::invalid_argument("a particle order for another number of particles");
  state();  // by global id before the slots change
  use_order(std::move(order));
}

// A state still in the old slots moves straight into the new ones: one conversion, not one to
// global ids and one back. Each part's time goes to the profile (a GPU's transfers are most of it).
void Simulation::renew_cell_order() {
  RunProfile::ReorderParts& parts = profile_.reorder_parts;
  {
    ProfileClock clock(&parts.download);
    if (!unread_batches_.empty()) download();
  }
  ParticleOrder next;
  {
    ProfileClock clock(&parts.order);
    if (state_in_slots_) {
      next = cell_order(state_.pos, order_.id_of, state_.bodies, model_.cell, backend_->host_threads());
      to_other_slots(state_, order_, next, backend_->host_threads());
    } else {  // by global id: something read the state since the last batch
      next = cell_order(state_.pos, state_.bodies, model_.cell, backend_->host_threads());
      if (!next.is_identity()) to_stored(state_, next, backend_->host_threads());
    }
    state_in_slots_ = !next.is_identity();
  }
  ProfileClock clock(&parts.upload);
  use_order(std::move(next));
}

void Simulation::use_order(ParticleOrder order) {
  order_ = std::move(order);
  stored_by_id_ = order_.is_identity();
  // The constants and the state anew, in the new slots (the scratch rows need no zeroing: a
  // restart's are zero, a running simulation's are not, and both give the same bytes).
  backend_->upload_constants(stored_constants(model_, order_));
  upload();
}

// A list for `needed` contacts and some to spare, uploading state_ again. After an overflow
// state_ must be a state of the run from before the failed attempt (its control words included:
// the attempt's largest list, reached after contacts went missing, is no state of the run), so the
// redone evaluation starts where an ample list's would.
void Simulation::grow(uint32_t needed) {
  allocate(std::max(layout_.capacity, grown_capacity(needed)));
}

// After grow() in an overflow: the device back at the failed batch's start. state_, uploaded by
// grow(), is the state before the batches nobody read (none was downloaded); they run again on
// the larger list. Each ran without overflow on the smaller one, so each does again, to the same
// bytes (a list's capacity never changes the results). A run read at every frame or reorder
// replays at most the batches since then; overflows are rare (the list grows by a quarter).
void Simulation::replay_unread(std::vector<uint32_t> batches) {
  uint64_t first = step_;
  for (uint32_t k : batches) first -= k;
  for (uint32_t k : batches) {
    run_batch(first, k);
    first += k;
  }
  unread_batches_ = std::move(batches);
  {
    ProfileClock clock(transfer_clock());
    control_ = backend_->read_control();
  }
  if (control_[gpu::kCtlOverflow]) throw std::logic_error("a batch run again on a larger contact list overflowed it");
}

void Simulation::run_batch(uint64_t first, uint32_t steps) {
  {
    ProfileClock clock(transfer_clock());
    upload_walls(first, wall_time_offset(), steps);
  }
  if (!profiling_) return backend_->execute(batch_program(first, steps));
  ExecuteTimes times;
  {
    ProfileClock clock(&profile_.batch_seconds);
    backend_->execute(batch_program(first, steps), &times);
  }
  profile_.add(times);
}

// The moving walls' rows for `steps` steps from step `first`, each at (first + s + offset) dt
// (the still walls' rows stay as allocate() put them).
void Simulation::upload_walls(uint64_t first, double offset, uint32_t steps) {
  if (model_.moving_walls.empty()) return;
  std::vector<gpu::WallState> rows;
  rows.reserve(size_t(steps) * model_.moving_walls.size());
  for (uint32_t s = 0; s < steps; ++s) {
    double t = (double(first + s) + offset) * model_.dt;
    for (uint32_t w : model_.moving_walls) rows.push_back(model_.wall_state(w, t));
  }
  backend_->upload_walls(rows, model_.walls.size());
}

namespace {

// True when some wall moves between the start of step `first` and the end of `steps` steps
// (velocity Verlet evaluates a step's walls at its end).
bool walls_move_during(const Model& m, uint64_t first, uint32_t steps) {
  double t0 = double(first) * m.dt, t1 = double(first + steps + 1) * m.dt;
  for (uint32_t w : m.moving_walls) {
    const WallMotion& motion = m.walls[w].motion;
    if (motion.start_time < t1 && motion.stop_time > t0) return true;
  }
  return false;
}

}  // namespace

std::vector<Dispatch> Simulation::dispatches_of_run() const {
  std::vector<Dispatch> all;
  auto append = [&](const std::vector<Dispatch>& program) { all.insert(all.end(), program.begin(), program.end()); };
  if (layout_.n_bodies) append(body_place_program(model_, layout_, variant_));
  if (model_.integrator == Integrator::VelocityVerlet) append(initial_forces_program(model_, layout_, variant_, 0));
  for (bool walls_still : {true, false}) append(step_program(model_, layout_, variant_, 0, walls_still));
  if (layout_.n_wall_groups) all.push_back(wall_sums_dispatch());
  return all;
}

Dispatch Simulation::wall_sums_dispatch() const {
  Dispatch d;
  d.kernel = KernelId::WallReduce;
  d.groups = layout_.n_wall_groups;
  d.sim = base_push(model_, layout_, variant_);
  return d;
}

std::vector<Dispatch> Simulation::batch_program(uint64_t first, uint32_t steps) const {
  // A batch in which no wall moves forces no rebuilds for walls: the skin check alone suffices.
  bool still = !walls_move_during(model_, first, steps);
  std::vector<Dispatch> program;
  for (uint32_t s = 0; s < steps; ++s) {
    auto one = step_program(model_, layout_, variant_, s, still);
    program.insert(program.end(), one.begin(), one.end());
    if (summing_walls_) {
      // After the step's forces: each named wall's, summed over the batch from its first step.
      Dispatch d = wall_sums_dispatch();
      d.sim.wall_sums = s == 0 ? 2u : 1u;
      program.push_back(d);
    }
  }
  return program;
}

void Simulation::sum_wall_forces() {
  if (model_.walls.empty()) return;
  summing_walls_ = true;
  wall_sum_.assign(3 * size_t(model_.n_wall_groups), 0.0);
  wall_peak_.assign(model_.n_wall_groups, 0.0);
}

// A batch's sums (each batch starts them anew, so a batch redone after an overflow counts once),
// added in batch order in double.
void Simulation::add_batch_wall_sums() {
  std::vector<gpu::vec4> sums = backend_->wall_sums();
  size_t n = model_.n_wall_groups;
  for (size_t w = 0; w < n; ++w) {
    wall_sum_[3 * w] += sums[w].x;
    wall_sum_[3 * w + 1] += sums[w].y;
    wall_sum_[3 * w + 2] += sums[w].z;
    wall_peak_[w] = std::max(wall_peak_[w], double(sums[n + w].w));
  }
}

std::vector<WallImpulse> Simulation::take_wall_impulses() {
  std::vector<WallImpulse> out;
  for (const auto& name : model_.wall_group_names()) out.push_back({name, 0, 0, 0, 0});
  if (!summing_walls_) return out;
  for (size_t w = 0; w < out.size(); ++w) {
    WallImpulse& g = out[w];
    g.jx += wall_sum_[3 * w] * model_.dt;
    g.jy += wall_sum_[3 * w + 1] * model_.dt;
    g.jz += wall_sum_[3 * w + 2] * model_.dt;
    g.peak = std::max(g.peak, std::sqrt(wall_peak_[w]));
  }
  std::fill(wall_sum_.begin(), wall_sum_.end(), 0.0);
  std::fill(wall_peak_.begin(), wall_peak_.end(), 0.0);
  return out;
}

void Simulation::advance(uint64_t steps, const std::function<void(const Simulation&)>& on_batch) {
  uint64_t target = step_ + steps;
  auto since = [](auto t0) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  while (step_ < target) {
    auto t0 = std::chrono::steady_clock::now();
    if (reorder_.due(rebuilds())) {
      renew_cell_order();
      double seconds = since(t0);
      reorder_.reordered(rebuilds(), seconds);
      profile_.reorders += 1;
      profile_.reorder_seconds += seconds;
    }
    auto batch_start = std::chrono::steady_clock::now();
    uint32_t k = static_cast<uint32_t>(std::min<uint64_t>(layout_.batch_steps, target - step_));
    run_batch(step_, k);
    std::vector<uint32_t> ctl;
    {
      ProfileClock clock(transfer_clock());
      ctl = backend_->read_control();  // a few words: the state stays until someone reads it
    }
    if (ctl[gpu::kCtlOverflow]) {
      // Redo the batch from its start with a larger list: nothing of it is kept.
      ++retries_;
      std::vector<uint32_t> unread = std::move(unread_batches_);
      grow(ctl[gpu::kCtlMaxContacts]);
      replay_unread(std::move(unread));
      profile_.wall_seconds += since(t0);
      continue;
    }
    uint32_t rebuilds_before = rebuilds();
    control_ = std::move(ctl);
    unread_batches_.push_back(k);
    rows_current_.reset();
    if (unread_batches_.size() >= kMostUnreadBatches) {  // an overflow replays no more
      ProfileClock clock(transfer_clock());
      download();
    }
    if (summing_walls_) add_batch_wall_sums();
    step_ += k;
    profile_.steps += k;
    profile_.rebuilds += rebuilds() - rebuilds_before;
    profile_.contact_steps += double(contacts()) * k;
    profile_.wall_seconds += since(t0);
    reorder_.stepped(since(batch_start));
    if (on_batch) on_batch(*this);
    if (observer_) observer_(*this);
  }
}

std::vector<gpu::vec4> Simulation::contact_forces() {
  std::vector<gpu::vec4> stored = backend_->contact_forces(contacts());
  if (stored_by_id_) return stored;
  std::vector<uint32_t> contact_of = stored_contact_ids(state(), order_);
  std::vector<gpu::vec4> by_id(stored.size());
  for (size_t c = 0; c < stored.size() && c < contact_of.size(); ++c) by_id[contact_of[c]] = stored[c];
  return by_id;
}

RunProfile Simulation::take_profile() {
  RunProfile p = std::move(profile_);
  profile_ = RunProfile{};
  return p;
}

void Simulation::set_state(const HostState& s) {
  state_ = s;
  state_in_slots_ = false;
  upload();
}

void Simulation::restore(const HostState& s, uint64_t step) {
  auto refuse = [](const std::string& what) { throw std::invalid_argument("the state does not fit the case: " + what); };
  auto count = [](size_t k) { return std::to_string(k); };
  if (s.pos.size() != model_.n_particles)
    refuse(count(s.pos.size()) + " particles in the state, " + count(model_.n_particles) + " in the case");
  if (s.bodies.size() != model_.bodies.size())
    refuse(count(s.bodies.size()) + " bodies in the state, " + count(model_.bodies.size()) + " in the case");
  if (layout_.rolling_springs != !s.rolling_spring.empty() && !s.partner.empty())
    refuse(layout_.rolling_springs ? "the case has EPSD rolling springs, the state none"
                                   : "the state has EPSD rolling springs, the case none");
  if (s.control.size() != gpu::kControlWords || s.pos_at_build.size() != s.pos.size())
    refuse("the state holds no neighbour-list bookkeeping (written by an older version)");
  state_ = s;
  state_in_slots_ = false;
  reorder_.restart();  // cell order by the restored positions before the first batch
  // Dispatch sizes over the current list follow this run's workgroup size (the kernels return
  // early past the contact count, so only coverage matters).
  uint32_t contacts = state_.control[gpu::kCtlContacts];
  uint32_t groups = (contacts + variant_.workgroup - 1) / variant_.workgroup;
  state_.control[gpu::kCtlArgsContacts] = gpu::dispatch_columns(groups, max_groups_x());
  state_.control[gpu::kCtlArgsContacts + 1] = gpu::dispatch_rows(groups, max_groups_x());
  state_.control[gpu::kCtlArgsContacts + 2] = 1;
  grow(std::max(contacts, state_.control[gpu::kCtlMaxContacts]));
  step_ = step;
}

EnergySummary Simulation::kinetic_energy() const { return repose::kinetic_energy(state()); }

std::vector<WallForce> Simulation::wall_forces() {
  gpu::SimPush push = base_push(model_, layout_, variant_);
  auto f = backend_->wall_forces(push);  // one per named wall, a mesh's triangles in one sum
  std::vector<WallForce> out;
  for (const auto& name : model_.wall_group_names()) out.push_back({name, 0, 0, 0});
  for (size_t w = 0; w < f.size() && w < out.size(); ++w) {
    out[w].fx += f[w].x;
    out[w].fy += f[w].y;
    out[w].fz += f[w].z;
  }
  return out;
}

}  // namespace repose
