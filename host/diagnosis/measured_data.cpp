#include "diagnosis/measured_data.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "case/case_error.h"
#include "util/input_file.h"
#include "experiments/registry.h"

namespace repose {

namespace {

namespace fs = std::filesystem;

struct Cell {
  std::string text;
  int column = 0;  // 1-based character column where the cell starts
};

// One CSV line into cells (RFC 4180 quotes, no embedded newlines).
std::vector<Cell> split_csv(const std::string& line, const std::string& file, int line_no) {
  std::vector<Cell> cells;
  Cell cur{"", 1};
  bool quoted = false, was_quoted = false;
  for (size_t k = 0; k < line.size(); ++k) {
    char c = line[k];
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') { cur.text += '"'; ++k; }
      else if (c == '"') quoted = false;
      else cur.text += c;
    } else if (c == '"' && cur.text.empty() && !was_quoted) {
      quoted = was_quoted = true;
    } else if (c == ',') {
      cells.push_back(cur);
      cur = {"", int(k) + 2};
      was_quoted = false;
    } else if (c != '\r') {
      cur.text += c;
    }
  }
  if (quoted) throw DataError(file + ":" + std::to_string(line_no) + ":" + std::to_string(cur.column) +
                              ": unterminated quoted cell");
  cells.push_back(cur);
  for (auto& cell : cells) {  // spreadsheets pad cells with spaces
    auto b = cell.text.find_first_not_of(" \t"), e = cell.text.find_last_not_of(" \t");
    cell.text = b == std::string::npos ? "" : cell.text.substr(b, e - b + 1);
  }
  return cells;
}

[[noreturn]] void fail(const std::string& file, int line, const Cell& cell, const std::string& column,
                       const std::string& what) {
  throw DataError(file + ":" + std::to_string(line) + ":" + std::to_string(cell.column) + ": column '" +
                  column + "': " + what);
}

double number(const std::string& file, int line, const Cell& cell, const std::string& column) {
  try {
    size_t used = 0;
    double v = std::stod(cell.text, &used);
    if (used == cell.text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  fail(file, line, cell, column, "'" + cell.text + "' is not a number");
}

}  // namespace

const std::vector<MeasureInfo>& known_measures() {
  static const std::vector<MeasureInfo> measures = diagnosed_measures();
  return measures;
}

std::string unit_of(const std::string& measure) {
  for (const auto& m : known_measures())
    if (measure == m.name) return m.unit;
  return "";
}

namespace {

// The header of a measured-data file: its cells, line and the columns by name.
struct Columns {
  std::vector<Cell> header;
  int line = 0;
  std::map<std::string, size_t> col;
  std::vector<std::pair<std::string, size_t>> set_cols;  // set:KEY columns
};

// The first non-blank line as the header; errors name the file, line and column.
Columns read_header(std::istream& in, const std::string& path, int& line_no) {
  Columns c;
  std::string line;
  while (c.header.empty() && std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") != std::string::npos) c.header = split_csv(line, path, line_no);
  }
  if (c.header.empty()) throw DataError(path + ": the file is empty (expected a header line)");
  c.line = line_no;
  static const std::vector<std::string> fixed = {"case", "measure", "value", "replicate", "sigma", "t"};
  for (size_t k = 0; k < c.header.size(); ++k) {
    const std::string& name = c.header[k].text;
    if (name.rfind("set:", 0) == 0 && name.size() > 4) c.set_cols.push_back({name.substr(4), k});
    else if (std::find(fixed.begin(), fixed.end(), name) != fixed.end()) c.col[name] = k;
    else fail(path, c.line, c.header[k], name,
              "unknown column (expected case, set:KEY..., measure, value, replicate, sigma, t)");
  }
  for (const char* required : {"case", "measure", "value", "replicate"})
    if (!c.col.count(required))
      throw DataError(path + ":" + std::to_string(c.line) + ": missing column '" + required + "'");
  return c;
}

// The row's case must load with its overrides (cached by case and overrides); its errors become
// errors of this row, at the set: column they name.
const CaseSpec& case_of_row(const Measurement& m, const std::vector<Cell>& cells, const Columns& c,
                            const std::string& path, std::map<std::string, CaseSpec>& loaded) {
  std::string key = m.case_path;
  for (const auto& s : m.sets) key += "|" + s.key + "=" + s.value;
  if (!loaded.count(key)) {
    try {
      loaded[key] = load_case(m.case_path, m.sets);
    } catch (const CaseError& e) {
      size_t k = c.set_cols.empty() ? c.col.at("case") : c.set_cols.front().second;
      for (const auto& [name, idx] : c.set_cols)
        if (std::string(e.what()).find(name) != std::string::npos) k = idx;
      fail(path, m.line, cells[k], c.header[k].text, e.what());
    }
  }
  return loaded[key];
}

// One data row, checked: its case and overrides, a known measure, numbers where numbers belong,
// and a value the measure and the case's experiment can have.
Measurement read_row(const std::vector<Cell>& cells, int line_no, const Columns& c, const std::string& path,
                     const fs::path& base, std::map<std::string, CaseSpec>& loaded) {
  auto cell = [&](const std::string& name) -> const Cell& { return cells[c.col.at(name)]; };
  Measurement m;
  m.line = line_no;
  m.case_path = (base / cell("case").text).lexically_normal().string();
  if (cell("case").text.empty() || !fs::exists(m.case_path))
    fail(path, line_no, cell("case"), "case", "no case file '" + cell("case").text + "' (relative to the CSV)");
  for (const auto& [key, k] : c.set_cols)
    if (!cells[k].text.empty()) m.sets.push_back({key, cells[k].text});
  m.measure = cell("measure").text;
  auto info = std::find_if(known_measures().begin(), known_measures().end(),
                           [&](const MeasureInfo& i) { return m.measure == i.name; });
  if (info == known_measures().end()) {
    std::string names;
    for (const auto& i : known_measures()) names += (names.empty() ? "" : ", ") + i.name;
    fail(path, line_no, cell("measure"), "measure", "unknown measure '" + m.measure + "' (" + names + ")");
  }
  m.value = number(path, line_no, cell("value"), "value");
  double rep = number(path, line_no, cell("replicate"), "replicate");
  if (rep != std::floor(rep) || rep < 0) fail(path, line_no, cell("replicate"), "replicate", "must be a whole number >= 0");
  m.replicate = int(rep);
  if (c.col.count("sigma") && !cell("sigma").text.empty()) {
    m.sigma = number(path, line_no, cell("sigma"), "sigma");
    if (!(*m.sigma > 0)) fail(path, line_no, cell("sigma"), "sigma", "must be greater than 0");
  }
  if (c.col.count("t") && !cell("t").text.empty()) m.t = number(path, line_no, cell("t"), "t");
  if (info->series && !m.t) fail(path, line_no, cell("measure"), "measure", "'" + m.measure + "' is a time series: give t");

  const CaseSpec& spec = case_of_row(m, cells, c, path, loaded);
  if (const Experiment* e = experiment_for(spec)) {
    std::string problem = e->implausible(*info, m.value, spec);
    if (!problem.empty()) fail(path, line_no, cell("value"), "value", problem);
  }
  if (info->unit == "m" && !info->series && m.value < 0)
    fail(path, line_no, cell("value"), "value", "a " + m.measure + " cannot be negative: lengths are measured from the "
                                                "plate or floor upwards, in m");
  if (info->unit == "deg" && (m.value <= 0 || m.value >= 90))
    fail(path, line_no, cell("value"), "value", "an angle in degrees must lie in (0, 90)");
  return m;
}

}  // namespace

MeasuredData read_measured_data(const std::string& path) {
  if (auto why = why_not_input_file(path, 256u << 20); !why.empty()) throw DataError(path + ": " + why);
  std::ifstream in(path);
  if (!in) throw DataError(path + ": cannot read the measured-data file");
  MeasuredData data;
  data.path = path;
  int line_no = 0;
  Columns c = read_header(in, path, line_no);
  fs::path base = fs::path(path).parent_path();
  std::map<std::string, CaseSpec> loaded;  // case + overrides -> checked case (units check)
  std::string line;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r,") == std::string::npos) continue;
    auto cells = split_csv(line, path, line_no);
    if (cells.size() != c.header.size())
      throw DataError(path + ":" + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                      " cells, the header has " + std::to_string(c.header.size()));
    data.rows.push_back(read_row(cells, line_no, c, path, base, loaded));
  }
  if (data.rows.empty()) throw DataError(path + ": no data rows after the header");
  return data;
}

}  // namespace repose
