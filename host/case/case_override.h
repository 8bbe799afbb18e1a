// Overrides: "set this key of the case to this value" before the case is checked, as a
// diagnosis table's `set:KEY` columns or `repose run --set KEY=VALUE` need.
//
// Key scheme (docs/case-format.md): dotted path through the document.
//   simulation.end_time          a key of a table
//   simulation.gravity.2         an element of an array of values, by 0-based index
//   material.0.density           an element of an array of tables by 0-based index ...
//   material.cabbage.density     ... or by its `name` (a material without a name: its preset)
//   wall.floor.material          walls by `name` as well
//   interaction.cabbage/steel.restitution   an interaction by its two materials, either order
//   fill.0.box.max               keys of inline tables continue the path
// Tables on the way that do not exist yet are created ("neighbour.skin" without [neighbour]).
// The value is TOML ("0.5", "[0, 0, -9.8]", "\"clip\"", "{ velocity = [0, 0, 1] }"); text that
// is not a TOML value is taken as a bare string, so `clip` works as well as `"clip"`. An empty
// value removes the key or array element: "simulation.dt=" then "simulation.rayleigh_fraction=0.3"
// trades one time step form for the other; "wall.gate=" drops a wall.
#pragma once
#include <string>

#include <toml++/toml.h>

namespace repose {

// Sets root[dotted_key] = value_text. Throws CaseError (naming `file`, the key and the override)
// when the path cannot be followed: an index out of range, no element with that name, a value
// where a table was expected.
void apply_override(toml::table& root, const std::string& dotted_key, const std::string& value_text,
                    const std::string& file = "");

}  // namespace repose
