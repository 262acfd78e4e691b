#pragma once
// Reading the CSV files tumble writes (trajectories, bench results, stability matrices), as
// RFC 4180 says: fields quoted when they hold commas, quotes (doubled) or line breaks.

#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "support/run_command.hpp"

namespace tumble::testing {

/// The records of CSV `text`, each a list of fields. A record ends at a line break outside
/// quotes ("\r\n" or "\n"); the line break ending the text starts no record, but an empty line
/// is a record of one empty field. A quote left open fails the test.
inline std::vector<std::vector<std::string>> parse_csv_records(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record(1);
  bool quoted = false;
  bool pending = false;  // characters since the last record ended
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    pending = true;
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        record.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        record.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.emplace_back();
    } else if (c == '\n' || (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n')) {
      if (c == '\r') ++i;
      records.push_back(std::move(record));
      record.assign(1, "");
      pending = false;
    } else {
      record.back() += c;
    }
  }
  EXPECT_FALSE(quoted) << "CSV ends inside a quoted field";
  if (pending) records.push_back(std::move(record));
  return records;
}

/// The fields of one CSV line.
inline std::vector<std::string> csv_fields(const std::string& line) {
  const auto records = parse_csv_records(line);
  EXPECT_LE(records.size(), 1u) << "more than one record in " << line;
  return records.empty() ? std::vector<std::string>(1) : records.front();
}

/// A CSV file with a header: every record after it, raw and by column name.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> records;
  std::vector<std::map<std::string, std::string>> rows;
};

/// The header and rows of CSV `text`; a record whose field count differs from the header's
/// fails the test (its fields still go to the columns they fall in).
inline CsvTable parse_csv_table(const std::string& text) {
  CsvTable table;
  auto records = parse_csv_records(text);
  EXPECT_FALSE(records.empty()) << "CSV without a header";
  if (records.empty()) return table;
  table.header = std::move(records.front());
  records.erase(records.begin());
  for (const auto& record : records) {
    EXPECT_EQ(record.size(), table.header.size()) << "record " << table.rows.size() + 1;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < record.size() && i < table.header.size(); ++i) {
      row[table.header[i]] = record[i];
    }
    table.rows.push_back(std::move(row));
  }
  table.records = std::move(records);
  return table;
}

/// parse_csv_table of a file.
inline CsvTable read_csv(const std::filesystem::path& file) {
  EXPECT_TRUE(std::filesystem::is_regular_file(file)) << file;
  return parse_csv_table(read_text(file));
}

}  // namespace tumble::testing
