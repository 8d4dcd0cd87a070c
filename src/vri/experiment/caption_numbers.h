#pragma once
// Numbers in a caption that come from the data: the gallery writes an experiment's agreement text
// with every reference `{{table:NAME:ROW:COLUMN}}` replaced by that cell of NAME.csv in the
// experiment's results folder, as vri-tabulate printed it. A caption so written cannot drift from
// its tables when the experiment is run again.
#include <filesystem>
#include <string>

namespace vri {

// `text` with each reference filled from the CSV files in `folder`. Throws vri::Error naming the
// reference when it is malformed (an unclosed "{{", a kind other than table, a part missing or
// empty), or its file, row or column does not exist, or its cell is empty.
std::string fillCaptionNumbers(const std::string& text, const std::filesystem::path& folder);

}  // namespace vri
