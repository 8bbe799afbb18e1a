// Drives a backend through a case: batches of steps in one submit, device-decided list
// rebuilds, a retry with a larger contact list when one overflows (nothing of the batch is
// kept), and the host copy of the state for output, downloaded only when something reads it
// (a few control words come back after every batch). The device stores the particles in cell
// order (ParticleOrder), renewed between batches as they move; the host's state is by global id
// whenever anyone reads it, so nothing outside sees the slots.
#pragma once
#include <bitset>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/backend.h"
#include "engine/kinetic_energy.h"
#include "engine/model.h"
#include "engine/particle_order.h"
#include "engine/reorder_schedule.h"
#include "engine/run_profile.h"
#include "engine/step_program.h"

namespace repose {

struct WallForce {
  std::string name;
  double fx = 0, fy = 0, fz = 0;
};

// What a wall took between two readings: the impulse (the integral of its force over the steps,
// N s) and the largest force at one step (N; for a mesh, of all its triangles together).
struct WallImpulse {
  std::string name;
  double jx = 0, jy = 0, jz = 0;
  double peak = 0;
};

// The contact-list capacity a simulation starts with: room for ~6 contacts per particle plus
// walls (a settled bed of equal spheres holds ~4.6 per particle with the default skin); it grows
// on overflow.
uint32_t first_contact_capacity(const Model& m);
// The capacity a list grows to when it needs `needed` entries: a quarter more, and some.
uint32_t grown_capacity(uint32_t needed);
// The capacity a simulation of m holds after restoring state s (Simulation::restore).
uint32_t restored_capacity(const Model& m, const HostState& s);

class Simulation {
 public:
  // first_capacity: contact-list entries to start with (0: first_contact_capacity);
  // the list grows on overflow, so it only changes how often that happens, never the results.
  Simulation(Model model, std::unique_ptr<Backend> backend, KernelVariant variant = {},
             uint32_t max_batch_steps = 200, uint32_t first_capacity = 0);

  // Runs `steps` more steps; `on_batch` (optional) is called after every batch.
  void advance(uint64_t steps, const std::function<void(const Simulation&)>& on_batch = {});

  const Model& model() const { return model_; }
  // The state by global id after the last batch. It is downloaded here, on its first reading
  // after a batch, in the device's slots, and turned to global ids: a batch nobody reads is never
  // downloaded. The reference stays valid, and by global id, until the next advance(),
  // set_state(), restore() or store_in_order() (each of which may leave it in slots again).
  const HostState& state() const;
  // One row of every particle (&HostState::pos, vel, omega, ...) or of every body (bodies) after
  // the last batch, in the order the device stores them, downloaded alone (16 B per particle for a
  // vec4 row) unless the whole state is here already: for checks whose answer does not depend on
  // the order (any particle out of the domain? the largest kinetic energy?), which would otherwise
  // download the contact list and turn it to global ids. Valid until the next advance() or state().
  template <class T>
  const std::vector<T>& rows_in_any_order(std::vector<T> HostState::*row) const;
  uint64_t step() const { return step_; }
  double time() const { return double(step_) * model_.dt; }
  uint32_t contacts() const { return control_.empty() ? 0 : control_[gpu::kCtlContacts]; }
  uint32_t rebuilds() const { return control_.empty() ? 0 : control_[gpu::kCtlRebuildCount]; }
  uint32_t capacity() const { return layout_.capacity; }
  const Layout& layout() const { return layout_; }
  const KernelVariant& variant() const { return variant_; }
  uint32_t retries() const { return retries_; }
  Backend& backend() { return *backend_; }
  const Backend& backend() const { return *backend_; }
  EnergySummary kinetic_energy() const;
  // Force of the particles on each named wall (a mesh's triangles summed), from the last step's
  // contacts; names as Model::wall_group_names().
  std::vector<WallForce> wall_forces();
  // From now on every step also sums each wall's force and keeps its peak (one more kernel per
  // step: opt-in); take_wall_impulses() returns them per named wall since the previous call (or
  // since this one) and starts anew.
  void sum_wall_forces();
  std::vector<WallImpulse> take_wall_impulses();
  bool sums_wall_forces() const { return summing_walls_; }
  // The last step's force on the owner i of each contact-list entry (state().partner, row_start).
  std::vector<gpu::vec4> contact_forces();
  // Called after every batch of every advance() from now on, after its on_batch (frames written
  // as an experiment goes); empty: none.
  void set_observer(std::function<void(Simulation&)> observer) { observer_ = std::move(observer); }
  // Replaces particle velocities etc. on the device (used by experiment drivers and tests).
  void set_state(const HostState& s);
  // Continues from a state written by write_state_file after `step` steps of this same model:
  // the following steps give the bytes of a run that never stopped. Throws std::invalid_argument
  // when the state does not fit the model (particle, body or rolling-spring counts).
  void restore(const HostState& s, uint64_t step);
  // From now on the device stores global id order.id_of[s] in slot s (between batches; tests
  // scramble the order with it). The bytes of the run do not change.
  void store_in_order(ParticleOrder order);
  const ParticleOrder& particle_order() const { return order_; }
  // With profiling on, advance() also times every kernel (a clock read per dispatch on the cpu
  // backend, timestamp queries on Vulkan). The profile always counts steps, rebuilds, contacts
  // and the wall time inside advance(); take_profile() returns it and starts a new one.
  void set_profiling(bool on) { profiling_ = on; }
  RunProfile take_profile();

