// The report options name the field that is wrong and its accepted range; format_table refuses them whole.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/report/rock_export.h"
#include "core/report/table_format.h"

namespace ipd {
namespace {

TEST(ReportOptions, TableFormatOptionsNameTheBadField) {
  TableFormatOptions o;
  EXPECT_EQ(o.validate(), "");
  o.resamples = -1;
  EXPECT_EQ(o.validate(), "resamples must be >= 0 (0: no intervals), got -1");
  o.resamples = 2000;
  o.level = 95;
  EXPECT_EQ(o.validate(), "level must be in (0, 1), got 95");
  o.level = 0.95;
  o.conf_threshold = 1.5;
  EXPECT_EQ(o.validate(), "conf_threshold must be in [0, 1], got 1.5");
  try {
    format_table(CrossTable{}, TableFormat::kText, o);
    FAIL() << "format_table accepted a threshold above 1";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "table format options: conf_threshold must be in [0, 1], got 1.5");
  }
}

TEST(ReportOptions, RockExportOptionsAlwaysUsable) {
  RockExportOptions o;
  EXPECT_EQ(o.validate(), "");
  o.unpaired = true;
  EXPECT_EQ(o.validate(), "");
}

}  // namespace
}  // namespace ipd
