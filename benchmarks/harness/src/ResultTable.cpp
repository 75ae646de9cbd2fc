#include "throng/bench/ResultTable.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace throng::bench {

ResultTable::ResultTable(std::vector<Column> columns) : columns_(std::move(columns)) {}

void ResultTable::add(std::vector<Cell> row) {
    if (row.size() != columns_.size())
        throw std::invalid_argument("ResultTable::add: " + std::to_string(row.size()) + " cells for " + std::to_string(columns_.size()) + " columns");
    rows_.push_back(std::move(row));
}

std::string ResultTable::csvHeader() const {
    std::string line;
    for (const Column& c : columns_)
        if (!c.csv.empty()) line += (line.empty() ? "" : ",") + c.csv;
    return line + "\n";
}

std::string ResultTable::csvRows() const {
    std::ostringstream out;
    for (const auto& row : rows_) {
        bool first = true;
        for (std::size_t c = 0; c < columns_.size(); ++c) {
            if (columns_[c].csv.empty()) continue;
            if (!first) out << ',';
            first = false;
            std::visit([&](const auto& v) { out << v; }, row[c]);
        }
        out << '\n';
    }
    return out.str();
}

std::string ResultTable::csv() const { return csvHeader() + csvRows(); }

std::string ResultTable::markdown() const {
    std::string header = "|", align = "|";
    for (const Column& c : columns_)
        if (!c.markdown.empty()) header += " " + c.markdown + " |", align += c.text ? "---|" : "---:|";
    std::string out = header + "\n" + align + "\n";
    char cell[256];
    for (const auto& row : rows_) {
        out += "|";
        for (std::size_t c = 0; c < columns_.size(); ++c) {
            if (columns_[c].markdown.empty()) continue;
            const char* format = columns_[c].format.c_str();
            if (const auto* s = std::get_if<std::string>(&row[c])) std::snprintf(cell, sizeof cell, "%s", s->c_str());
            else if (const auto* i = std::get_if<std::int64_t>(&row[c])) std::snprintf(cell, sizeof cell, format, (long long)*i);
            else std::snprintf(cell, sizeof cell, format, std::get<double>(row[c]));
            out += " " + std::string(cell) + " |";
        }
        out += "\n";
    }
    return out;
}

}  // namespace throng::bench
