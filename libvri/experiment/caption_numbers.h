#pragma once
// Numbers in a caption that come from the data: the gallery writes an experiment's agreement text
// with every reference `{{table:NAME:ROW:COLUMN}}` replaced by that cell of NAME.csv in the
// experiment's results folder, as vri-tabulate printed it, and every `{{json:NAME:PATH}}` by the
// number at the dotted PATH of NAME.json there (a run's stats, a comparison; an integer whole, any
// other number to 4 significant digits). A caption so written
// cannot drift from its data when the experiment is run again.
#include <filesystem>
#include <string>

namespace vri {

// `text` with each reference filled from the CSV files in `folder`. Throws vri::Error naming the
// reference when it is malformed (an unclosed "{{", a kind other than table or json, a part missing
// or empty), or its file, row, column or path does not exist, or its cell is empty or not a number.
std::string fillCaptionNumbers(const std::string& text, const std::filesystem::path& folder);

}  // namespace vri
