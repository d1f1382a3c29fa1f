#include "sympathy/core/csv.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

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

}  // namespace
}  // namespace sympathy
