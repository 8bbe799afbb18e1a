// Sphere lists as CSV: one sphere per row, columns found by header name (x, y, z, radius; "r" is
// accepted for radius; other columns are ignored), metres. Used for clump templates and for the
// settled heaps that the angle measurement reads.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "geometry/sphere.h"

namespace repose {

// Reads a sphere CSV. Throws InputError naming file, line and column for: a missing or unreadable
// file, an empty file, a header without x/y/z/radius, a row with the wrong number of fields, a
// field that is not a finite number, a radius that is not positive, and a file with no rows.
// Blank lines and lines starting with '#' are skipped.
std::vector<Sphere> read_sphere_csv(const std::string& path);

// The same from a stream; source_name is used in error messages.
std::vector<Sphere> parse_sphere_csv(std::istream& in, const std::string& source_name);

// Writes "x,y,z,radius" and one row per sphere with the shortest text that reads back to the
// same double, so a written template round-trips bit for bit. Throws std::runtime_error on I/O
// failure.
void write_sphere_csv(const std::string& path, const std::vector<Sphere>& spheres);
void write_sphere_csv(std::ostream& out, const std::vector<Sphere>& spheres);

}  // namespace repose
