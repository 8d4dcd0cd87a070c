#pragma once
// Where the input digests of a merged record's parts came from (util/input_digest.h): the parts of one render
// (tiles, a brick's layers) each say it (`input_digests_from`), and a part that computed its digests itself says
// nothing. The merged record names every record its parts took digests from.
#include <vector>

#include <nlohmann/json.hpp>

namespace vri {

// Sets merged["input_digests_from"] to the one record the parts name (a path), to the list of them where they
// name several, and erases it where none names one.
void mergeDigestSources(nlohmann::json& merged, const std::vector<nlohmann::json>& parts);

}  // namespace vri
