#include "stats/csv_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "stats/errors.h"
#include "util/input_file.h"

namespace repose::stats {

namespace {

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// Splits one line into fields, honouring double quotes ("" inside quotes is a quote).
// Returns the 1-based column where each field starts so errors can point at the cell.
std::vector<std::string> split_line(const std::string& line, const std::string& source, int line_no,
                                    std::vector<int>& starts) {
  std::vector<std::string> fields;
  std::string cur;
  bool quoted = false;
  int start = 1;
  for (size_t i = 0; i < line.size(); ++i) {
    char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          cur += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        cur += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(trim(cur));
      starts.push_back(start);
      cur.clear();
      start = static_cast<int>(i) + 2;
    } else {
      cur += c;
    }
  }
  if (quoted) throw TableError(source, line_no, start, "unterminated quoted cell");
  fields.push_back(trim(cur));
  starts.push_back(start);
  return fields;
}

}  // namespace

bool parse_number(const std::string& text, double& value) {
  std::string t = trim(text);
  if (t.empty()) return false;
  errno = 0;
  char* end = nullptr;
  double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return false;
  value = v;
  return true;
}

bool Table::has_column(const std::string& name) const {
  for (const auto& c : columns)
    if (c == name) return true;
  return false;
}

int Table::column_index(const std::string& name) const {
  for (size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return static_cast<int>(i);
  std::string present;
  for (const auto& c : columns) present += (present.empty() ? "" : ", ") + c;
  throw TableError(source, header_line, 0,
                   "no column named '" + name + "' (columns: " + present + ")");
}

double Table::number(int row, int col) const {
  const std::string& cell = cells.at(row).at(col);
  double v = 0;
  if (cell.empty())
    throw TableError(source, row_lines[row], col + 1,
                     "empty cell in column '" + columns[col] + "'");
  if (!parse_number(cell, v))
    throw TableError(source, row_lines[row], col + 1,
                     "'" + cell + "' in column '" + columns[col] + "' is not a number");
  return v;
}

std::vector<double> Table::numeric_column(const std::string& name) const {
  int col = column_index(name);
  std::vector<double> out;
  out.reserve(cells.size());
  for (int r = 0; r < rows(); ++r) out.push_back(number(r, col));
  return out;
}

void Table::add_row(std::vector<std::string> row, int line) {
  cells.push_back(std::move(row));
  row_lines.push_back(line);
}

Table parse_csv(const std::string& text, const std::string& source) {
  Table t;
  t.source = source;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    std::vector<int> starts;
    auto fields = split_line(line, source, line_no, starts);
    if (t.columns.empty()) {
      for (size_t i = 0; i < fields.size(); ++i) {
        if (fields[i].empty())
          throw TableError(source, line_no, starts[i], "empty column name in header");
        for (size_t j = 0; j < i; ++j)
          if (fields[j] == fields[i])
            throw TableError(source, line_no, starts[i], "duplicate column '" + fields[i] + "'");
      }
      t.columns = fields;
      t.header_line = line_no;
      continue;
    }
    if (fields.size() != t.columns.size())
      throw TableError(source, line_no, 0,
                       "row has " + std::to_string(fields.size()) + " cells, header has " +
                           std::to_string(t.columns.size()));
    t.add_row(std::move(fields), line_no);
  }
  if (t.columns.empty()) throw TableError(source, 0, 0, "no header row (file is empty)");
  return t;
}

Table read_csv(const std::string& path) {
  if (auto why = why_not_input_file(path, 256u << 20); !why.empty()) throw TableError(path, 0, 0, why);
  std::ifstream f(path, std::ios::binary);
  if (!f) throw TableError(path, 0, 0, "cannot open file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return parse_csv(ss.str(), path);
}

std::string format_csv(const Table& table, const std::vector<std::string>& comments) {
  auto cell = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  std::string out;
  for (const auto& c : comments) out += "# " + c + "\n";
  for (size_t i = 0; i < table.columns.size(); ++i)
    out.append(i ? "," : "").append(cell(table.columns[i]));
  out += "\n";
  for (const auto& row : table.cells) {
    for (size_t i = 0; i < row.size(); ++i) out.append(i ? "," : "").append(cell(row[i]));
    out += "\n";
  }
  return out;
}

}  // namespace repose::stats
