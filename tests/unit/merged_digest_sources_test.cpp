#include <doctest/doctest.h>

#include "libvri/render/merged_digest_sources.h"

using nlohmann::json;

TEST_CASE("a merged record names every record its parts took input digests from") {
    const json fromA = {{"input_digests_from", "/run/a.json"}}, fromB = {{"input_digests_from", "/run/b.json"}},
               computed = json::object();
    json merged = fromB;  // a copy of a part's record, as the merges begin
    vri::mergeDigestSources(merged, {computed, computed});
    CHECK_FALSE(merged.contains("input_digests_from"));
    merged = computed;
    vri::mergeDigestSources(merged, {computed, fromA, fromA});  // the first part computed its own
    CHECK(merged["input_digests_from"] == "/run/a.json");
    vri::mergeDigestSources(merged, {fromA, fromB, computed, fromA});
    CHECK(merged["input_digests_from"] == json::array({"/run/a.json", "/run/b.json"}));
}
