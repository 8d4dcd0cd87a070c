#pragma once
// The stats record's schema: every field of the "stats" and "timing" records that vri-render, vri-reference
// and vri-outside write to a --stats file, where it sits and how the tiles of one image combine it, declared
// once. The writers (render_json.cpp, exact_reference_json.cpp, render_job.cpp), the tile merger
// (tile_merge.cpp) and the readers (report/, the experiment ledger, Python) all name a field by its constant
// here, so a field renamed or removed is a compile error in each of them, not a reader that silently finds
// nothing; and a table's value path ("stats.wal_seconds") is checked against the schema before any file is read.
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace vri {

// How a field of the tiles' records becomes the whole image's. Arrays combine element by element.
enum class TileRule {
    Sum,         // counts (rays, samples, pieces, pixels) and seconds: the tiles ran one after another
    Max,         // maxima (error bounds, the most early termination left out, the largest value)
    Min,         // minima (the smallest value)
    PixelMean,   // a mean over pixels: the tiles' means weighted by their pixels ("rays")
    All,         // true when true in every tile (setup_reused)
    Same,        // a property of the render (backend, threads, ...): kept when every tile agrees
    Agree,       // the same in every tile, else the tiles are refused (timing.repeats: frames are summed)
    FirstPixel,  // a pixel in whole-image coordinates: the first in row order of the tiles that have one
    Derived,     // recomputed from the combined fields (samples_per_second, the median and its interval)
};

struct StatsField {
    std::string_view pointer;  // JSON pointer into a stats file: "/stats/error_bound/max"
    TileRule rule;

    nlohmann::json::json_pointer at() const { return nlohmann::json::json_pointer(std::string(pointer)); }
    std::string dotted() const;  // "stats.error_bound.max", as messages and value paths spell it
};

// The fields. An object field (max_error_search, timing.load, machine) is combined as a whole.
namespace stats_field {
// Every render (render_json.cpp).
inline constexpr StatsField wallSeconds{"/stats/wall_seconds", TileRule::Sum};
inline constexpr StatsField setupSeconds{"/stats/setup_seconds", TileRule::Sum};  // each tile built its own
inline constexpr StatsField setupReused{"/stats/setup_reused", TileRule::All};
inline constexpr StatsField threads{"/stats/threads", TileRule::Same};
inline constexpr StatsField rays{"/stats/rays", TileRule::Sum};
inline constexpr StatsField raysHit{"/stats/rays_hit", TileRule::Sum};
inline constexpr StatsField samplesPlaced{"/stats/samples_placed", TileRule::Sum};
inline constexpr StatsField samplesEvaluated{"/stats/samples_evaluated", TileRule::Sum};
inline constexpr StatsField samplesPerSecond{"/stats/samples_per_second", TileRule::Derived};
inline constexpr StatsField emptyBrickFraction{"/stats/empty_brick_fraction", TileRule::Same};
inline constexpr StatsField raysTerminated{"/stats/rays_terminated", TileRule::Sum};
inline constexpr StatsField terminationLeftOutMax{"/stats/termination_left_out_max", TileRule::Max};
inline constexpr StatsField backend{"/stats/backend", TileRule::Same};  // "cpu", "vulkan", "outside"
inline constexpr StatsField device{"/stats/device", TileRule::Same};
inline constexpr StatsField interpolation{"/stats/interpolation", TileRule::Same};
inline constexpr StatsField simdTarget{"/stats/simd_target", TileRule::Same};
inline constexpr StatsField voxelLoads{"/stats/voxel_loads", TileRule::Same};
inline constexpr StatsField nonfinitePixels{"/stats/nonfinite_pixels", TileRule::Sum};
inline constexpr StatsField firstNonfinitePixel{"/stats/first_nonfinite_pixel", TileRule::FirstPixel};
inline constexpr StatsField maxErrorSearch{"/stats/max_error_search", TileRule::Same};
// The adaptive Simpson methods' counts (AdaptiveCounts).
inline constexpr StatsField adaptiveInnerTries{"/stats/adaptive/inner_tries", TileRule::Sum};
inline constexpr StatsField adaptiveInnerFailures{"/stats/adaptive/inner_failures", TileRule::Sum};
inline constexpr StatsField adaptiveOuterTries{"/stats/adaptive/outer_tries", TileRule::Sum};
inline constexpr StatsField adaptiveOuterFailures{"/stats/adaptive/outer_failures", TileRule::Sum};
inline constexpr StatsField adaptiveOuterSteps{"/stats/adaptive/outer_steps", TileRule::Sum};
inline constexpr StatsField adaptiveAcceptedAtMinimum{"/stats/adaptive/accepted_at_h_min_above_tolerance", TileRule::Sum};
inline constexpr StatsField adaptivePointsUsed{"/stats/adaptive/points_used", TileRule::Sum};
inline constexpr StatsField adaptivePointsEvaluated{"/stats/adaptive/points_evaluated", TileRule::Sum};
// Simpson's steps against the range where they mean something (simpson_range.h).
inline constexpr StatsField simpsonRangeLimit{"/stats/simpson_range/tau_h_limit", TileRule::Same};
inline constexpr StatsField simpsonRangeLargest{"/stats/simpson_range/largest_tau_h", TileRule::Max};
inline constexpr StatsField simpsonRangePixelsBeyond{"/stats/simpson_range/pixels_beyond", TileRule::Sum};
// The pre-integration table and its measured error: every tile builds the same table.
inline constexpr StatsField preintSize{"/stats/preintegration/size", TileRule::Same};
inline constexpr StatsField preintOrder{"/stats/preintegration/order", TileRule::Same};
inline constexpr StatsField preintSegmentLength{"/stats/preintegration/segment_length", TileRule::Same};
inline constexpr StatsField preintErrorColour{"/stats/preintegration/table_error_colour", TileRule::Same};
inline constexpr StatsField preintErrorAlpha{"/stats/preintegration/table_error_alpha", TileRule::Same};
inline constexpr StatsField preintPointsChecked{"/stats/preintegration/table_points_checked", TileRule::Same};
inline constexpr StatsField preintCheckedDeltas{"/stats/preintegration/table_checked_deltas", TileRule::Same};
inline constexpr StatsField preintErrorColourByDelta{"/stats/preintegration/table_error_colour_by_delta",
                                                     TileRule::Same};
inline constexpr StatsField preintErrorAlphaByDelta{"/stats/preintegration/table_error_alpha_by_delta", TileRule::Same};
// Order 2 on the CPU: the largest |delta| the render asked, and the errors checked up to it (upTo).
inline constexpr StatsField preintLargestDelta{"/stats/preintegration/largest_delta", TileRule::Max};
inline constexpr StatsField preintLookupsByDelta{"/stats/preintegration/lookups_by_delta", TileRule::Sum};
inline constexpr StatsField preintErrorColourUsed{"/stats/preintegration/table_error_colour_used", TileRule::Max};
inline constexpr StatsField preintErrorAlphaUsed{"/stats/preintegration/table_error_alpha_used", TileRule::Max};
// Values outside [0, 1] as the method returned them (out_of_range_pixels.h).
inline constexpr StatsField outOfRangePixels{"/stats/out_of_range_pixels/pixels", TileRule::Sum};
inline constexpr StatsField outOfRangeAbove{"/stats/out_of_range_pixels/channels_above_1", TileRule::Sum};
inline constexpr StatsField outOfRangeBelow{"/stats/out_of_range_pixels/channels_below_0", TileRule::Sum};
inline constexpr StatsField outOfRangeMax{"/stats/out_of_range_pixels/max", TileRule::Max};
inline constexpr StatsField outOfRangeMin{"/stats/out_of_range_pixels/min", TileRule::Min};
// The exact method's (exact_reference_json.cpp).
inline constexpr StatsField raysOpaque{"/stats/rays_opaque", TileRule::Sum};
inline constexpr StatsField raysWholeSubPieceWindow{"/stats/rays_whole_sub_piece_window", TileRule::Sum};
inline constexpr StatsField pieces{"/stats/pieces", TileRule::Sum};
inline constexpr StatsField piecesVisible{"/stats/pieces_visible", TileRule::Sum};
inline constexpr StatsField subPieces{"/stats/sub_pieces", TileRule::Sum};
inline constexpr StatsField quadratureIntervals{"/stats/quadrature_intervals", TileRule::Sum};
inline constexpr StatsField quadratureNodes{"/stats/quadrature_nodes", TileRule::Sum};
inline constexpr StatsField errorBoundChannels{"/stats/error_bound/channels", TileRule::Same};
inline constexpr StatsField errorBoundMax{"/stats/error_bound/max", TileRule::Max};
inline constexpr StatsField errorBoundMean{"/stats/error_bound/mean", TileRule::PixelMean};
inline constexpr StatsField errorBoundAppliesTo{"/stats/error_bound/applies_to", TileRule::Same};
inline constexpr StatsField errorBoundRoundingMax{"/stats/error_bound/float32_rounding_max", TileRule::Max};
inline constexpr StatsField errorBoundStoredMax{"/stats/error_bound/stored_max", TileRule::Max};
inline constexpr StatsField errorBoundErrorImage{"/stats/error_bound/error_image", TileRule::Same};
// An outside renderer's image (vri-outside): how its values were quantised.
inline constexpr StatsField quantisation{"/stats/quantisation", TileRule::Same};
// The frames (frameTimingRecord, render_job.h): frame k of the whole is frame k of every tile, one after another.
inline constexpr StatsField warmUpFrames{"/timing/warm_up_frames", TileRule::Agree};
inline constexpr StatsField repeats{"/timing/repeats", TileRule::Agree};
inline constexpr StatsField frameSeconds{"/timing/wall_seconds", TileRule::Sum};
inline constexpr StatsField medianFrameSeconds{"/timing/median_wall_seconds", TileRule::Derived};
inline constexpr StatsField medianCi{"/timing/median_ci", TileRule::Derived};
inline constexpr StatsField load{"/timing/load", TileRule::Same};
inline constexpr StatsField timed{"/timing/timed", TileRule::Same};  // what an outside renderer's seconds cover
inline constexpr StatsField machine{"/machine", TileRule::Same};     // tiles may run on different machines
}  // namespace stats_field

// Sets a field of a stats file's record.
inline void put(nlohmann::json& record, const StatsField& field, nlohmann::json value) {
    record[field.at()] = std::move(value);
}

// Every field above, in that order.
std::span<const StatsField> statsSchema();

// The field a JSON pointer ("/stats/error_bound/max/2", within stats.error_bound.max) or a dotted value path
// ("stats.error_bound.max.2") names or lies within, or nullptr.
const StatsField* statsFieldAt(std::string_view pointer);
const StatsField* statsFieldOf(std::string_view dotted);

// Throws vri::Error when a value path into a stats file ("stats.wall_seconds", or "1/" and one for its
// reciprocal) begins with "stats." or "timing." but names no field of the schema; `what` begins the message.
void requireStatsField(std::string_view expression, const std::string& what);

}  // namespace vri
