// Unit tests of the strict numeric CSV reader: what it accepts, and that each
// error names the file and the exact line.

#include "common/csv.hpp"

#include "common/error.hpp"

#include "tests/support/scratch_folder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace sartor {
namespace {

namespace fs = std::filesystem;

const fs::path& scratch_folder() {
  return test_support::scratch_folder("sartor_unit_csv");
}

// Writes `content` byte for byte to a file of its own for the running test.
std::string write_file(const std::string& name, const std::string& content) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir =
      scratch_folder() / (std::string(test->test_suite_name()) + "." + test->name());
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream out(path, std::ios::binary);
  out << content;
  return path.string();
}

// The message of the InputError that read_csv(path) throws, or "" (and a
// test failure) when it throws none.
std::string read_error(const std::string& path) {
  try {
    (void)read_csv(path);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "read_csv(" << path << ") accepted the file";
  return "";
}

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

::testing::AssertionResult starts_with(const std::string& text, const std::string& prefix) {
  if (text.rfind(prefix, 0) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not start with '" << prefix << "'";
}

// --- valid files ---------------------------------------------------------------

TEST(CsvRead, ParsesCommentsBlankLinesWhitespaceAndMixedCase) {
  const std::string path = write_file("history.csv",
                                      "# creep test record\n"          // 1
                                      "\n"                             // 2
                                      "  Time_S , TENSION_n_per_m\t\n" // 3
                                      "# a comment between rows\n"     // 4
                                      "0, 0\n"                         // 5
                                      "\t1.5 ,+2.5e3\n"                // 6
                                      "   \n"                          // 7
                                      "   # indented comment\n"        // 8
                                      "3600,-1E-3\n");                 // 9
  const CsvTable table = read_csv(path);
  EXPECT_EQ(table.path, path);
  EXPECT_EQ(table.names, (std::vector<std::string>{"time_s", "tension_n_per_m"}));
  ASSERT_EQ(table.rows(), 3u);
  EXPECT_EQ(table.lines, (std::vector<long>{5, 6, 9}));
  ASSERT_EQ(table.columns.size(), 2u);
  EXPECT_EQ(table.columns[0], (std::vector<double>{0.0, 1.5, 3600.0}));
  EXPECT_EQ(table.columns[1], (std::vector<double>{0.0, 2500.0, -1e-3}));
}

TEST(CsvRead, ParsesCrlfLineEndings) {
  const std::string path =
      write_file("crlf.csv", "# windows file\r\ntime,tension\r\n\r\n0,1\r\n2.5,3e2\r\n");
  const CsvTable table = read_csv(path);
  EXPECT_EQ(table.names, (std::vector<std::string>{"time", "tension"}));
  EXPECT_EQ(table.lines, (std::vector<long>{4, 5}));
  EXPECT_EQ(table.columns[0], (std::vector<double>{0.0, 2.5}));
  EXPECT_EQ(table.columns[1], (std::vector<double>{1.0, 300.0}));
}

TEST(CsvRead, LastLineWithoutNewlineAndSingleColumn) {
  const CsvTable table = read_csv(write_file("one.csv", "strain\n0.25\n0.5"));
  EXPECT_EQ(table.names, (std::vector<std::string>{"strain"}));
  EXPECT_EQ(table.columns[0], (std::vector<double>{0.25, 0.5}));
  EXPECT_EQ(table.lines, (std::vector<long>{2, 3}));
}

TEST(CsvRead, NumbersReadBackExactly) {
  const CsvTable table =
      read_csv(write_file("exact.csv", "x\n0.1\n2451.6625\n1e-300\n-1.7976931348623157e308\n"));
  EXPECT_EQ(table.columns[0],
            (std::vector<double>{0.1, 2451.6625, 1e-300, -1.7976931348623157e308}));
}

TEST(CsvRead, FindAndRequireAcceptAlternativeNames) {
  const CsvTable table = read_csv(write_file("alt.csv", "time,tension_n_per_m\n0,1\n"));
  EXPECT_EQ(table.find({"time_s", "time"}), std::optional<std::size_t>(0));
  EXPECT_EQ(table.find({"tension_n_per_m", "tension"}), std::optional<std::size_t>(1));
  EXPECT_EQ(table.find({"strain"}), std::nullopt);
  EXPECT_EQ(table.require({"time_s", "time"}, "time in s"), 0u);
  EXPECT_EQ(table.require({"tension", "tension_n_per_m"}, "membrane tension"), 1u);
}

// --- errors ----------------------------------------------------------------------

TEST(CsvErrors, MissingColumnNamesFileHeaderLineAndAcceptedNames) {
  const std::string path = write_file("missing.csv", "# comment\ntime_s,strain\n0,0.1\n");
  const CsvTable table = read_csv(path);
  try {
    (void)table.require({"tension_n_per_m", "tension"}, "membrane tension in N/m");
    ADD_FAILURE() << "require() found a column that is not there";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "'tension_n_per_m'"));
    EXPECT_TRUE(contains(what, "'tension'"));
    EXPECT_TRUE(contains(what, "membrane tension in N/m"));
    EXPECT_TRUE(contains(what, "time_s, strain"));
    // csv.hpp: "Errors say FILE:LINE": the line of the header.
    EXPECT_TRUE(starts_with(what, path + ":2: "));
  }
}

