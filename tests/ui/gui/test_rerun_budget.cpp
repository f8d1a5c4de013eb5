// The time budget a registration re-run in ipd-studio gets (ui/gui/views.h): the study's until edited.
#include <gtest/gtest.h>

#include "ui/gui/views.h"

namespace ipd::ui {
namespace {

TEST(RerunBudget, StartsAtTheStudysBudgetUntilEdited) {
  RegistrationOptions study;
  UiState ui;
  EXPECT_FLOAT_EQ(rerun_budget_ms(ui, study), 0.0f);  // no budget anywhere: none
  EXPECT_FALSE(rerun_time_budget(ui, study).has_value());
  study.time_budget_ms = 12.5;  // study.yaml's registration.budget_ms
  EXPECT_FLOAT_EQ(rerun_budget_ms(ui, study), 12.5f);
  EXPECT_EQ(rerun_time_budget(ui, study), 12.5);
  ui.rerun_budget_ms = 40;  // typed in the registration panel
  EXPECT_FLOAT_EQ(rerun_budget_ms(ui, study), 40.0f);
  EXPECT_EQ(rerun_time_budget(ui, study), 40.0);
  ui.rerun_budget_ms = 0;  // cleared: the re-run has no time limit, whatever the study says
  EXPECT_FLOAT_EQ(rerun_budget_ms(ui, study), 0.0f);
  EXPECT_FALSE(rerun_time_budget(ui, study).has_value());
}

}  // namespace
}  // namespace ipd::ui
