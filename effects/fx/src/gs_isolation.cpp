#include "fx/gs_isolation.h"

#include <algorithm>
#include <cctype>
#include <regex>
#include <set>

namespace fx {
namespace {

struct Function {
  std::string name;
  std::set<std::string> streamTypes;  // "PointStream<Particle>", whitespace removed
  size_t bodyOpen = 0, bodyClose = 0;  // positions of '{' and its matching '}'
};

bool IsIdent(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The matching closer of the bracket at `open`, or npos.
size_t Match(const std::string& s, size_t open, char o, char c) {
  int depth = 0;
  for (size_t i = open; i < s.size(); ++i) {
    if (s[i] == o) ++depth;
    if (s[i] == c && --depth == 0) return i;
  }
  return std::string::npos;
}

std::set<std::string> StreamTypes(const std::string& params) {
  static const std::regex kStream(R"(\binout\s+((Point|Line|Triangle)Stream\s*<[^>]*>))");
  std::set<std::string> types;
  for (std::sregex_iterator it(params.begin(), params.end(), kStream), end; it != end; ++it) {
    std::string t = (*it)[1];
    t.erase(std::remove_if(t.begin(), t.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); }),
            t.end());
    types.insert(t);
  }
  return types;
}

// Top-level `name(params) [: SEMANTIC] { body }` definitions with stream parameters.
// The text is preprocessed (no comments); `#line` lines hold no parentheses
// that matter and strings do not occur outside blanked effect constructs.
std::vector<Function> StreamFunctions(const std::string& s) {
  std::vector<Function> functions;
  int depth = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    char ch = s[i];
    if (ch == '{') ++depth;
    if (ch == '}') --depth;
    if (ch != '(' || depth != 0) continue;
    size_t nameEnd = i;
    while (nameEnd > 0 && std::isspace(static_cast<unsigned char>(s[nameEnd - 1]))) --nameEnd;
    size_t nameBegin = nameEnd;
    while (nameBegin > 0 && IsIdent(s[nameBegin - 1])) --nameBegin;
    size_t close = Match(s, i, '(', ')');
    if (close == std::string::npos) break;
    size_t j = close + 1;
    while (j < s.size() && (std::isspace(static_cast<unsigned char>(s[j])) || s[j] == ':' || IsIdent(s[j]))) ++j;
    if (j >= s.size() || s[j] != '{' || nameBegin == nameEnd) {
      i = close;
      continue;
    }
    size_t bodyClose = Match(s, j, '{', '}');
    if (bodyClose == std::string::npos) break;
    std::set<std::string> types = StreamTypes(s.substr(i, close - i));
    if (!types.empty()) functions.push_back({s.substr(nameBegin, nameEnd - nameBegin), types, j, bodyClose});
    i = bodyClose;  // the body is skipped whole, so depth stays 0
  }
  return functions;
}

}  // namespace

std::string IsolateGeometryShader(const std::string& hlsl, const std::vector<std::string>& keep) {
  if (hlsl.find("Stream") == std::string::npos) return hlsl;
  std::vector<Function> functions = StreamFunctions(hlsl);
  std::set<std::string> allTypes, keptTypes;
  for (const Function& f : functions) {
    allTypes.insert(f.streamTypes.begin(), f.streamTypes.end());
    if (std::find(keep.begin(), keep.end(), f.name) != keep.end())
      keptTypes.insert(f.streamTypes.begin(), f.streamTypes.end());
  }
  if (allTypes.size() <= 1) return hlsl;
  std::string out = hlsl;
  for (const Function& f : functions) {
    bool kept = std::find(keep.begin(), keep.end(), f.name) != keep.end() ||
                std::includes(keptTypes.begin(), keptTypes.end(), f.streamTypes.begin(), f.streamTypes.end());
    if (kept && !keptTypes.empty()) continue;
    for (size_t k = f.bodyOpen + 1; k < f.bodyClose; ++k)
      if (out[k] != '\n') out[k] = ' ';
  }
  return out;
}

}  // namespace fx