TEST(CsvErrors, TextInNumberGivesLine) {
  const std::string path = write_file("text.csv", "time,tension\n0,1\n# c\n1,abc\n");
  const std::string what = read_error(path);
  EXPECT_TRUE(starts_with(what, path + ":4: "));
  EXPECT_TRUE(contains(what, "'abc'"));
  EXPECT_TRUE(contains(what, "tension"));
}

TEST(CsvErrors, PartialNumberOrNonFiniteValueGivesLine) {
  for (const std::string bad : {"1.5x", "1..5", "nan", "inf", "1e999", "0x10", "", "- 1"}) {
    SCOPED_TRACE(bad);
    const std::string path = write_file("partial.csv", "time,tension\n0,1\n\n5," + bad + "\n");
    EXPECT_TRUE(starts_with(read_error(path), path + ":4: "));
  }
}

TEST(CsvErrors, WrongFieldCountGivesLine) {
  {
    const std::string path = write_file("many.csv", "time,tension\n0,1\n1,2,3\n");
    const std::string what = read_error(path);
    EXPECT_TRUE(starts_with(what, path + ":3: "));
    EXPECT_TRUE(contains(what, "expected 2 values, found 3"));
  }
  {
    const std::string path = write_file("few.csv", "time,tension\n\n\n7\n");
    const std::string what = read_error(path);
    EXPECT_TRUE(starts_with(what, path + ":4: "));
    EXPECT_TRUE(contains(what, "expected 2 values, found 1"));
  }
  {
    const std::string path = write_file("trailing.csv", "time,tension\n1,2,\n");
    EXPECT_TRUE(starts_with(read_error(path), path + ":2: "));
  }
}

TEST(CsvErrors, EmptyFileIsReported) {
  for (const std::string content : {"", "\n\n", "# only a comment\n\n"}) {
    const std::string path = write_file("empty.csv", content);
    const std::string what = read_error(path);
    EXPECT_TRUE(starts_with(what, path + ": "));
    EXPECT_TRUE(contains(what, "empty"));
  }
}

TEST(CsvErrors, HeaderOnlyFileIsReported) {
  const std::string path = write_file("header_only.csv", "# c\ntime,tension\n\n# no rows\n");
  const std::string what = read_error(path);
  EXPECT_TRUE(starts_with(what, path + ": "));
  EXPECT_TRUE(contains(what, "no data rows"));
}

TEST(CsvErrors, DuplicateColumnGivesLine) {
  const std::string path = write_file("dup.csv", "\n# c\ntime,Tension, TIME\n0,1,2\n");
  const std::string what = read_error(path);
  EXPECT_TRUE(starts_with(what, path + ":3: "));
  EXPECT_TRUE(contains(what, "'time' appears twice"));
}

