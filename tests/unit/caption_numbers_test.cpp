// Caption numbers filled from an experiment's CSV tables: each reference becomes its cell as printed,
// and a reference that names no table, row, column or value fails instead of leaving a stale number.
#include <doctest/doctest.h>

#include <fstream>

#include "temp_dir.h"
#include "libvri/experiment/caption_numbers.h"
#include "libvri/util/error.h"

using namespace vri;

TEST_CASE("caption numbers are read from the experiment's tables") {
    const test::TempDir dir("caption");
    std::ofstream(dir / "time.csv") << "Method,bonsai,\"teapot, 8 bit\"\nRiemann (h = 0.1),2.86,1.95\ncoupled-eps0.01,1.96,\n";
    std::ofstream(dir / "run.json") << R"({"stats": {"adaptive": {"inner_tries": 32274890}, "seconds": [0.5, 0.0018520355224609375]}, "name": "x"})";
    CHECK(fillCaptionNumbers("no numbers", dir.path) == "no numbers");
    CHECK(fillCaptionNumbers("{{json:run:stats.adaptive.inner_tries}} tries, {{json:run:stats.seconds.1}} s", dir.path) ==
          "32274890 tries, 0.001852 s");
    CHECK(fillCaptionNumbers("{{table:time:coupled-eps0.01:bonsai}} s against {{table:time:Riemann (h = 0.1):bonsai}} s "
                             "({{table:time:Riemann (h = 0.1):teapot, 8 bit}})",
                             dir.path) == "1.96 s against 2.86 s (1.95)");
    for (const char* bad : {"{{table:time:coupled-eps0.01:bonsai", "{{json:time:a:b}}", "{{table:time:bonsai}}",
                            "{{table:none:coupled-eps0.01:bonsai}}", "{{table:time:riemann:bonsai}}",
                            "{{table:time:coupled-eps0.01:engine}}", "{{table:time:coupled-eps0.01:Method}}",
                            "{{table:time:coupled-eps0.01:teapot, 8 bit}}", "{{table:../time:a:b}}", "{{table::a:b}}",
                            "{{json:run:stats.none}}", "{{json:run:name}}", "{{json:run:stats.seconds.2}}", "{{json:none:a}}"})
        CHECK_THROWS_AS(fillCaptionNumbers(std::string("x ") + bad, dir.path), Error);
}
