// A CSV table as read from a file: a header row of column names, then rows of cells.
// Cells stay text until a caller asks for a number, so a design file with a text "Type" column
// can still be fitted; the error for a bad cell then names file, line and column.
// Lines starting with '#' are comments (used for provenance notes), blank lines are skipped.
#pragma once
#include <string>
#include <vector>

namespace repose::stats {

struct Table {
  std::string source;                         // file name used in error messages
  int header_line = 0;                        // 1-based line of the header
  std::vector<std::string> columns;           // header names, trimmed
  std::vector<std::vector<std::string>> cells;  // cells[row][col], trimmed
  std::vector<int> row_lines;                 // 1-based source line of each row

  int rows() const { return static_cast<int>(cells.size()); }
  bool has_column(const std::string& name) const;
  // Index of a column; throws TableError naming the header line and the columns present.
  int column_index(const std::string& name) const;
  // Every cell of a column as a number; throws TableError at the first empty or non-numeric cell.
  std::vector<double> numeric_column(const std::string& name) const;
  double number(int row, int col) const;
  // Rows of a wholly numeric table (e.g. a table with no header written by hand).
  void add_row(std::vector<std::string> row, int line = 0);
};

Table parse_csv(const std::string& text, const std::string& source);
Table read_csv(const std::string& path);  // throws TableError when the file cannot be opened

// Strict number parsing: the whole (trimmed) text must be a finite number.
bool parse_number(const std::string& text, double& value);

// CSV text of a table; cells containing commas or quotes are quoted.
std::string format_csv(const Table& table, const std::vector<std::string>& comments = {});

}  // namespace repose::stats
