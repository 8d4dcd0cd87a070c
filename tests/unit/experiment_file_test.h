#pragma once
// What the experiment-file tests share: the message an experiment file is refused with, and whether a
// planned command line holds an option with its value.
#include <string>
#include <vector>

#include "libvri/util/error.h"

namespace vri::test {

// The vri::Error message `parse` throws, or "no error".
template <class Parse>
std::string errorOf(Parse&& parse) {
    try {
        parse();
    } catch (const vri::Error& e) {
        return e.what();
    }
    return "no error";
}

// True when `option` is followed by `value` somewhere in a command's words.
inline bool hasOption(const std::vector<std::string>& words, const std::string& option, const std::string& value) {
    for (std::size_t i = 0; i + 1 < words.size(); ++i)
        if (words[i] == option && words[i + 1] == value) return true;
    return false;
}

}  // namespace vri::test
