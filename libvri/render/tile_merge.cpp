#include "libvri/render/tile_merge.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>

#include "libvri/core/brick_layers.h"
#include "libvri/render/merged_digest_sources.h"
#include "libvri/render/render_job.h"  // medianIntervalRecord
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"
#include "libvri/util/printable.h"
#include "libvri/util/statistics.h"

namespace vri {

namespace {

using nlohmann::json;

// The largest count or time a tile's stats may hold: 2^53, beyond which a double no longer counts by one,
// and no sum of a few thousand tiles' overflows 64 bits.
constexpr long long kMostCount = 1LL << 53;

// Sum, Max, Min or PixelMean of numbers (`weights`: each tile's pixels, for PixelMean); nullopt when a
// value is not a number.
std::optional<json> combineNumbers(TileRule rule, const std::vector<const json*>& values,
                                   const std::vector<double>& weights) {
    if (!std::ranges::all_of(values, [](const json* v) { return v->is_number(); })) return std::nullopt;
    if (rule == TileRule::Sum && std::ranges::all_of(values, [](const json* v) { return v->is_number_unsigned(); })) {
        std::uint64_t sum = 0;  // counts stay exact integers
        for (const json* v : values) sum += v->get<std::uint64_t>();
        return json(sum);
    }
    double result = values[0]->get<double>(), pixels = 0.0;
    if (rule == TileRule::Sum || rule == TileRule::PixelMean) result = 0.0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = values[i]->get<double>();
        if (rule == TileRule::Sum) result += v;
        else if (rule == TileRule::Max) result = std::max(result, v);
        else if (rule == TileRule::Min) result = std::min(result, v);
        else {
            result += v * weights[i];
            pixels += weights[i];
        }
    }
    return json(rule == TileRule::PixelMean ? result / pixels : result);
}

class StatsCombiner {
public:
    StatsCombiner(const std::vector<json>& records, const std::vector<std::string>& names)
        : records_(records), names_(names) {
        for (std::size_t i = 0; i < records.size(); ++i)
            weights_.push_back(static_cast<double>(wholeNumberAt(records[i], stats_field::rays.dotted(), names[i], 0, kMostCount)));
    }

    // The combined value at `pointer`, or null (noted in notCombined) when it cannot be combined.
    json combine(const std::string& pointer) {
        std::vector<const json*> values;
        const json::json_pointer at(pointer);
        for (const json& r : records_)
            if (r.contains(at)) values.push_back(&r.at(at));
        const StatsField* field = statsFieldAt(pointer);
        const std::optional<TileRule> rule = field ? std::optional(field->rule) : std::nullopt;
        if (rule == TileRule::FirstPixel) return firstPixel(values);
        if (values.size() != records_.size()) return notCombined(pointer);
        const bool objects = std::ranges::all_of(values, [](const json* v) { return v->is_object(); });
        if (objects && rule != TileRule::Same && rule != TileRule::Agree) {
            json out = json::object();
            for (const json* v : values)
                for (const auto& [key, unused] : v->items())
                    // A key of a file edited by hand may hold '~' or '/': json_pointer escapes it (fuzzing found it).
                    if (!out.contains(key)) out[key] = combine((json::json_pointer(pointer) / key).to_string());
            return out;
        }
        if (!rule) return notCombined(pointer);
        switch (*rule) {
        case TileRule::Same:
        case TileRule::Agree:
            for (std::size_t i = 1; i < values.size(); ++i)
                if (*values[i] != *values[0]) {
                    if (rule == TileRule::Same) return notCombined(pointer);
                    throw Error(names_[i] + ": " + dottedPath(pointer) + " is " + values[i]->dump() + ", but " + names_[0] +
                                " has " + values[0]->dump() + " (the tiles of one image must agree in it)");
                }
            return *values[0];
        case TileRule::All:
            if (!std::ranges::all_of(values, [](const json* v) { return v->is_boolean(); })) return notCombined(pointer);
            return std::ranges::all_of(values, [](const json* v) { return v->get<bool>(); });
        case TileRule::Derived:
            return nullptr;  // filled in from the combined fields
        default:
            break;
        }
        if (values[0]->is_array()) {  // element by element
            json out = json::array();
            for (std::size_t k = 0; k < values[0]->size(); ++k) {
                std::vector<const json*> elements;
                for (std::size_t i = 0; i < values.size(); ++i) {
                    if (!values[i]->is_array() || values[i]->size() != values[0]->size())
                        throw Error(names_[i] + ": " + dottedPath(pointer) + " has " + std::to_string(values[i]->size()) +
                                    " elements, but " + names_[0] + " has " + std::to_string(values[0]->size()));
                    elements.push_back(&(*values[i])[k]);
                }
                const std::optional<json> e = combineNumbers(*rule, elements, weights_);
                if (!e) return notCombined(pointer);
                out.push_back(*e);
            }
            return out;
        }
        if (*rule == TileRule::Sum) requireCounts(values, pointer);
        const std::optional<json> v = combineNumbers(*rule, values, weights_);
        return v ? *v : notCombined(pointer);
    }

