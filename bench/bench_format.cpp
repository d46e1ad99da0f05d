// SPDX-License-Identifier: MIT
// calder-bench: numbers as text and tables as text or Markdown.
#include "bench_parts.hpp"

namespace calder::app::bench {

std::string printf_text(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

// "3.89e+09" -> "3.89e9", "8.5e-04" -> "8.5e-4".
namespace {

std::string short_exponent(const std::string& text) {
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  return text.substr(0, e + 1) + std::to_string(std::stoi(text.substr(e + 1)));
}

}  // namespace

// Three significant digits, at least: 3.90, 50.8, 691, 1160, 3.89e9.
std::string rate_text(double value) {
  if (!std::isfinite(value) || value <= 0.0) return "-";
  if (value >= 1e4 || value < 1e-2) return short_exponent(printf_text("%.2e", value));
  if (value >= 99.95) return printf_text("%.0f", value);
  return printf_text("%#.3g", value);  // 3.90, not 3.9
}

std::string error_text(double value) {
  if (!std::isfinite(value)) return "-";
  return short_exponent(printf_text("%.1e", value));
}

// Three significant digits, trailing zeros kept (1.80x is not 1.8x rounded up).
std::string ratio_text(double value) {
  if (!std::isfinite(value) || value <= 0.0) return "-";
  if (value >= 99.95) return printf_text("%.0f", value) + "x";
  if (value >= 9.995) return printf_text("%.1f", value) + "x";
  return printf_text("%.2f", value) + "x";
}

std::string percent_text(double value) {
  if (!std::isfinite(value) || value <= 0.0) return "-";
  return printf_text("%.0f", 100.0 * value) + "%";
}

// 16000 -> "16,000".
std::string count_text(std::size_t n) {
  std::string digits = std::to_string(n);
  std::string text;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
    text += digits[i];
  }
  return text;
}

std::string seconds_text(double seconds) { return printf_text("%.2g", seconds) + " s"; }

namespace {

std::string column_name(const std::string& column) {
  return !column.empty() && column.front() == '>' ? column.substr(1) : column;
}

bool right_aligned(const std::string& column) { return !column.empty() && column.front() == '>'; }

void print_text(std::ostream& out, const Table& table) {
  if (!table.title.empty()) out << table.title << "\n\n";
  const std::size_t columns = table.columns.size();
  std::vector<std::size_t> width(columns, 0);
  for (std::size_t c = 0; c < columns; ++c) width[c] = column_name(table.columns[c]).size();
  for (const auto& row : table.rows) {
    for (std::size_t c = 0; c < columns && c < row.size(); ++c) {
      width[c] = std::max(width[c], row[c].size());
    }
  }
  auto line = [&](const std::vector<std::string>& cells, bool header) {
    std::string text = "  ";
    for (std::size_t c = 0; c < columns; ++c) {
      const std::string cell = header ? column_name(cells[c]) : (c < cells.size() ? cells[c] : "");
      const std::string pad(width[c] - cell.size(), ' ');
      text += right_aligned(table.columns[c]) ? pad + cell : cell + pad;
      if (c + 1 < columns) text += "  ";
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out << text << '\n';
  };
  line(table.columns, true);
  std::vector<std::string> rule;
  for (std::size_t c = 0; c < columns; ++c) rule.emplace_back(width[c], '-');
  line(rule, false);
  for (const auto& row : table.rows) line(row, false);
  out << '\n';
}

void print_markdown(std::ostream& out, const Table& table) {
  if (!table.title.empty()) out << table.title << "\n\n";
  out << '|';
  for (const auto& column : table.columns) out << ' ' << column_name(column) << " |";
  out << "\n|";
  for (const auto& column : table.columns) out << (right_aligned(column) ? "--:|" : "---|");
  out << '\n';
  for (const auto& row : table.rows) {
    out << '|';
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      out << ' ' << (c < row.size() ? row[c] : "") << " |";
    }
    out << '\n';
  }
  out << '\n';
}

}  // namespace

void print_section(std::ostream& out, const Section& section, bool markdown) {
  out << (markdown ? "## " : "== ") << section.title << "\n\n";
  for (const Table& table : section.tables) {
    if (markdown) {
      print_markdown(out, table);
    } else {
      print_text(out, table);
    }
  }
  for (const std::string& note : section.notes) out << (markdown ? "- " : "  - ") << note << '\n';
  if (!section.notes.empty()) out << '\n';
}

}  // namespace calder::app::bench
