// Strict parsing of the command-line programs' arguments (fxtool, replay, demo,
// the benchmarks): a number must be all digits and in range, a folder must be
// creatable. Each failure is one line of text for the program to print before
// exiting nonzero, never a silent default, a wrapped value or an exception.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cli {

// The integer `text` spells exactly (decimal, optional sign), if it lies in [min, max];
// else nullopt and *error = "OPTION: 'TEXT' is not a whole number from MIN to MAX".
std::optional<int64_t> ParseInteger(std::string_view option, std::string_view text, int64_t min, int64_t max,
                                    std::string* error);

// The finite number `text` spells exactly, if it lies in [min, max]; else nullopt and *error.
std::optional<double> ParseNumber(std::string_view option, std::string_view text, double min, double max,
                                  std::string* error);

// `count` integers in [min, max] separated by `separator` ("64,1,1", "320x180").
std::optional<std::vector<int64_t>> ParseIntegers(std::string_view option, std::string_view text, char separator,
                                                  size_t count, int64_t min, int64_t max, std::string* error);

// Creates `folder` and its parents. False with *error ("OPTION: cannot create
// folder 'X': reason") when that fails or the path is not a folder.
bool MakeFolder(std::string_view option, const std::string& folder, std::string* error);

}  // namespace cli
