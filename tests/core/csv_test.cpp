#include "sympathy/core/csv.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sympathy/core/errors.hpp"

namespace sympathy {
namespace {

// Fields with commas, quotes or line breaks are quoted (RFC 4180); numbers read back exactly.
TEST(CsvWriter, QuotesAndRoundTrips) {
  const auto path = (std::filesystem::temp_directory_path() / "sympathy_csv_test.csv").string();
  {
    CsvWriter csv(path, {"name", "value"});
    csv.row(std::vector<std::string>{"BDF, dense", "say \"hi\""});
    csv.row(std::vector<double>{0.1, 1.0 / 3.0});
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "name,value\n\"BDF, dense\",\"say \"\"hi\"\"\"\n0.1,0.3333333333333333\n");
  EXPECT_EQ(std::stod(format_double(1.0 / 3.0)), 1.0 / 3.0);
}

// Numbers may carry one sign, '+' or '-'; "+-1", "++1" and "+" are no numbers, and the error
// names the line, the column and what it got.
TEST(ReadCsv, OneSignAtMost) {
  const auto path =
      (std::filesystem::temp_directory_path() / "sympathy_read_csv_test.csv").string();
  auto write = [&](const std::string& text) { std::ofstream(path) << text; };
  write("t,x\n0,+1.5\n1,-2\n");
  const CsvTable table = read_csv(path);
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0][1], 1.5);
  EXPECT_EQ(table.rows[1][1], -2.0);
  for (const std::string bad : {"+-1", "++1", "+", "-+1"}) {
    write("t,x\n0," + bad + "\n");
    try {
      read_csv(path);
      ADD_FAILURE() << bad << " was read as a number";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(":2: column 'x' (field 2): expected a number, got '" +
                                           bad + "'"),
                std::string::npos)
          << e.what();
    }
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace sympathy
