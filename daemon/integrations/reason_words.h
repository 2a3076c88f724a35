#pragma once
// What a reason means to the owner, in the dashboard's words (web/www/js/names.js
// REASONS; reason_words.cpp is generated from it): the title, what happened and
// what to do, for the pushes and Home Assistant (docs/integrations.md "Alarms").
#include <string_view>

namespace xr::integrations {

struct ReasonWords {
  std::string_view code;  // REASON_TEMP_CRITICAL
  std::string_view kind;  // fault | warn | state
  std::string_view title, meaning, action;
};

// nullptr for a code the dashboard has no words for.
const ReasonWords* reasonWords(std::string_view code);

}  // namespace xr::integrations
