// Transfer function evaluation and validation.
#include <doctest/doctest.h>

#include <cstdint>

#include "libvri/core/transfer_function.h"
#include "libvri/io/transfer_function_yaml.h"
#include "libvri/io/yaml_util.h"
#include "libvri/util/error.h"

using namespace vri;

TEST_CASE("transfer function: linear between points, constant outside, right-continuous at jumps") {
    TransferFunction tf({{0.2, 0, 0, 0, 0}, {0.6, 1, 0.5, 0, 2}, {0.6, 0, 0, 1, 4}, {1.0, 0, 0, 1, 0}},
                        EmissionModel::ColourTimesExtinction);
    CHECK(tf(0.0).tau == 0.0);
    CHECK(tf(0.4).tau == doctest::Approx(1.0));
    CHECK(tf(0.4).r == doctest::Approx(0.5));
    CHECK(tf(0.6).tau == 4.0);  // the jump takes the right value
    CHECK(tf(0.599999).tau == doctest::Approx(2.0).epsilon(1e-4));
    CHECK(tf(0.8).tau == doctest::Approx(2.0));
    CHECK(tf(1.5).b == 1.0);
    CHECK(tf(0.4f).tau == doctest::Approx(1.0f));
    // Every s between breakpoints brackets correctly, whatever bin it falls in.
    for (int i = 0; i < 1000; ++i) {
        const double s = 0.2 + 0.4 * i / 1000.0;
        CHECK(tf(s).tau == doctest::Approx(5.0 * (s - 0.2)).epsilon(1e-12));
    }
}

TEST_CASE("transfer function: the remembered segment never changes a value") {
    const TransferFunction tf({{0.1, 0, 0, 0, 0}, {0.3, 1, 0.5, 0, 2}, {0.3, 0, 0, 1, 4}, {0.3, 1, 1, 1, 3},
                               {0.55, 0.2, 0.7, 0.1, 1}, {0.9, 0, 0, 1, 0}},
                              EmissionModel::ColourTimesExtinction);
    std::size_t segment = 0;
    std::uint64_t state = 12345;
    double s = 0.0;
    for (int k = 0; k < 20000; ++k) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double u = double(state >> 11) * 0x1.0p-53;  // in [0, 1)
        // Small steps as along a ray, a jump now and then, and breakpoints exactly.
        if (k % 97 == 0) s = tf.points()[(state >> 33) % tf.points().size()].s;
        else if (k % 13 == 0) s = u * 1.2 - 0.1;
        else s += (u - 0.5) * 0.02;
        if (k % 5 == 0) segment = (state >> 20) % 8;  // any stale value, even past the last segment
        const TransferFunctionSample<double> plain = tf(s), remembered = tf(s, segment);
        CAPTURE(s);
        CHECK(remembered.r == plain.r);
        CHECK(remembered.g == plain.g);
        CHECK(remembered.b == plain.b);
        CHECK(remembered.tau == plain.tau);
        const TransferFunctionSample<float> plainF = tf(float(s)), rememberedF = tf(float(s), segment);
        CHECK(rememberedF.tau == plainF.tau);
        CHECK(rememberedF.r == plainF.r);
    }
}

TEST_CASE("transfer function: a jump at the first point also takes the right value") {
    TransferFunction tf({{0.0, 0, 0, 0, 0}, {0.0, 1, 1, 1, 4}, {1.0, 1, 1, 1, 4}}, EmissionModel::Colour);
    CHECK(tf(0.0).tau == 4.0);
    CHECK(tf(-0.1).tau == 0.0);
    CHECK(tf(0.0f).tau == 4.0f);
}