    json notCombinedList() const { return notCombined_; }

private:
    // What is summed (counts, seconds) is a finite number >= 0 that a sum of them cannot overflow: a stats
    // file edited to rays 1e308 or seconds -5 is named, not added.
    void requireCounts(const std::vector<const json*>& values, const std::string& pointer) const {
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (!values[i]->is_number()) continue;  // not combined, as before
            const double v = values[i]->get<double>();
            if (!(v >= 0.0 && v <= static_cast<double>(kMostCount)))
                throw Error(names_[i] + ": " + dottedPath(pointer) + ": expected a count or a time in [0, 2^53], got " +
                            printableShort(values[i]->dump(), 40));
        }
    }

    json notCombined(const std::string& pointer) {
        notCombined_.push_back(dottedPath(pointer));
        return nullptr;
    }

    // The first pixel [x, y] in row order among the tiles that have one.
    json firstPixel(const std::vector<const json*>& values) {
        const json* first = nullptr;
        for (const json* v : values) {
            if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number_integer() || !(*v)[1].is_number_integer())
                return nullptr;
            if (!first || std::pair((*v)[1].get<int>(), (*v)[0].get<int>()) <
                              std::pair((*first)[1].get<int>(), (*first)[0].get<int>()))
                first = v;
        }
        return first ? *first : json(nullptr);
    }

    const std::vector<json>& records_;
    const std::vector<std::string>& names_;
    std::vector<double> weights_;
    json notCombined_ = json::array();
};

// The tiles' record of `key`, which every tile must have and share with the first.
void requireShared(const std::vector<json>& records, const std::vector<std::string>& names, const char* key) {
    for (std::size_t i = 0; i < records.size(); ++i) {
        if (!records[i].contains(key))
            throw Error(names[i] + ": has no \"" + key + "\" (expected the stats file of vri-render or vri-reference)");
        if (records[i][key] == records[0][key]) continue;
        // Tiles rendered with --max-error each searched their own pixels: say so rather than "options differ".
        const json& a = records[0][key];
        const json& b = records[i][key];
        if (std::string_view(key) == "options" && a.is_object() && b.is_object() && a.contains("max_error") &&
            a.value("max_error", json()) == b.value("max_error", json()) && a.value("tolerance", json()) != b.value("tolerance", json()))
            throw Error(names[i] + ": found tolerance " + b["tolerance"].dump() + " for --max-error " +
                        a["max_error"].dump() + " where " + names[0] + " found " + a["tolerance"].dump() +
                        " (each tile searched its own pixels): render the tiles with one --tolerance, e.g. the one "
                        "an untiled --max-error run records");
        throw Error(names[i] + ": its \"" + key + "\" differs from " + names[0] +
                    "'s (the tiles of one image share tool, build, inputs, scene, transfer function, camera and options)");
    }
}

}  // namespace

json combineTileStats(const std::vector<json>& records, const std::vector<std::string>& names) {
    using namespace stats_field;
    StatsCombiner combiner(records, names);
    json out = {{"stats", combiner.combine("/stats")}, {"timing", combiner.combine("/timing")}};
    if (std::ranges::all_of(records, [](const json& r) { return r.contains(machine.at()); }))
        out[machine.at()] = combiner.combine(std::string(machine.pointer));
    // The derived fields, from the combined ones; null and listed as not combined where those are not numbers.
    json notCombined = combiner.notCombinedList();
    const auto underived = [&](const StatsField& field) {
        if (!out.contains(field.at())) return;
        out[field.at()] = nullptr;
        notCombined.push_back(field.dotted());
    };
    const json samples = out.value(samplesEvaluated.at(), json()), seconds = out.value(wallSeconds.at(), json());
    if (samples.is_number() && seconds.is_number()) {
        if (out.contains(samplesPerSecond.at()))  // as render_json.cpp computes it
            out[samplesPerSecond.at()] = seconds.get<double>() > 0 ? samples.get<double>() / seconds.get<double>() : 0.0;
    } else {
        underived(samplesPerSecond);
    }
    const json frames = out.value(frameSeconds.at(), json());
    if (frames.is_array() && !frames.empty() && std::ranges::all_of(frames, [](const json& f) { return f.is_number(); })) {
        const std::vector<double> times = frames.get<std::vector<double>>();
        if (out.contains(medianFrameSeconds.at())) out[medianFrameSeconds.at()] = median(times);
        if (out.contains(medianCi.at())) out[medianCi.at()] = medianIntervalRecord(times);
    } else {
        underived(medianFrameSeconds);
        underived(medianCi);
    }
    out["not_combined"] = std::move(notCombined);
    return out;
}

