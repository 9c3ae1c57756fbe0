// docs/API_COVERAGE.md lists every method of ID3D11Device and
// ID3D11DeviceContext (Direct3D 11.0) with its status and the tests that cover
// it. These tests hold it to rhi/include/rhi/rhi.h and to the test sources: a
// method declared without a row, a row naming a method that is not declared
// (or "not yet" for one that is), and a test name that no test defines all fail.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

const fs::path kRoot = PROJECT_SOURCE_ROOT;

// The methods a class of rhi.h declares: `virtual ... Name(` lines, and the
// methods of in-class parameterised macros (`Prefix##Name(`) expanded for
// each invocation (`MACRO(VS)`).
std::set<std::string> DeclaredMethods(const std::string& header, const std::string& classHead) {
  const size_t begin = header.find(classHead);
  if (begin == std::string::npos) return {};
  const size_t end = header.find("\n};", begin);
  std::istringstream body(header.substr(begin, end - begin));
  const std::regex virtualMethod(R"(virtual\s[^(]*?\b(\w+)\s*\()");
  const std::regex macroHead(R"(#define\s+(\w+)\((\w+)\))");
  const std::regex macroUse(R"(^\s*(\w+)\((\w+)\)\s*$)");
  std::map<std::string, std::vector<std::string>> macroSuffixes;  // macro -> method names after the prefix
  std::set<std::string> methods;
  std::string line, openMacro, openParam;
  while (std::getline(body, line)) {
    std::smatch m;
    if (std::regex_search(line, m, macroHead)) {
      openMacro = m[1];
      openParam = m[2];
    }
    if (!openMacro.empty()) {
      const std::regex member(openParam + R"(##(\w+)\s*\()");
      for (auto it = std::sregex_iterator(line.begin(), line.end(), member); it != std::sregex_iterator(); ++it)
        macroSuffixes[openMacro].push_back((*it)[1]);
      if (line.empty() || line.back() != '\\') openMacro.clear();
      continue;
    }
    if (std::regex_search(line, m, macroUse) && macroSuffixes.count(m[1])) {
      for (const std::string& suffix : macroSuffixes[m[1]]) methods.insert(std::string(m[2]) + suffix);
      continue;
    }
    if (std::regex_search(line, m, virtualMethod)) methods.insert(m[1]);
  }
  return methods;
}

struct Row {
  std::string method, status, tests;
};

// The table rows of each `## Section` of the coverage document.
std::map<std::string, std::vector<Row>> CoverageRows() {
  std::istringstream doc(ReadFile(kRoot / "docs/API_COVERAGE.md"));
  const std::regex row(R"(^\|\s*(\w+)\s*\|\s*([^|]*?)\s*\|\s*([^|]*?)\s*\|\s*$)");
  std::map<std::string, std::vector<Row>> sections;
  std::string line, section;
  while (std::getline(doc, line)) {
    if (line.rfind("## ", 0) == 0) section = line.substr(3);
    std::smatch m;
    if (std::regex_match(line, m, row) && m[1] != "Method") sections[section].push_back({m[1], m[2], m[3]});
  }
  return sections;
}

// "Suite.Name" of every TEST, TEST_F and TEST_P under tests/.
std::set<std::string> DefinedTests() {
  const std::regex test(R"(\bTEST(?:_F|_P)?\(\s*(\w+)\s*,\s*(\w+)\s*\))");
  std::set<std::string> tests;
  for (const auto& entry : fs::recursive_directory_iterator(kRoot / "tests")) {
    if (entry.path().extension() != ".cpp") continue;
    const std::string source = ReadFile(entry.path());
    for (auto it = std::sregex_iterator(source.begin(), source.end(), test); it != std::sregex_iterator(); ++it)
      tests.insert(std::string((*it)[1]) + "." + std::string((*it)[2]));
  }
  return tests;
}

bool NotYet(const Row& row) { return row.status.rfind("not yet", 0) == 0; }

struct Interface {
  const char* section;     // of API_COVERAGE.md
  const char* classHead;   // in rhi.h
  size_t d3d11Methods;     // in Direct3D 11.0's d3d11.h
};
const Interface kInterfaces[] = {
    {"ID3D11Device", "class Device : public Unknown {", 40},
    {"ID3D11DeviceContext", "class DeviceContext : public DeviceChild {", 108},
};

class ApiCoverageTest : public ::testing::TestWithParam<Interface> {};

TEST_P(ApiCoverageTest, EveryDeclaredMethodHasOneRowAndEveryRowMatchesTheHeader) {
  const Interface& api = GetParam();
  const std::set<std::string> declared = DeclaredMethods(ReadFile(kRoot / "rhi/include/rhi/rhi.h"), api.classHead);
  ASSERT_FALSE(declared.empty()) << api.classHead << " not found in rhi.h";
  const auto sections = CoverageRows();
  ASSERT_TRUE(sections.count(api.section)) << "API_COVERAGE.md has no section ## " << api.section;
  const std::vector<Row>& rows = sections.at(api.section);
  const std::string extensions = std::string(api.section) + ", not in D3D11";
  std::vector<Row> all = rows;
  if (sections.count(extensions)) all.insert(all.end(), sections.at(extensions).begin(), sections.at(extensions).end());

  EXPECT_EQ(rows.size(), api.d3d11Methods) << "rows of ## " << api.section;
  std::map<std::string, int> rowCount;
  for (const Row& row : all) {
    ++rowCount[row.method];
    const bool isDeclared = declared.count(row.method) != 0;
    if (NotYet(row))
      EXPECT_FALSE(isDeclared) << row.method << " is declared in rhi.h but its row says \"" << row.status << "\"";
    else
      EXPECT_TRUE(isDeclared) << "the row of " << row.method << " says \"" << row.status
                              << "\" but rhi.h does not declare it";
  }
  for (const auto& [method, count] : rowCount) EXPECT_EQ(count, 1) << method << " has " << count << " rows";
  for (const std::string& method : declared)
    EXPECT_TRUE(rowCount.count(method)) << api.section << "::" << method << " is declared in rhi.h without a row";
}

TEST_P(ApiCoverageTest, EveryRowOfADeclaredMethodNamesTestsThatExist) {
  const Interface& api = GetParam();
  const std::set<std::string> tests = DefinedTests();
  ASSERT_GT(tests.size(), 100u);
  const auto sections = CoverageRows();
  const std::regex testName(R"(\b(\w+)\.(\w+)\b)");
  for (const std::string section : {std::string(api.section), std::string(api.section) + ", not in D3D11"}) {
    if (!sections.count(section)) continue;
    for (const Row& row : sections.at(section)) {
      if (NotYet(row)) continue;
      int named = 0;
      for (auto it = std::sregex_iterator(row.tests.begin(), row.tests.end(), testName); it != std::sregex_iterator();
           ++it, ++named)
        EXPECT_TRUE(tests.count((*it)[0])) << row.method << ": no test " << (*it)[0] << " under tests/";
      EXPECT_GT(named, 0) << row.method << " names no test";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Interfaces, ApiCoverageTest, ::testing::ValuesIn(kInterfaces),
                         [](const auto& info) { return std::string(info.param.section); });

}  // namespace