TEST_CASE("transfer function: invisible ranges") {
    TransferFunction tf({{0.0, 1, 1, 1, 0}, {0.3, 1, 1, 1, 0}, {0.5, 1, 1, 1, 1}}, EmissionModel::ColourTimesExtinction);
    CHECK(tf.isInvisible(0.0, 0.3));
    CHECK_FALSE(tf.isInvisible(0.0, 0.31));
    TransferFunction direct({{0.0, 1, 0, 0, 0}, {1.0, 1, 0, 0, 0}}, EmissionModel::Colour);
    CHECK_FALSE(direct.isInvisible(0.0, 0.1));  // emits without extinction
}

TEST_CASE("transfer function: bad points are rejected with a clear message") {
    CHECK_THROWS_WITH_AS(TransferFunction({{0.5, 0, 0, 0, 0}, {0.2, 0, 0, 0, 0}}, EmissionModel::Colour, "tf"),
                         doctest::Contains("sorted"), Error);
    CHECK_THROWS_WITH_AS(TransferFunction({{0.5, 0, 0, 0, -1}}, EmissionModel::Colour, "tf"),
                         doctest::Contains("negative extinction"), Error);
    CHECK_THROWS_AS(TransferFunction({}, EmissionModel::Colour, "tf"), Error);
    std::vector<TransferFunctionPoint> many(TransferFunction::kMaxPoints, {0.5, 0, 0, 0, 0});
    CHECK_NOTHROW(TransferFunction(many, EmissionModel::Colour, "tf"));
    many.push_back({0.5, 0, 0, 0, 0});
    CHECK_THROWS_WITH_AS(TransferFunction(many, EmissionModel::Colour, "tf"),
                         "tf: 10001 points, more than the limit of 10000", Error);
}

TEST_CASE("transfer function YAML: both point forms, and errors with line and column") {
    auto tf = parseTransferFunction("emission: color\npoints:\n  - {s: 0, color: [0, 0, 0], tau: 0}\n"
                                    "  - [1, 1, 1, 1, 0.5]\n",
                                    "a.yaml");
    CHECK(tf.emission() == EmissionModel::Colour);
    CHECK(tf(0.5).tau == doctest::Approx(0.25));
    CHECK_THROWS_WITH_AS(parseTransferFunction("points:\n  - [0.5, 0, 0, 0, 0]\n  - [0.2, 0, 0, 0, 0]\n", "u.yaml"),
                         doctest::Contains("u.yaml:3:5: points[1] has s = 0.2 below"), Error);
    CHECK_THROWS_WITH_AS(parseTransferFunction("points:\n  - [0, 0, 0, 0, 0]\n  - [0.5, 0, 0, 0, -2]\n", "n.yaml"),
                         doctest::Contains("n.yaml:3:5: points[1] has a negative extinction"), Error);
    CHECK_THROWS_WITH_AS(parseTransferFunction("points: [[0, 0, 0]\n", "m.yaml"),
                         doctest::Contains("m.yaml:"), Error);
    CHECK_THROWS_WITH_AS(parseTransferFunction("points: [[0, 0, 0]\n", "m.yaml"),
                         doctest::Contains("malformed YAML"), Error);
    CHECK_THROWS_WITH_AS(parseTransferFunction("pionts: []\n", "k.yaml"),
                         doctest::Contains("k.yaml:1:1: unknown key 'pionts'"), Error);
    CHECK_THROWS_WITH_AS(loadTransferFunction("/nonexistent/tf.yaml"), doctest::Contains("no such file"), Error);
}

TEST_CASE("transfer function YAML: a key given twice is an error naming both lines") {
    // yaml-cpp keeps both entries and a lookup takes one silently; the points below would be lost.
    CHECK_THROWS_WITH_AS(parseTransferFunction("points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 1]\n"
                                               "emission: color\npoints:\n  - [0, 1, 1, 1, 9]\n",
                                               "d.yaml"),
                         doctest::Contains("d.yaml:5:1: duplicate key 'points' (first at line 1)"), Error);
    // In a nested mapping (the braces form of a point) and in a flow mapping on one line.
    CHECK_THROWS_WITH_AS(parseTransferFunction("points:\n  - {s: 0, color: [0, 0, 0], tau: 0, tau: 2}\n", "n.yaml"),
                         doctest::Contains("n.yaml:2:38: duplicate key 'tau' (first at line 2)"), Error);
    // Equal keys in different mappings, or an equal value next to a key, are not duplicates.
    CHECK_NOTHROW(parseTransferFunction("points:\n  - {s: 0, color: [0, 0, 0], tau: 0}\n"
                                        "  - {s: 1, color: [1, 1, 1], tau: 1}\nemission: color\n",
                                        "ok.yaml"));
}

