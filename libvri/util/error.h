#pragma once
// One exception type for every user-facing failure. Its message is the one line a tool prints:
// it names the file, field or argument and says what was expected.
#include <stdexcept>
#include <string>

namespace vri {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// A failure of the command line itself (options that contradict each other, an output of the wrong
// kind): a tool reports it like any Error but exits with the usage code (cli.h's kExitUsage).
class UsageError : public Error {
public:
    using Error::Error;
};

// A failure whose first line is the message and whose further lines show what explains it: a failed
// step's command and the tool's own output. Printed as real lines (only other control characters are
// escaped), since a command and a tool's message folded into one line with \x0a between them read as noise.
class DetailedError : public Error {
public:
    using Error::Error;
};

}  // namespace vri
