#include "libvri/render/merged_digest_sources.h"

#include <algorithm>
#include <string>

namespace vri {

void mergeDigestSources(nlohmann::json& merged, const std::vector<nlohmann::json>& parts) {
    constexpr const char* kKey = "input_digests_from";
    std::vector<std::string> records;  // in the parts' order, each once
    for (const nlohmann::json& part : parts)
        if (const auto it = part.find(kKey); it != part.end() && it->is_string())
            if (std::ranges::find(records, it->get<std::string>()) == records.end())
                records.push_back(it->get<std::string>());
    merged.erase(kKey);
    if (records.size() == 1) merged[kKey] = records.front();
    if (records.size() > 1) merged[kKey] = records;
}

}  // namespace vri