TEST_CASE("transfer function: points whose s span more than a double holds are refused") {
    // Between two points the weight is (s - s0) / (s1 - s0): an infinite span gives every s the first point's value.
    CHECK_THROWS_WITH_AS(
        parseTransferFunction("points:\n  - [-1e308, 0, 0, 0, 0]\n  - [1e308, 1, 1, 1, 1]\n", "w.yaml"),
        "w.yaml: the points' s from -1e+308 to 1e+308 span more than the largest double (expected a finite s1 - s0)",
        Error);
    CHECK_NOTHROW(parseTransferFunction("points:\n  - [-1e307, 0, 0, 0, 0]\n  - [1e307, 1, 1, 1, 1]\n", "w.yaml"));
}

TEST_CASE("YAML: a comma outside a flow collection is refused where it is, not looped on") {
    // yaml-cpp 0.7 reads a ',' there as an empty document it never consumes (its issue 1040).
    CHECK_THROWS_WITH_AS(yaml::parse("{a: 1},", "c.yaml"), "c.yaml:1:7: malformed YAML: ',' outside a flow collection",
                         Error);
    CHECK_THROWS_WITH_AS(yaml::parse("[1],", "c.yaml"), doctest::Contains("c.yaml:1:4: malformed YAML: ','"), Error);
    CHECK_THROWS_WITH_AS(yaml::parse("- 1\n,", "c.yaml"), doctest::Contains("c.yaml:2:1: malformed YAML: ','"), Error);
    CHECK_THROWS_WITH_AS(yaml::parse(",", "c.yaml"), doctest::Contains("c.yaml:1:1: malformed YAML: ','"), Error);
    CHECK_THROWS_WITH_AS(yaml::parse("---\na: 1\n---\n,\n", "c.yaml"),
                         doctest::Contains("c.yaml:4:1: malformed YAML: ','"), Error);
    // After a block mapping, and a ']' or '}' anywhere outside a flow collection, yaml-cpp refuses itself.
    CHECK_THROWS_WITH_AS(yaml::parse("a: 1\n,\n", "c.yaml"), "c.yaml:2:1: malformed YAML: end of map not found", Error);
    CHECK_THROWS_WITH_AS(yaml::parse("a: [1, 2]\n]\n", "c.yaml"), doctest::Contains("c.yaml:2:1: malformed YAML"),
                         Error);
    CHECK_THROWS_WITH_AS(yaml::parse("---\na: 1\n---\n}\n", "c.yaml"), doctest::Contains("c.yaml:4:1: malformed YAML"),
                         Error);
    // Commas inside quotes, flow collections and plain scalars stay valid.
    CHECK(yaml::parse("a: 'x, y'\nb: \"1,2\"\n", "ok.yaml")["a"].as<std::string>() == "x, y");
    CHECK(yaml::parse("a: [1, 2, 3]\nb: {c: 1, d: [4, 5]}\n", "ok.yaml")["a"].size() == 3);
    CHECK(yaml::parse("a: 1, 2\n", "ok.yaml")["a"].as<std::string>() == "1, 2");
    CHECK(yaml::parse("- [1, 2]\n- {a: 1,}\n", "ok.yaml").size() == 2);
    CHECK(yaml::parse("", "ok.yaml").IsNull());
    CHECK(yaml::parse("---\na: 1\n---\nb: 2\n", "ok.yaml")["a"].as<int>() == 1);
}
