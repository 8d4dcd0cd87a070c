// Fuzz target: a tile's stats JSON as vri-merge-tiles combines it (tile_merge.h): the input as one tile's
// record beside the committed seed it was made from, combined field by field. An input that is no JSON is
// out of scope (readJsonFile refuses it with one line); a vri::Error is a clean rejection; anything else
// (a nlohmann exception reaching the caller, a crash) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/render/tile_merge.h"
#include "libvri/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const nlohmann::json record = nlohmann::json::parse(data, data + size, nullptr, false);
    if (record.is_discarded()) return 0;
    try {
        vri::combineTileStats({record, record}, {"a.json", "b.json"});
    } catch (const vri::Error&) {
    }
    return 0;
}
