#include "TextTable.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace throng::costmodel {

void TextTable::addRow(std::vector<std::string> cells) {
    if (cells.size() > headers_.size())
        throw std::invalid_argument("TextTable::addRow: " + std::to_string(cells.size()) + " cells for " +
                                    std::to_string(headers_.size()) + " columns");
    cells.resize(headers_.size());
    rows_.push_back(std::move(cells));
}

std::string TextTable::text() const {
    std::vector<std::size_t> width(headers_.size());
    for (std::size_t c = 0; c < headers_.size(); ++c) {
        width[c] = headers_[c].size();
        for (const auto& r : rows_) width[c] = std::max(width[c], r[c].size());
    }
    std::ostringstream out;
    auto line = [&](const std::vector<std::string>& cells) {
        for (std::size_t c = 0; c < cells.size(); ++c) {
            out << (c ? "  " : "") << cells[c];
            if (c + 1 < cells.size()) out << std::string(width[c] - cells[c].size(), ' ');
        }
        out << '\n';
    };
    line(headers_);
    std::vector<std::string> rule;
    for (std::size_t w : width) rule.push_back(std::string(w, '-'));
    line(rule);
    for (const auto& r : rows_) line(r);
    return out.str();
}

std::string TextTable::markdown() const {
    std::ostringstream out;
    auto line = [&](const std::vector<std::string>& cells) {
        out << '|';
        for (const auto& c : cells) out << ' ' << c << " |";
        out << '\n';
    };
    line(headers_);
    out << '|';
    for (std::size_t c = 0; c < headers_.size(); ++c) out << "---|";
    out << '\n';
    for (const auto& r : rows_) line(r);
    return out.str();
}

std::string TextTable::csv() const {
    std::ostringstream out;
    auto cell = [&](const std::string& s) {
        if (s.find_first_of(",\"\n") == std::string::npos) {
            out << s;
            return;
        }
        out << '"';
        for (char ch : s) out << (ch == '"' ? "\"\"" : std::string(1, ch));
        out << '"';
    };
    auto line = [&](const std::vector<std::string>& cells) {
        for (std::size_t c = 0; c < cells.size(); ++c) {
            if (c) out << ',';
            cell(cells[c]);
        }
        out << '\n';
    };
    line(headers_);
    for (const auto& r : rows_) line(r);
    return out.str();
}

std::string fixed(double value, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, value);
    return buf;
}

std::string grouped(double value) {
    const long long v = std::llround(value);
    std::string digits = std::to_string(v < 0 ? -v : v), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return v < 0 ? "-" + out : out;
}

}  // namespace throng::costmodel
