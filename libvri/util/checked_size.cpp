#include "libvri/util/checked_size.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "libvri/util/error.h"

namespace vri {

namespace {

// Counts up to 2^53 exactly (rounded down), beyond that in three significant digits ("about 7.38e+19").
std::string amountText(double amount) {
    if (amount >= 0.0 && amount <= 9007199254740992.0) return std::to_string(static_cast<std::uint64_t>(amount));
    char text[32];
    std::snprintf(text, sizeof text, "about %.3g", amount);
    return text;
}

double productAsDouble(std::initializer_list<std::uint64_t> factors) {
    double product = 1.0;
    for (std::uint64_t f : factors) product *= static_cast<double>(f);
    return product;
}

[[noreturn]] void refuse(const std::string& what, const std::string& needed, std::uint64_t limit,
                         std::string_view unit, std::string_view hint = {}) {
    throw OverLimit(what + ": needs " + needed + " " + std::string(unit) + ", limit " + std::to_string(limit) +
                    std::string(hint));
}

}  // namespace

std::uint64_t byteLimit() {
    const char* text = std::getenv("VRI_MAX_BYTES");
    if (!text) return kDefaultByteLimit;
    const std::string_view s(text);
    std::uint64_t limit = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), limit);
    if (ec != std::errc() || end != s.data() + s.size() || limit == 0)
        throw Error("VRI_MAX_BYTES: expected a positive byte count, got '" + std::string(s) + "'");
    return limit;
}

bool byteLimitIsExplicit() { return std::getenv("VRI_MAX_BYTES") != nullptr; }

std::optional<std::uint64_t> checkedProduct(std::initializer_list<std::uint64_t> factors) {
    std::uint64_t product = 1;
    for (std::uint64_t f : factors) {
        if (f != 0 && product > std::numeric_limits<std::uint64_t>::max() / f) {
            // Overflow unless a later factor is zero.
            for (std::uint64_t g : factors)
                if (g == 0) return 0;
            return std::nullopt;
        }
        product *= f;
    }
    return product;
}

std::uint64_t checkedCount(const std::string& what, std::initializer_list<std::uint64_t> factors, std::uint64_t limit,
                           std::string_view unit) {
    const std::optional<std::uint64_t> product = checkedProduct(factors);
    if (!product) refuse(what, amountText(productAsDouble(factors)), limit, unit);
    if (*product > limit) refuse(what, std::to_string(*product), limit, unit);
    return *product;
}

std::size_t checkedBytes(const std::string& what, std::initializer_list<std::uint64_t> factors) {
    const std::uint64_t limit = std::min<std::uint64_t>(byteLimit(), std::numeric_limits<std::size_t>::max());
    constexpr std::string_view hint = " (VRI_MAX_BYTES)";
    const std::optional<std::uint64_t> product = checkedProduct(factors);
    if (!product) refuse(what, amountText(productAsDouble(factors)), limit, "bytes", hint);
    if (*product > limit) refuse(what, std::to_string(*product), limit, "bytes", hint);
    return static_cast<std::size_t>(*product);
}

std::size_t checkedUnpackedBytes(const std::string& what, std::initializer_list<std::uint64_t> factors,
                                 std::uint64_t packedBytes, std::string_view packedWhat, std::uint64_t maxExpansion) {
    const std::size_t bytes = checkedBytes(what, factors);
    if (byteLimitIsExplicit()) return bytes;
    const std::uint64_t plausible =
        std::max(kAlwaysPlausibleBytes, checkedProduct({packedBytes, maxExpansion}).value_or(std::numeric_limits<std::uint64_t>::max()));
    if (bytes > plausible)
        throw OverLimit(what + ": needs " + std::to_string(bytes) + " bytes, limit " + std::to_string(plausible) +
                        " for " + std::string(packedWhat) + " of " + std::to_string(packedBytes) + " bytes (" +
                        std::to_string(maxExpansion) + " times its size or 256 MiB; set VRI_MAX_BYTES to allow more)");
    return bytes;
}

void requireWithin(const std::string& what, double amount, double limit, std::string_view unit) {
    if (amount >= 0.0 && amount <= limit) return;
    throw OverLimit(what + ": needs " + (std::isfinite(amount) ? amountText(amount) : "unboundedly many") + " " +
                    std::string(unit) + ", limit " + amountText(limit));
}

bool isSizeRefusal(const Error& e) {
    return dynamic_cast<const OverLimit*>(&e) != nullptr || dynamic_cast<const OutOfMemory*>(&e) != nullptr;
}

void throwLike(const Error& e, const std::string& message) {
    if (dynamic_cast<const OverLimit*>(&e)) throw OverLimit(message);
    if (dynamic_cast<const OutOfMemory*>(&e)) throw OutOfMemory(message);
    throw Error(message);
}

}  // namespace vri
