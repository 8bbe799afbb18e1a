#include "engine/memory_need.h"

#include <algorithm>
#include <cstdio>

#include "engine/buffer_table.h"
#include "engine/simulation.h"
#include "engine/vulkan_backend.h"
#include "walk_lanes.h"

namespace repose {

namespace {

// A frame's own arrays (radius, speed, ids, offsets: 20 B) and its appended bytes (76 B per
// particle, in a string that may double while it grows): io/vtk_writer.cpp.
constexpr double kFrameBytesPerParticle = 20 + 2 * 76;

// Bytes of the buffer table's rows of one kind, the contact list at the layout's capacity.
template <class Pick>
size_t rows_bytes(const Layout& l, Pick pick) {
  size_t bytes = 0;
  for (const BufferSpec& b : kBufferTable)
    if (!b.alias() && pick(b)) bytes += buffer_elements(b, l) * b.element_bytes;
  return bytes;
}

bool kept(const BufferSpec& b) { return b.keep == BufferKeep::State || b.keep == BufferKeep::File; }
bool constant(const BufferSpec& b) { return b.keep == BufferKeep::Constant; }

size_t device_bytes(const Layout& l) {
  size_t bytes = 0;
  for (uint32_t b = 0; b < gpu::kBindingCount; ++b) bytes += std::max<size_t>(binding_bytes(b, l), 16);
  return bytes;
}

// Bytes that turn the state between the case's order and the slots (particle_order.cpp): the
// particle order (slot -> id, id -> slot) for the run, and while converting new row starts, each
// contact's new index and a copy of one row, the largest, moving (the state moves a row at a time).
size_t order_bytes(const Layout& l) {
  auto bytes = [&](const BufferSpec& b) { return buffer_elements(b, l) * b.element_bytes; };
  size_t largest = 0;
  for (const BufferSpec& b : kBufferTable)
    if (kept(b) && (b.count == BufferCount::Particles || b.count == BufferCount::Contacts))
      largest = std::max(largest, bytes(b));
  return 2 * sizeof(uint32_t) * l.n_particles + bytes(kBufferTable[kRowRowStart]) + bytes(kBufferTable[kRowOwner]) +
         largest;
}

// The host's copies: Simulation's state, the positions alone (what `repose run`'s escape check
// downloads between readings of the state), the particle order, the constants while they are
// uploaded, the Model's arrays, the wall rows (every wall's, then a batch of the moving ones').
size_t host_bytes(const Model& m, const Layout& l, bool frames, bool reordered) {
  size_t n = m.n_particles;
  size_t model = n * (3 * sizeof(gpu::vec4) + sizeof(uint32_t)) + m.subs.size() * sizeof(gpu::SubSphere) +
                 m.bodies.size() * sizeof(gpu::Body) + m.pairs.size() * sizeof(gpu::PairParams) +
                 m.walls.size() * sizeof(ModelWall) + m.wall_grid.size() * sizeof(uint32_t);
  size_t walls = (l.n_walls + size_t(l.batch_steps) * l.n_moving_walls) * sizeof(gpu::WallState);
  size_t frame = frames ? size_t(kFrameBytesPerParticle * double(n)) : 0;
  size_t positions = n * sizeof(gpu::vec4);
  return rows_bytes(l, kept) + positions + (reordered ? order_bytes(l) : 0) + rows_bytes(l, constant) + model + walls +
         frame;
}

// A GPU's two staging buffers (one each way), as large as the largest transfer makes them.
size_t staging_host_bytes(const Layout& l) {
  size_t largest = 0;
  for (uint32_t i = 0; i < gpu::kBindingCount; ++i) largest = std::max(largest, binding_bytes(i, l));
  return 2 * vk::staging_size_for(largest);
}

// The cpu backend's scratch beside the buffer table: the walk's sorted rows (Buffers::walk_rows).
void add_cpu_scratch(MemoryNeed& need) {
  size_t bytes = gpu::walk_rows_floats(need.layout.n_particles) * sizeof(float);
  need.device_bytes += bytes;
  need.bytes_per_particle += double(bytes) / std::max(1u, need.layout.n_particles);
}

}  // namespace

MemoryNeed memory_need(const Model& m, const KernelVariant& v, uint32_t batch_steps, bool device_in_host_memory,
                       bool frames, uint32_t capacity) {
  MemoryNeed need;
  need.layout = model_layout(m, v, batch_steps, capacity ? capacity : first_contact_capacity(m));
  need.device_bytes = device_bytes(need.layout);
  bool reordered = v.reorder != 0;
  need.host_bytes = host_bytes(m, need.layout, frames, reordered);
  need.device_in_host_memory = device_in_host_memory;
  if (!device_in_host_memory) need.staging_bytes = staging_host_bytes(need.layout);
  Layout one = need.layout;
  one.capacity = 1;
  Layout none = need.layout;
  none.capacity = 0;
  double host_entry = double(rows_bytes(one, kept) - rows_bytes(none, kept));
  if (reordered && need.layout.capacity)  // its scratch row is the larger of a particle's and a contact's
    host_entry += double(order_bytes(need.layout) - order_bytes(none)) / need.layout.capacity;
  need.bytes_per_entry = host_entry + (device_in_host_memory ? double(bytes_per_contact(need.layout)) : 0.0);
  need.bytes_per_particle = (double(need.host_total() - need.staging_bytes) - need.bytes_per_entry * need.layout.capacity) /
                            std::max(1u, m.n_particles);
  return need;
}

std::string describe_memory_need(const MemoryNeed& need) {
  char text[256];
  std::snprintf(text, sizeof text, "needs %s (%u particles x %.0f B + %u list entries x %.0f B",
                format_bytes(double(need.host_total())).c_str(), need.layout.n_particles, need.bytes_per_particle,
                need.layout.capacity, need.bytes_per_entry);
  std::string line = text;
  if (need.staging_bytes) line += " + " + format_bytes(double(need.staging_bytes)) + " of staging";
  line += ")";
  if (!need.device_in_host_memory) line += " on the host, " + format_bytes(double(need.device_bytes)) + " on the device";
  if (need.available.bytes) line += ", " + format_bytes(double(need.available.bytes)) + " available";
  return line;
}

void check_memory_fits(MemoryNeed& need, const vk::DeviceInfo* device) {
  if (device) {
    std::string problem = vulkan_fit_problem(*device, need.layout);
    if (!problem.empty()) throw MemoryShortfall(problem);
  }
  const AvailableMemory& room = need.available = available_memory();
  if (room.bytes && need.host_total() > room.bytes)
    throw MemoryShortfall("needs " + format_bytes(double(need.host_total())) + ", " + format_bytes(double(room.bytes)) +
                          " available (" + room.limited_by + ")");
}

MemoryNeed check_run_memory(const Model& m, const KernelVariant& v, uint32_t batch_steps, const std::string& backend,
                            int device, bool frames, uint32_t capacity) {
  if (backend != "vulkan") {
    MemoryNeed need = memory_need(m, v, batch_steps, true, frames, capacity);
    add_cpu_scratch(need);
    check_memory_fits(need, nullptr);
    return need;
  }
  std::vector<vk::DeviceInfo> devices = vk::Context::list_devices();
  int index = device >= 0 ? device : vk::Context::default_device_index(devices);
  if (index < 0 || size_t(index) >= devices.size())
    throw std::runtime_error("no Vulkan device [" + std::to_string(index) + "] (see `repose devices`)");
  const vk::DeviceInfo& d = devices[size_t(index)];
  // lavapipe's and an integrated GPU's memory is the host's.
  MemoryNeed need = memory_need(m, v, batch_steps, d.type == "cpu" || d.type == "integrated-gpu", frames, capacity);
  check_memory_fits(need, &d);
  return need;
}

}  // namespace repose
