#pragma once
// A table of strings written as aligned text (terminal), Markdown (report) or CSV (data), so every
// table of the cost-model report has one source.

#include <string>
#include <vector>

namespace throng::costmodel {

/// Rows of cells under a header.
class TextTable {
public:
    /// A table with these column headers.
    explicit TextTable(std::vector<std::string> headers) : headers_(std::move(headers)) {}
    /// Appends a row (missing cells are blank, extra cells are an error).
    void addRow(std::vector<std::string> cells);
    /// Aligned columns for a terminal.
    std::string text() const;
    /// A Markdown table.
    std::string markdown() const;
    /// Comma-separated values, quoted where needed.
    std::string csv() const;

private:
    std::vector<std::string> headers_;
    std::vector<std::vector<std::string>> rows_;
};

/// `value` with `digits` decimals.
std::string fixed(double value, int digits = 0);
/// `value` with thousands separators and no decimals ("4,206,240").
std::string grouped(double value);

}  // namespace throng::costmodel