 private:
  void allocate(uint32_t capacity);
  void upload();
  void download() const;
  // The particles in cell order again, from the state as the device stores it (a reorder).
  void renew_cell_order();
  // From now on the device stores the particles under `order`: the constants and state_ (by
  // global id, or in the new order's slots already) uploaded anew.
  void use_order(ParticleOrder order);
  void grow(uint32_t needed);
  void replay_unread(std::vector<uint32_t> batches);
  void upload_walls(uint64_t first, double offset, uint32_t steps);
  // The walls of steps [first, first + steps) uploaded and the batch run; timed when profiling.
  void run_batch(uint64_t first, uint32_t steps);
  // Where profiling puts the time of a transfer (nullptr: not profiling).
  double* transfer_clock() { return profiling_ ? &profile_.transfer_seconds : nullptr; }
  // Where in a step the walls' rows are taken: velocity Verlet evaluates forces at its end (1),
  // symplectic Euler at its start (0).
  double wall_time_offset() const { return model_.integrator == Integrator::VelocityVerlet ? 1.0 : 0.0; }
  std::vector<Dispatch> batch_program(uint64_t first, uint32_t steps) const;
  // The dispatches a run may make (the setup's, a step's with the walls still and moving, the
  // walls' sums), for the backend to prepare at once (Backend::prepare).
  std::vector<Dispatch> dispatches_of_run() const;
  // wall_reduce over the named walls, with the run's push constants (batch_program sets its sums).
  Dispatch wall_sums_dispatch() const;
  void add_batch_wall_sums();
  Model model_;
  std::unique_ptr<Backend> backend_;
  KernelVariant variant_;
  Layout layout_;
  // The state of step step_ - (the unread batches' steps): by global id, or by slot of order_
  // while state_in_slots_ (a download not yet read, or an upload). state() downloads and turns
  // it, which a reader cannot see: hence mutable.
  mutable HostState state_;
  mutable bool state_in_slots_ = false;
  // The steps of each batch run since state_ was downloaded or uploaded (empty: state_ is the
  // device's state). An overflow uploads state_ into the larger list and runs them again.
  mutable std::vector<uint32_t> unread_batches_;
  // A run nobody reads still downloads every so many batches, so that an overflow late in a long
  // run replays at most these (~1,600 steps at 50 per batch) at 1/32 of the downloads it saves.
  static constexpr size_t kMostUnreadBatches = 32;
  std::vector<uint32_t> control_;  // the device's control words after the last batch or upload
  // Rows downloaded alone after the last batch (in slots; rows_in_any_order), and which are.
  mutable HostState rows_;
  mutable std::bitset<gpu::kBindingCount> rows_current_;
  ParticleOrder order_;
  bool stored_by_id_ = true;          // order_ is the identity
  ReorderSchedule reorder_;
  uint64_t step_ = 0;
  uint32_t retries_ = 0;
  bool profiling_ = false;
  RunProfile profile_;
  std::function<void(Simulation&)> observer_;
  bool summing_walls_ = false;
  std::vector<double> wall_sum_, wall_peak_;  // per named wall: sum x, y, z (N, steps) and peak^2 (N^2)
};

}  // namespace repose
