// Reading back the XML VTK files Repose writes (io/vtk_writer.h), as ParaView would: a .vtp's
// header, and its raw appended block where each DataArray's offset points at a UInt64 byte count
// equal to what the piece's counts, the array's type and its components need, the blocks one after
// another to the end; a .pvd's list of frames. Shared by the test folders that write frames.
#pragma once
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace repose::test {

inline std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

inline size_t piece_count(const std::string& head, const char* what) {
  std::smatch m;
  std::string pattern = std::string(what) + "=\"(\\d+)\"";
  return std::regex_search(head, m, std::regex(pattern)) ? std::stoul(m[1]) : 0;
}

// Checks the file and that it holds the arrays `names`; returns the piece's NumberOfLines.
inline size_t check_vtp(const std::filesystem::path& file, const std::vector<std::string>& names) {
  INFO(file.string());
  std::string text = file_text(file);
  REQUIRE(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                     "header_type=\"UInt64\">",
                     0) == 0);
  size_t data = text.find("<AppendedData encoding=\"raw\">");
  REQUIRE(data != std::string::npos);
  data = text.find('_', data) + 1;
  std::string head = text.substr(0, data);
  size_t points = piece_count(head, "NumberOfPoints");
  size_t cells = piece_count(head, "NumberOfLines") + piece_count(head, "NumberOfPolys");
  for (const auto& name : names) CHECK(head.find("Name=\"" + name + "\"") != std::string::npos);
  size_t cell_data = head.find("<CellData"), cell_data_end = head.find("</CellData>");
  std::regex array("<DataArray type=\"(\\w+)\"( Name=\"(\\w+)\")?( NumberOfComponents=\"(\\d)\")? format=\"appended\" offset=\"(\\d+)\"/>");
  std::vector<std::pair<size_t, size_t>> blocks;  // (offset, length with its count)
  int arrays = 0;
  for (auto it = std::sregex_iterator(head.begin(), head.end(), array); it != std::sregex_iterator(); ++it, ++arrays) {
    size_t offset = std::stoul((*it)[6]);
    INFO("array '" << (*it)[3] << "' at " << offset);
    uint64_t bytes = 0;
    REQUIRE(data + offset + 8 <= text.size());
    std::memcpy(&bytes, text.data() + data + offset, 8);
    REQUIRE(data + offset + 8 + bytes <= text.size());
    blocks.push_back({offset, 8 + bytes});
    std::string name = (*it)[3];
    size_t components = (*it)[5].matched ? std::stoul((*it)[5]) : 1, size = (*it)[1] == "Float64" ? 8 : 4;
    bool per_cell = cell_data != std::string::npos && size_t(it->position()) > cell_data &&
                    size_t(it->position()) < cell_data_end;
    // Offsets: one per cell of the section that holds them (Verts, Lines or Polys).
    std::string before = head.substr(0, size_t(it->position()));
    size_t verts = before.rfind("<Verts>"), lines = before.rfind("<Lines>"), polys = before.rfind("<Polys>");
    size_t section = std::max({verts == std::string::npos ? 0 : verts, lines == std::string::npos ? 0 : lines,
                               polys == std::string::npos ? 0 : polys});
    const char* count = section == verts ? "NumberOfVerts" : section == lines ? "NumberOfLines" : "NumberOfPolys";
    if (name == "offsets") CHECK(bytes == piece_count(head, count) * 4);
    else if (name == "connectivity") CHECK(bytes % 4 == 0);
    else CHECK(bytes == (per_cell ? cells : points) * components * size);
  }
  CHECK(arrays >= 2);
  // The blocks, by offset, follow one another from the start of the data to its end.
  std::sort(blocks.begin(), blocks.end());
  size_t end = 0;
  for (const auto& [offset, length] : blocks) {
    CHECK(offset == end);
    end = offset + length;
  }
  CHECK(text.compare(data + end, std::string::npos, "\n  </AppendedData>\n</VTKFile>\n") == 0);
  return piece_count(head, "NumberOfLines");
}

// The files a .pvd lists, in order.
inline std::vector<std::string> pvd_files(const std::filesystem::path& pvd) {
  std::string text = file_text(pvd);
  std::vector<std::string> files;
  std::regex entry("<DataSet timestep=\"[^\"]+\" part=\"0\" file=\"([^\"]+)\"/>");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
    files.push_back((*it)[1]);
  return files;
}

}  // namespace repose::test