TEST(CsvErrors, NumericFirstLineMeansNoHeader) {
  {
    const std::string path = write_file("noheader.csv", "0,100\n1,200\n");
    const std::string what = read_error(path);
    EXPECT_TRUE(starts_with(what, path + ":1: "));
    EXPECT_TRUE(contains(what, "must name the columns"));
  }
  {
    const std::string path = write_file("noheader2.csv", "# data\n\ntime,5\n1,200\n");
    EXPECT_TRUE(starts_with(read_error(path), path + ":3: "));
  }
}

TEST(CsvErrors, EmptyColumnNameGivesLine) {
  const std::string path = write_file("blankname.csv", "time,,tension\n0,1,2\n");
  const std::string what = read_error(path);
  EXPECT_TRUE(starts_with(what, path + ":1: "));
  EXPECT_TRUE(contains(what, "empty column name"));
}

TEST(CsvErrors, MissingFileIsReported) {
  const std::string path = write_file("exists.csv", "x\n1\n") + ".not-there";
  const std::string what = read_error(path);
  EXPECT_TRUE(starts_with(what, path + ": "));
  EXPECT_TRUE(contains(what, "cannot open"));
}

// --- require_nondecreasing ---------------------------------------------------------

TEST(CsvNondecreasing, AcceptsEqualNeighbours) {
  const CsvTable table = read_csv(write_file("ok.csv", "time,tension\n0,0\n0,5\n1,5\n1,0\n"));
  EXPECT_NO_THROW(require_nondecreasing(table, 0));
}

TEST(CsvNondecreasing, ReportsLineOfFirstDecreasingRow) {
  const std::string path = write_file("order.csv",
                                      "time,tension\n" // 1
                                      "0,0\n"          // 2
                                      "# hold\n"       // 3
                                      "10,5\n"         // 4
                                      "\n"             // 5
                                      "9.5,5\n"        // 6: first decrease
                                      "3,0\n");        // 7: another one
  const CsvTable table = read_csv(path);
  try {
    require_nondecreasing(table, 0);
    ADD_FAILURE() << "accepted a decreasing column";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(starts_with(what, path + ":6: "));
    EXPECT_TRUE(contains(what, "'time'"));
    EXPECT_TRUE(contains(what, "9.5 after 10"));
  }
  // The other column decreases first at line 7.
  try {
    require_nondecreasing(table, 1);
    ADD_FAILURE() << "accepted a decreasing column";
  } catch (const InputError& e) {
    EXPECT_TRUE(starts_with(e.what(), path + ":7: "));
  }
}

// --- format_number -------------------------------------------------------------------

TEST(CsvFormatNumber, RoundTripsRandomDoublesExactly) {
  std::mt19937_64 rng(2024);
  int checked = 0;
  while (checked < 20000) {
    const std::uint64_t bits = rng();
    double value = 0.0;
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isfinite(value)) continue;
    ++checked;
    const std::string text = format_number(value);
    const double back = std::strtod(text.c_str(), nullptr);
    ASSERT_EQ(std::memcmp(&back, &value, sizeof value), 0) << text;
  }
}

TEST(CsvFormatNumber, RoundTripsSpecialValuesAndIsShortest) {
  for (const double value : {0.0, -0.0, 1.0, 0.1, 1.0 / 3.0, 2451.6625, 1e-300, 5e-324,
                             std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                             -std::numeric_limits<double>::max(), std::nextafter(1.0, 2.0)}) {
    const std::string text = format_number(value);
    const double back = std::strtod(text.c_str(), nullptr);
    EXPECT_EQ(std::memcmp(&back, &value, sizeof value), 0) << text;
  }
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(2451.6625), "2451.6625");
  EXPECT_EQ(format_number(32600.0), "32600");
  EXPECT_EQ(format_number(-0.5), "-0.5");
}

TEST(CsvFormatNumber, ReadCsvReadsFormattedNumbersBack) {
  std::mt19937_64 rng(7);
  std::string content = "value\n";
  std::vector<double> values;
  for (int i = 0; i < 200; ++i) {
    const double value =
        std::ldexp(std::uniform_real_distribution<double>(-1.0, 1.0)(rng), int(rng() % 200) - 100);
    values.push_back(value);
    content += format_number(value) + "\n";
  }
  const CsvTable table = read_csv(write_file("formatted.csv", content));
  EXPECT_EQ(table.columns[0], values);
}

} // namespace
} // namespace sartor
