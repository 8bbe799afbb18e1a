#include "io/vtk_writer.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "util/atomic_file.h"

namespace repose {

namespace {

// Legacy VTK binary is big-endian.
template <class T>
void put_be(std::ostream& out, T value) {
  static_assert(sizeof(T) == 4);
  uint32_t u = std::bit_cast<uint32_t>(value);
  if constexpr (std::endian::native == std::endian::little) u = __builtin_bswap32(u);
  out.write(reinterpret_cast<const char*>(&u), 4);
}

void vectors(std::ostream& out, const char* name, const std::vector<gpu::vec4>& v) {
  out << "VECTORS " << name << " float\n";
  for (const auto& a : v) { put_be(out, a.x); put_be(out, a.y); put_be(out, a.z); }
  out << "\n";
}

}  // namespace

void write_vtk_frame(const std::string& path, const HostState& s, double time) {
  write_file_atomically(path, [&](std::ostream& out) {
    size_t n = s.pos.size();
    out << "# vtk DataFile Version 3.0\nRepose particles t=" << time << "\nBINARY\n"
        << "DATASET POLYDATA\nFIELD FieldData 1\nTIME 1 1 double\n";
    uint64_t tb = std::bit_cast<uint64_t>(time);
    if constexpr (std::endian::native == std::endian::little) tb = __builtin_bswap64(tb);
    out.write(reinterpret_cast<const char*>(&tb), 8);
    out << "\nPOINTS " << n << " float\n";
    for (const auto& p : s.pos) { put_be(out, p.x); put_be(out, p.y); put_be(out, p.z); }
    out << "\nVERTICES " << n << " " << 2 * n << "\n";
    for (size_t i = 0; i < n; ++i) { put_be(out, int32_t(1)); put_be(out, int32_t(i)); }
    out << "\nPOINT_DATA " << n << "\nSCALARS radius float 1\nLOOKUP_TABLE default\n";
    for (const auto& p : s.pos) put_be(out, p.w);
    out << "\nSCALARS speed float 1\nLOOKUP_TABLE default\n";
    for (const auto& v : s.vel) put_be(out, std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
    out << "\nSCALARS id int 1\nLOOKUP_TABLE default\n";
    for (size_t i = 0; i < n; ++i) put_be(out, int32_t(i));
    out << "\n";
    vectors(out, "velocity", s.vel);
    vectors(out, "angular_velocity", s.omega);
    vectors(out, "force", s.force);
  }, true);
}

}  // namespace repose
