#pragma once
// An environment variable set, or unset, for a scope: its earlier value, or its absence, comes back at
// the end, so that a test leaves the process's environment as it found it.
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

namespace vri::test {

class ScopedEnvironment {
public:
    // `value` empty (std::nullopt): the variable is unset for the scope.
    ScopedEnvironment(std::string name, const std::optional<std::string>& value) : name_(std::move(name)) {
        if (const char* old = std::getenv(name_.c_str())) old_ = old;
        set(value);
    }
    ~ScopedEnvironment() { set(old_); }
    ScopedEnvironment(const ScopedEnvironment&) = delete;
    ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

    // Another value (or none) within the same scope.
    void set(const std::optional<std::string>& value) const {
        if (value)
            ::setenv(name_.c_str(), value->c_str(), 1);
        else
            ::unsetenv(name_.c_str());
    }

private:
    std::string name_;
    std::optional<std::string> old_;
};

}  // namespace vri::test
