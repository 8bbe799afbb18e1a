#include "case/case_override.h"

#include <algorithm>
#include <cctype>

#include "case/case_error.h"
#include "case/spelling.h"

namespace repose {
namespace {

bool is_index(const std::string& segment) {
  return !segment.empty() &&
         std::all_of(segment.begin(), segment.end(), [](unsigned char c) { return std::isdigit(c); });
}

std::vector<std::string> split_key(const std::string& dotted_key) {
  std::vector<std::string> segments;
  size_t start = 0;
  while (true) {
    size_t dot = dotted_key.find('.', start);
    segments.push_back(dotted_key.substr(start, dot - start));
    if (dot == std::string::npos) return segments;
    start = dot + 1;
  }
}

std::string string_at(const toml::table& table, std::string_view key) {
  const toml::node* node = table.get(key);
  return node && node->is_string() ? node->as_string()->get() : std::string();
}

// Does this [[material]], [[wall]] or [[interaction]] answer to `segment`?
bool answers_to(const toml::table& element, const std::string& segment) {
  std::string name = string_at(element, "name");
  if (!name.empty()) return name == segment;
  if (!string_at(element, "preset").empty() && !element.contains("materials"))
    return string_at(element, "preset") == segment;  // an unnamed material takes its preset's name
  size_t slash = segment.find('/');
  const toml::array* pair = element.get_as<toml::array>("materials");
  if (slash == std::string::npos || !pair || pair->size() != 2) return false;
  std::string a = segment.substr(0, slash), b = segment.substr(slash + 1);
  std::string first = pair->get(0)->value_or(std::string()), second = pair->get(1)->value_or(std::string());
  return (first == a && second == b) || (first == b && second == a);
}

std::vector<std::string> names_in(const toml::array& array) {
  std::vector<std::string> names;
  for (const toml::node& node : array) {
    if (!node.is_table()) continue;
    const toml::table& element = *node.as_table();
    std::string name = string_at(element, "name");
    if (name.empty()) name = string_at(element, "preset");
    if (const toml::array* pair = element.get_as<toml::array>("materials"); pair && pair->size() == 2)
      name = pair->get(0)->value_or(std::string()) + "/" + pair->get(1)->value_or(std::string());
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

// The value an override's text stands for: a TOML value, else the text itself as a string.
toml::table parse_value(const std::string& value_text) {
  try {
    toml::table holder = toml::parse("v = " + value_text);
    if (holder.size() == 1 && holder.contains("v")) return holder;
  } catch (const toml::parse_error&) {
  }
  toml::table holder;
  holder.insert("v", value_text);
  return holder;
}

}  // namespace

void apply_override(toml::table& root, const std::string& dotted_key, const std::string& value_text,
                    const std::string& file) {
  SourceRef where{file, "override " + dotted_key + "=" + value_text, 0};
  auto fail = [&](const std::string& problem) { throw CaseError(where, problem); };

  std::vector<std::string> segments = split_key(dotted_key);
  for (const std::string& segment : segments)
    if (segment.empty()) fail("the key has an empty part (two dots, or a dot at an end)");
  // An empty value removes the key (or the array element): the way to trade dt for
  // rayleigh_fraction, or to drop a wall, from the command line.
  bool remove = value_text.find_first_not_of(" \t") == std::string::npos;
  toml::table holder = parse_value(remove ? "0" : value_text);
  toml::node& value = *holder.get("v");

  toml::node* current = &root;
  std::string path;  // how far we got, for messages: "material[2]"
  for (size_t i = 0; i < segments.size(); ++i) {
    const std::string& segment = segments[i];
    bool last = i + 1 == segments.size();
    if (toml::table* table = current->as_table()) {
      std::string here = path.empty() ? segment : path + "." + segment;
      if (last && remove) {
        if (!table->contains(segment)) fail("there is no " + here + " to remove");
        table->erase(segment);
        return;
      }
      if (last) {
        // A copy, not a move: copies drop the source position, which belongs to the override's
        // one-line parse and would otherwise pass for a line of the case file.
        value.visit([&](const auto& node) { table->insert_or_assign(segment, node); });
        return;
      }
      if (!table->contains(segment)) {
        if (is_index(segments[i + 1])) fail("there is no " + here + " to pick element " + segments[i + 1] + " of");
        table->insert(segment, toml::table{});
      }
      current = table->get(segment);
      path = here;
    } else if (toml::array* array = current->as_array()) {
      size_t index = 0;
      if (is_index(segment)) {
        index = std::stoul(segment);
        if (index >= array->size())
          fail("there is no " + path + "[" + segment + "]: it has " + std::to_string(array->size()) +
               (array->size() == 1 ? " element" : " elements"));
      } else {
        std::vector<size_t> matches;
        for (size_t k = 0; k < array->size(); ++k)
          if (const toml::table* element = array->get(k)->as_table(); element && answers_to(*element, segment))
            matches.push_back(k);
        if (matches.empty()) fail("no " + path + " is named '" + segment + "'" + did_you_mean(segment, names_in(*array)));
        if (matches.size() > 1) fail("more than one " + path + " is named '" + segment + "': use its index");
        index = matches[0];
      }
      if (last && remove) {
        array->erase(array->cbegin() + std::ptrdiff_t(index));
        return;
      }
      if (last) {
        value.visit([&](const auto& node) { array->replace(array->cbegin() + std::ptrdiff_t(index), node); });
        return;
      }
      current = array->get(index);
      path += "[" + std::to_string(index) + "]";
    } else {
      fail(path + " is a single value, it has no '" + segment + "' inside");
    }
  }
}

}  // namespace repose
