#include "cli_args.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>

namespace cli {

namespace {

std::string Quoted(std::string_view option, std::string_view text) {
  return std::string(option) + ": '" + std::string(text) + "'";
}

std::string Shortest(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

std::optional<int64_t> ParseInteger(std::string_view option, std::string_view text, int64_t min, int64_t max,
                                    std::string* error) {
  int64_t value = 0;
  // from_chars takes no '+'; accept one as the only extra.
  std::string_view digits = text.starts_with('+') ? text.substr(1) : text;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || value < min || value > max) {
    *error = Quoted(option, text) + " is not a whole number from " + std::to_string(min) + " to " +
             std::to_string(max);
    return std::nullopt;
  }
  return value;
}

std::optional<double> ParseNumber(std::string_view option, std::string_view text, double min, double max,
                                  std::string* error) {
  double value = 0;
  std::string_view digits = text.starts_with('+') ? text.substr(1) : text;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value) ||
      value < min || value > max) {
    *error = Quoted(option, text) + " is not a number from " + Shortest(min) + " to " + Shortest(max);
    return std::nullopt;
  }
  return value;
}

std::optional<std::vector<int64_t>> ParseIntegers(std::string_view option, std::string_view text, char separator,
                                                  size_t count, int64_t min, int64_t max, std::string* error) {
  std::vector<int64_t> values;
  std::string_view rest = text;
  for (size_t i = 0; i < count; ++i) {
    const size_t cut = i + 1 < count ? rest.find(separator) : rest.size();
    if (cut == std::string_view::npos || (i + 1 == count && rest.find(separator) != std::string_view::npos)) {
      *error = Quoted(option, text) + " is not " + std::to_string(count) + " numbers separated by '" + separator + "'";
      return std::nullopt;
    }
    std::optional<int64_t> value = ParseInteger(option, rest.substr(0, cut), min, max, error);
    if (!value) return std::nullopt;
    values.push_back(*value);
    rest = rest.substr(std::min(rest.size(), cut + 1));
  }
  return values;
}

bool MakeFolder(std::string_view option, const std::string& folder, std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (!ec && !std::filesystem::is_directory(folder, ec)) ec = std::make_error_code(std::errc::not_a_directory);
  if (ec) *error = std::string(option) + ": cannot create folder '" + folder + "': " + ec.message();
  return !ec;
}

}  // namespace cli
