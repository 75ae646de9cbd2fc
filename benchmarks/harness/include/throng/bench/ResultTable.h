#pragma once
// The rows an experiment reports, written the two ways every benchmark writes them: CSV for
// scripts (numbers as a C++ stream writes them, so the files stay byte for byte what they were)
// and a Markdown table for people (each column with its own printf format).

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace throng::bench {

/// A table of results with typed cells.
class ResultTable {
public:
    /// One column: its CSV header (empty: not in the CSV), its Markdown header (empty: not in the
    /// Markdown table) and the printf format of its numbers there ("%.2f", "%lld" for whole numbers).
    struct Column {
        std::string csv;              ///< CSV header of the column ("" when only Markdown shows it)
        std::string markdown;         ///< Markdown header ("" when only the CSV has it)
        std::string format = "%g";    ///< printf format of a number in Markdown
        bool text = false;            ///< left-aligned in Markdown (names), else right-aligned
    };
    /// A cell: a whole number, a number or a text.
    using Cell = std::variant<std::int64_t, double, std::string>;

    /// A table with `columns`, in order.
    explicit ResultTable(std::vector<Column> columns);
    /// Appends a row, one cell per column. Throws std::invalid_argument on a wrong cell count.
    void add(std::vector<Cell> row);
    /// Rows so far.
    std::size_t rows() const { return rows_.size(); }
    /// The CSV columns' header line, then one line per row.
    std::string csv() const;
    /// The CSV rows without the header (for files that collect runs).
    std::string csvRows() const;
    /// The CSV header line.
    std::string csvHeader() const;
    /// The Markdown table: header, alignment line, rows.
    std::string markdown() const;

private:
    std::vector<Column> columns_;
    std::vector<std::vector<Cell>> rows_;
};

}  // namespace throng::bench
