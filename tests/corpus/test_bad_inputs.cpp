// The corpus of bad inputs (tests/corpus/corpus.txt): each file, run as its line says, must exit
// with code 2 (bad input) and its message, and leave no output folder behind.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/cli_support.h"

namespace fs = std::filesystem;

namespace {

struct Entry {
  int line;
  std::string file, command, expected;
};

std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

std::vector<Entry> read_corpus(const fs::path& manifest) {
  std::vector<Entry> entries;
  std::ifstream in(manifest);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    size_t a = line.find(" | "), b = line.find(" | ", a + 3);
    REQUIRE(b != std::string::npos);
    entries.push_back({number, trim(line.substr(0, a)), trim(line.substr(a + 3, b - a - 3)), trim(line.substr(b + 3))});
  }
  return entries;
}

}  // namespace

TEST_CASE("every bad input of the corpus gives its message, exit code 2 and no output", "[corpus]") {
  const fs::path corpus = fs::path(REPOSE_SOURCE_DIR) / "tests" / "corpus";
  auto entries = read_corpus(corpus / "corpus.txt");
  CHECK(entries.size() >= 30);
  fs::path out = fs::temp_directory_path() / "repose_test_corpus_out";
  for (const Entry& e : entries) {
    fs::remove_all(out);
    // Run from the file's folder, so that messages name it as a user in that folder sees it.
    std::string file = e.file[0] == '/' ? e.file : fs::path(e.file).filename().string();
    std::string command = replace_all(replace_all(e.command, "FILE", file), "OUT", out.string());
    auto r = repose::test::run_repose(command, (corpus / fs::path(e.file).parent_path()).string());
    INFO("corpus.txt:" << e.line << ": repose " << command << "\n" << r.output);
    CHECK(r.status == 2);  // an exit (not a crash), the code of bad input
    CHECK(r.output.find(e.expected) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
}
