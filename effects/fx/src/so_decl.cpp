#include "fx/so_decl.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string_view>

namespace fx {
namespace {

struct ParsedEntry {
  rhi::SO_DECLARATION_ENTRY entry{};
  std::string semantic;  // empty for $SKIP
};

// Parses one ';'-separated entry of a declaration string.
class EntryParser {
 public:
  EntryParser(std::string_view text, size_t begin, size_t end, rhi::UINT stream)
      : s_(text), pos_(begin), end_(end), stream_(stream) {}

  // nullopt for an empty entry; the error is left in `error`.
  std::optional<ParsedEntry> Parse(std::optional<SoDeclError>& error) {
    SkipSpace();
    if (pos_ == end_) return std::nullopt;
    ParsedEntry e;
    e.entry.Stream = stream_;
    if (!ParseSlot(e) || !ParseSemantic(e) || !ParseMask(e)) {
      error = error_;
      return std::nullopt;
    }
    SkipSpace();
    if (pos_ != end_) {
      error = Error(pos_, std::string("unexpected '") + s_[pos_] + "' in stream-output entry");
      return std::nullopt;
    }
    return e;
  }

 private:
  SoDeclError Error(size_t at, std::string message) { return SoDeclError{stream_, at, std::move(message)}; }
  bool Fail(size_t at, std::string message) {
    error_ = Error(at, std::move(message));
    return false;
  }
  void SkipSpace() {
    while (pos_ < end_ && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool AtDigit() const { return pos_ < end_ && std::isdigit(static_cast<unsigned char>(s_[pos_])); }

  // "[slot :]"
  bool ParseSlot(ParsedEntry& e) {
    if (pos_ < end_ && s_[pos_] == ':') return Fail(pos_, "missing output slot before ':'");
    if (!AtDigit()) return true;
    size_t start = pos_;
    while (AtDigit()) ++pos_;
    std::string_view digits = s_.substr(start, pos_ - start);
    SkipSpace();
    if (pos_ >= end_ || s_[pos_] != ':') return Fail(start, "a semantic name cannot start with a digit");
    ++pos_;
    if (digits.size() > 3 || std::stoi(std::string(digits)) >= static_cast<int>(rhi::SO_BUFFER_SLOT_COUNT)) {
      return Fail(start, "output slot " + std::string(digits) + " is out of range (0-3)");
    }
    e.entry.OutputSlot = static_cast<rhi::UINT8>(std::stoi(std::string(digits)));
    SkipSpace();
    return true;
  }

  // "SEMANTIC[index]" or "$SKIP"
  bool ParseSemantic(ParsedEntry& e) {
    size_t start = pos_;
    if (pos_ < end_ && s_[pos_] == '$') ++pos_;
    while (pos_ < end_ && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    std::string_view word = s_.substr(start, pos_ - start);
    if (word == "$SKIP") return true;
    if (word.empty() || std::isdigit(static_cast<unsigned char>(word[0]))) {
      return Fail(start, "expected a semantic name or $SKIP");
    }
    if (word[0] == '$') return Fail(start, "unknown token '" + std::string(word) + "' (only $SKIP starts with '$')");
    size_t digits = word.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(word[digits - 1]))) --digits;
    if (word.size() - digits > 9) return Fail(start + digits, "semantic index too large");
    e.semantic = std::string(word.substr(0, digits));
    if (digits < word.size()) e.entry.SemanticIndex = std::stoul(std::string(word.substr(digits)));
    return true;
  }

  // "[.mask]": a contiguous run of xyzw or rgba.
  bool ParseMask(ParsedEntry& e) {
    SkipSpace();
    e.entry.StartComponent = 0;
    e.entry.ComponentCount = 4;
    if (pos_ >= end_ || s_[pos_] != '.') return true;
    ++pos_;
    SkipSpace();
    size_t start = pos_;
    while (pos_ < end_ && std::isalpha(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    std::string_view mask = s_.substr(start, pos_ - start);
    if (mask.empty()) return true;  // FX11 reads "POSITION." as the full register
    for (std::string_view set : {std::string_view("xyzw"), std::string_view("rgba")}) {
      size_t at = set.find(mask);
      if (at != std::string_view::npos) {
        e.entry.StartComponent = static_cast<rhi::UINT8>(at);
        e.entry.ComponentCount = static_cast<rhi::UINT8>(mask.size());
        return true;
      }
    }
    bool allXyzw = mask.find_first_not_of("xyzw") == std::string_view::npos;
    bool allRgba = mask.find_first_not_of("rgba") == std::string_view::npos;
    if (allXyzw || allRgba) {
      return Fail(start, "mask '." + std::string(mask) + "' must name contiguous components in order");
    }
    return Fail(start, "invalid mask '." + std::string(mask) + "' (use xyzw or rgba)");
  }

  std::string_view s_;
  size_t pos_;
  size_t end_;
  rhi::UINT stream_;
  SoDeclError error_;
};

}  // namespace

std::variant<StreamOutputDecl, SoDeclError> StreamOutputDecl::Parse(const std::vector<std::string>& streams) {
  if (streams.size() > rhi::SO_STREAM_COUNT) {
    return SoDeclError{rhi::SO_STREAM_COUNT, 0, "at most 4 stream-output declarations"};
  }
  std::vector<ParsedEntry> parsed;
  std::array<int, rhi::SO_BUFFER_SLOT_COUNT> slotStream;
  slotStream.fill(-1);
  for (rhi::UINT stream = 0; stream < streams.size(); ++stream) {
    const std::string& s = streams[stream];
    for (size_t begin = 0; begin <= s.size();) {
      size_t end = std::min(s.find(';', begin), s.size());
      std::optional<SoDeclError> error;
      std::optional<ParsedEntry> e = EntryParser(s, begin, end, stream).Parse(error);
      if (error) return *error;
      if (e) {
        int& owner = slotStream[e->entry.OutputSlot];
        if (owner >= 0 && owner != static_cast<int>(stream)) {
          return SoDeclError{stream, begin,
                             "output slot " + std::to_string(e->entry.OutputSlot) +
                                 " is already written by stream " + std::to_string(owner)};
        }
        owner = static_cast<int>(stream);
        parsed.push_back(std::move(*e));
      }
      begin = end + 1;
    }
  }
  auto names = std::make_shared<std::vector<std::string>>();
  names->reserve(parsed.size());
  for (const ParsedEntry& e : parsed) names->push_back(e.semantic);
  StreamOutputDecl decl;
  for (size_t i = 0; i < parsed.size(); ++i) {
    rhi::SO_DECLARATION_ENTRY entry = parsed[i].entry;
    entry.SemanticName = parsed[i].semantic.empty() ? nullptr : (*names)[i].c_str();
    decl.entries_.push_back(entry);
  }
  decl.names_ = std::move(names);
  return decl;
}

std::array<rhi::UINT, rhi::SO_BUFFER_SLOT_COUNT> StreamOutputDecl::Strides() const {
  std::array<rhi::UINT, rhi::SO_BUFFER_SLOT_COUNT> strides{};
  for (const rhi::SO_DECLARATION_ENTRY& e : entries_) {
    strides[e.OutputSlot] += e.ComponentCount * static_cast<rhi::UINT>(sizeof(float));
  }
  return strides;
}

}  // namespace fx
