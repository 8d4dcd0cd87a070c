#pragma once
// Sizes taken from input (dims, image sizes, sizes in file metadata, counts on the command line) are
// checked before anything is allocated or looped over: the product must not overflow and must stay
// within a stated limit, or the input is refused with one line that names it and says how much it
// asks for ("<what>: needs N bytes, limit M"). A wrapped product or a bare std::bad_alloc says neither.
#include <cstdint>
#include <initializer_list>
#include <new>
#include <optional>
#include <string>
#include <string_view>

#include "libvri/util/error.h"

namespace vri {

// The most bytes one buffer sized from input may take: 2^34 (16 GiB), or the byte count in the
// environment variable VRI_MAX_BYTES. Throws vri::Error when that variable is not a positive integer.
inline constexpr std::uint64_t kDefaultByteLimit = std::uint64_t(1) << 34;
std::uint64_t byteLimit();
// True when VRI_MAX_BYTES is set: the user has stated the limit and plausibility guesses step aside.
bool byteLimitIsExplicit();

// The product of `factors`, or nullopt when it does not fit in 64 bits.
std::optional<std::uint64_t> checkedProduct(std::initializer_list<std::uint64_t> factors);

// The product of `factors` as a count of `unit` (samples, runs, rows); throws
// vri::Error("<what>: needs N <unit>, limit M") when it overflows or exceeds `limit`.
std::uint64_t checkedCount(const std::string& what, std::initializer_list<std::uint64_t> factors, std::uint64_t limit,
                           std::string_view unit);

// The product of `factors` as a byte count within byteLimit() (and within size_t); the message
// names VRI_MAX_BYTES, the way to raise the limit.
std::size_t checkedBytes(const std::string& what, std::initializer_list<std::uint64_t> factors);

// Data that unpack (a deflate stream, a compressed TIFF page, a sparse grid's tiles) can claim far more
// bytes than the file holds them in: 110 bytes of header claiming 4 GiB are far more likely an error or an
// attack than a volume, and the claim alone must not make the reader allocate. So, unless VRI_MAX_BYTES
// states the limit, the product of `factors` may be at most `maxExpansion` times the `packedBytes` it
// unpacks from, or kAlwaysPlausibleBytes whatever those are; and always within checkedBytes' limit.
// Throws vri::Error("<what>: needs N bytes, limit L for <packedWhat> of P bytes (R times its size or
// 256 MiB; set VRI_MAX_BYTES to allow more)").
inline constexpr std::uint64_t kAlwaysPlausibleBytes = std::uint64_t(1) << 28;
// A deflate stream's ratio: zlib reaches 1032 on a run of zeros; real volumes stay far below 256 (the
// test volumes 1 to 51).
inline constexpr std::uint64_t kPlausibleCompressedExpansion = 256;
// A sparse grid stores one tile for a constant region, so its file says little about its dense size.
inline constexpr std::uint64_t kPlausibleSparseExpansion = 1024;
std::size_t checkedUnpackedBytes(const std::string& what, std::initializer_list<std::uint64_t> factors,
                                 std::uint64_t packedBytes, std::string_view packedWhat, std::uint64_t maxExpansion);

// A size beyond its limit, as every refusal above throws it ("<what>: needs N <unit>, limit M"): what it
// names is the object, so a reader that knows the file puts the file's name in front.
class OverLimit : public Error {
public:
    using Error::Error;
};

// A size within the limit that the machine still cannot give (VRI_MAX_BYTES above its memory, a
// ulimit, other processes): a bare std::bad_alloc would say neither what nor how much.
class OutOfMemory : public Error {
public:
    using Error::Error;
};

// True for the two refusals of a size above (OverLimit, OutOfMemory).
bool isSizeRefusal(const Error& e);
// Throws an error of e's class (OverLimit, OutOfMemory, else Error) saying `message`: a reader that puts a
// file's name in front keeps what the error is.
[[noreturn]] void throwLike(const Error& e, const std::string& message);

// Runs allocate(), which allocates `bytes` for `what`; its std::bad_alloc becomes
// OutOfMemory("<what>: needs N bytes: out of memory"). A reader that knows the file adds its name.
template <class Allocate>
decltype(auto) allocateOrExplain(const std::string& what, std::uint64_t bytes, Allocate&& allocate) {
    try {
        return allocate();
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(what + ": needs " + std::to_string(bytes) +
                          " bytes: out of memory (VRI_MAX_BYTES below the free memory refuses such sizes before allocating)");
    }
}

// For work estimated in floating point (a rate times a length): throws
// vri::Error("<what>: needs N <unit>, limit M") unless 0 <= amount <= limit.
void requireWithin(const std::string& what, double amount, double limit, std::string_view unit);

}  // namespace vri
