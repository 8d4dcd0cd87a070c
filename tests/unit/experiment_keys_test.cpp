// experiments/README.md, the experiment files' schema, names every key the reader accepts: a key the code
// takes and the page omits is one a user cannot find.
#include <doctest/doctest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "libvri/experiment/experiment_keys.h"
#include "libvri/util/file_text.h"

TEST_CASE("experiments/README.md documents every key an experiment file may hold") {
    const std::filesystem::path readme = std::filesystem::path(VRI_TEST_DATA_DIR) / ".." / ".." / "experiments" / "README.md";
    const std::string text = vri::readFileText(readme, "the experiment files' schema");
    int keys = 0;
    for (const auto& [where, key] : vri::experimentKeys()) {
        // As YAML writes it, the key at a line's start or after blanks, '{' or '`', then ':'; or in the first
        // cell of a row of the parameters' table ("| h0, h_min, h_max |").
        const std::string k(key);
        const std::regex written("(^|[\\s{`])" + k + ":|\\n\\| ([a-z0-9_]+, )*" + k + "(, [a-z0-9_]+)* \\|");
        INFO("section: ", std::string(where), ", key: ", std::string(key));
        CHECK(std::regex_search(text, written));
        ++keys;
    }
    CHECK(keys > 60);  // every section's keys and the render options' were listed
}