MergedTiles mergeTiles(const std::vector<TileFiles>& tiles) {
    if (tiles.empty()) throw Error("no tiles to merge");
    std::vector<json> records;
    std::vector<std::string> names;
    for (const TileFiles& t : tiles) {
        records.push_back(readJsonFile(t.stats));
        names.push_back(t.stats);
    }
    for (const char* key : {"tool", "build", "inputs", "scene", "transfer_function", "camera", "options"})
        requireShared(records, names, key);
    // Sizes from the files, range-checked before they size anything.
    constexpr long long kLargest = std::numeric_limits<int>::max();
    const int width = static_cast<int>(wholeNumberAt(records[0], "camera.width", names[0], 1, kLargest));
    const int height = static_cast<int>(wholeNumberAt(records[0], "camera.height", names[0], 1, kLargest));
    const std::string imageSize = std::to_string(width) + "x" + std::to_string(height);

    std::vector<PixelRegion> regions;
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        if (!records[i].contains("region"))
            throw Error(names[i] + ": has no \"region\" (not a tile: render one with --region X,Y,WIDTH,HEIGHT)");
        const auto at = [&](const char* key, long long lo) {
            return static_cast<int>(wholeNumberAt(records[i], std::string("region.") + key, names[i], lo, kLargest));
        };
        const PixelRegion r{at("x", 0), at("y", 0), at("width", 1), at("height", 1)};
        if (!r.inside(width, height))
            throw Error(names[i] + ": region " + r.text() + " is not inside its camera's " + imageSize + " image");
        regions.push_back(r);
    }
    // The tiles cover the image once: no two overlap (rectangle against rectangle), and their areas add up
    // to the image's. Nothing the size of the image is made before the tiles' own images have been read.
    std::uint64_t covered = 0;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const PixelRegion& r = regions[i];
        for (std::size_t j = 0; j < i; ++j) {
            const PixelRegion& o = regions[j];
            const int x = std::max(r.x, o.x), y = std::max(r.y, o.y);
            if (x < std::min(r.x + r.width, o.x + o.width) && y < std::min(r.y + r.height, o.y + o.height))
                throw Error(names[i] + ": region " + r.text() + " overlaps " + names[j] + "'s region " + o.text() +
                            " at pixel " + std::to_string(x) + "," + std::to_string(y) +
                            " (tiles must cover the image once)");
        }
        covered += static_cast<std::uint64_t>(r.width) * static_cast<std::uint64_t>(r.height);
    }
    const std::uint64_t pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    if (covered != pixels)
        throw Error("the tiles cover " + std::to_string(covered) + " of the " + imageSize + " image's " +
                    std::to_string(pixels) + " pixels (tiles must cover the image once)");

    // A render's tiles are RGBA; a brick's (its scene names the brick) are its layer's channels (brick_layers.h).
    const bool layer = records[0]["scene"].is_object() && records[0]["scene"].contains("brick");
    const Image shape = layer ? brickLayerImage(1, 1) : Image(1, 1);
    std::vector<Image> images;
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        const PixelRegion& r = regions[i];
        Image tile = readImage(tiles[i].image);
        if (tile.width != r.width || tile.height != r.height || tile.channelNames != shape.channelNames)
            throw Error(tiles[i].image + ": a " + std::to_string(tile.width) + "x" + std::to_string(tile.height) +
                        " image of " + std::to_string(tile.channels) + " channels, but " + names[i] + " says a " +
                        (layer ? "brick layer's" : "RGBA") + " region " + r.text());
        const ImageMetadata metadata = readImageMetadata(tiles[i].image);
        const auto said = std::ranges::find(metadata, std::string("vri:region"), &ImageMetadata::value_type::first);
        if (said == metadata.end() || said->second != r.text())
            throw Error(tiles[i].image + ": its vri:region is '" + (said == metadata.end() ? "" : said->second.substr(0, 60)) +
                        "', but " + names[i] + " says " + r.text() + " (an image and stats of different tiles?)");
        images.push_back(std::move(tile));
    }
    MergedTiles merged;
    // As many pixels as the tiles' images hold: checked above.
    merged.image = layer ? brickLayerImage(width, height) : Image(width, height);
    const std::ptrdiff_t channels = shape.channels;
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        const PixelRegion& r = regions[i];
        for (int y = 0; y < r.height; ++y)
            std::copy_n(images[i].pixels.begin() + std::ptrdiff_t(y) * r.width * channels,
                        std::size_t(r.width) * std::size_t(channels), &merged.image.at(r.x, r.y + y, 0));
        images[i] = Image();  // each tile's pixels freed once copied
    }

    json record = records[0];
    for (const char* key : {"region", "command", "time_utc"}) record.erase(key);
    const json combined = combineTileStats(records, names);
    for (const auto& [key, value] : combined.items()) record[key] = value;
    mergeDigestSources(record, records);
    record["tiles"] = json::array();
    for (std::size_t i = 0; i < tiles.size(); ++i)
        record["tiles"].push_back({{"image", tiles[i].image},
                                   {"stats", tiles[i].stats},
                                   {"region", records[i]["region"]},
                                   {"command", records[i].value("command", json())},
                                   {"time_utc", records[i].value("time_utc", json())}});
    merged.record = std::move(record);
    // The attributes vri-render writes (render_job.cpp), from the tiles' shared records.
    merged.metadata = {{"vri:options", records[0]["options"].dump()}, {"vri:scene", records[0]["scene"].dump()}};
    return merged;
}

}  // namespace vri
