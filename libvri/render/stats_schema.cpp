#include "libvri/render/stats_schema.h"

#include <algorithm>
#include <array>

#include "libvri/util/error.h"
#include "libvri/util/json_file.h"
#include "libvri/util/printable.h"

namespace vri {

std::string StatsField::dotted() const { return dottedPath(pointer); }

std::span<const StatsField> statsSchema() {
    using namespace stats_field;
    static constexpr std::array fields = {
        wallSeconds,
        setupSeconds,
        setupReused,
        threads,
        rays,
        raysHit,
        samplesPlaced,
        samplesEvaluated,
        samplesPerSecond,
        emptyBrickFraction,
        raysTerminated,
        terminationLeftOutMax,
        backend,
        device,
        interpolation,
        simdTarget,
        voxelLoads,
        nonfinitePixels,
        firstNonfinitePixel,
        maxErrorSearch,
        adaptiveInnerTries,
        adaptiveInnerFailures,
        adaptiveOuterTries,
        adaptiveOuterFailures,
        adaptiveOuterSteps,
        adaptiveAcceptedAtMinimum,
        adaptivePointsUsed,
        adaptivePointsEvaluated,
        simpsonRangeLimit,
        simpsonRangeLargest,
        simpsonRangePixelsBeyond,
        preintSize,
        preintOrder,
        preintSegmentLength,
        preintErrorColour,
        preintErrorAlpha,
        preintPointsChecked,
        preintCheckedDeltas,
        preintErrorColourByDelta,
        preintErrorAlphaByDelta,
        preintLargestDelta,
        preintLookupsByDelta,
        preintErrorColourUsed,
        preintErrorAlphaUsed,
        outOfRangePixels,
        outOfRangeAbove,
        outOfRangeBelow,
        outOfRangeMax,
        outOfRangeMin,
        raysOpaque,
        raysWholeSubPieceWindow,
        pieces,
        piecesVisible,
        subPieces,
        quadratureIntervals,
        quadratureNodes,
        errorBoundChannels,
        errorBoundMax,
        errorBoundMean,
        errorBoundAppliesTo,
        errorBoundRoundingMax,
        errorBoundStoredMax,
        errorBoundErrorImage,
        quantisation,
        warmUpFrames,
        repeats,
        frameSeconds,
        medianFrameSeconds,
        medianCi,
        load,
        timed,
        machine,
    };
    return fields;
}

const StatsField* statsFieldAt(std::string_view pointer) {
    for (const StatsField& field : statsSchema())
        if (pointer == field.pointer || (pointer.starts_with(field.pointer) && pointer[field.pointer.size()] == '/'))
            return &field;
    return nullptr;
}

const StatsField* statsFieldOf(std::string_view dotted) {
    std::string pointer = "/" + std::string(dotted);
    std::ranges::replace(pointer, '.', '/');
    return statsFieldAt(pointer);
}

void requireStatsField(std::string_view expression, const std::string& what) {
    const std::string dotted(expression.starts_with("1/") ? expression.substr(2) : expression);
    if (!dotted.starts_with("stats.") && !dotted.starts_with("timing.")) return;
    if (statsFieldOf(dotted)) return;
    // The fields of the same record whose names share the most leading characters, as a hint.
    std::string hint;
    std::size_t best = 0;
    for (const StatsField& field : statsSchema()) {
        const std::string name = field.dotted();
        const std::size_t shared = static_cast<std::size_t>(std::ranges::mismatch(name, dotted).in1 - name.begin());
        if (shared > best) best = shared, hint = name;
    }
    throw Error(what + ": '" + printableShort(dotted) + "' is no field of a render's stats" +
                (hint.empty() ? "" : " (nearest: " + hint + ")") +
                "; docs/stats.md lists them");
}

}  // namespace vri
