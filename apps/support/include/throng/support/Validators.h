#pragma once
// Checks of option values the tools share (CLI11 validators). Each one names what it expects and
// what it got, and describes the allowed values for --help; CLI11 puts the option's name first.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace throng::support {

/// Decimal whole numbers from `lo` to `hi`, without sign '+' or leading zeros (CLI11 would read
/// "010" as octal eight, "0x10" as sixteen).
CLI::Validator wholeNumber(long long lo, long long hi);
/// Whole numbers of `lo` or more.
CLI::Validator wholeNumberFrom(long long lo);
/// Finite numbers from `lo` to `hi` (NaN and infinities are refused).
CLI::Validator number(double lo, double hi);
/// Finite numbers above zero.
CLI::Validator positiveNumber();
/// Finite numbers of zero or more.
CLI::Validator nonNegativeNumber();
/// One of `choices`, spelled exactly.
CLI::Validator oneOf(std::vector<std::string> choices);
/// The path of an existing regular file.
CLI::Validator existingFile();
/// A file to write: its folder exists (the current one when the path names none) and this process
/// can write into it, and the path is not a folder.
CLI::Validator fileToWrite();
/// A folder to write into: an existing folder this process can write into, or a new one whose
/// nearest existing folder it can write into (nothing is made by the check, so a run refused later
/// leaves nothing behind). Refuses a path that is a file or lies below one, and a folder that
/// cannot be written or created.
CLI::Validator folderToWrite();
/// The path of an existing regular file, or `keyword` (e.g. "seed-humanoid").
CLI::Validator existingFileOr(std::string keyword);
/// Impostor views "AxE": 3 to 256 azimuths by 1 to 64 elevation rings (see ViewGrid).
CLI::Validator viewGrid();

}  // namespace throng::support
