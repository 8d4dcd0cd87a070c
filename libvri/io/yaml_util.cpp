#include "libvri/io/yaml_util.h"

#include <cmath>

#include <map>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include <yaml-cpp/eventhandler.h>

#include "libvri/util/file_text.h"

namespace vri::yaml {

namespace {

// yaml-cpp 0.7 keeps both entries of a mapping that names a key twice, and a lookup silently takes
// one of them. The parser's event stream shows every key once, in order, with its position: a
// single pass over it finds the repeats. Aliases are events too, never expanded, so a document
// whose anchors nest costs no more than its text.
//
// The same pass stops a known hang (yaml-cpp issue 1040, fixed after 0.8.0; Debian ships 0.7.0): a
// ',' where a node should start outside a flow collection (after a flow collection at the top level,
// as in a JSON-style trailing comma, or after a block sequence) is read as an empty document that
// consumes nothing, so the next document starts at the same place, forever. A document that starts
// where the previous one did has consumed nothing; it is refused there. This costs one comparison per
// document and is exact, where a parse under a time limit would need a thread that cannot be stopped
// and a guess at how long a large file may take.
class DuplicateKeyFinder : public YAML::EventHandler {
public:
    DuplicateKeyFinder(const std::string& text, const std::string& source) : text_(text), source_(source) {}

    void OnDocumentStart(const YAML::Mark& mark) override {
        if (mark.pos == lastDocumentPos_) {
            // pos counts bytes of UTF-8 text after a byte-order mark: it names the ',' when it is there.
            const std::size_t at = std::size_t(mark.pos);
            const bool comma = at < text_.size() && text_[at] == ',';
            throw Error(
                source_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1) +
                ": malformed YAML: " + (comma ? "',' outside a flow collection" : "a token that starts no node"));
        }
        lastDocumentPos_ = mark.pos;
    }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, "~"); }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, std::nullopt); }
    void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string& value) override {
        node(mark, value);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
        node(mark, std::nullopt);
        open(mark, {});
    }
    void OnSequenceEnd() override { open_.pop_back(); }
    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
        node(mark, std::nullopt);
        open(mark, {true, true, {}});
    }
    void OnMapEnd() override { open_.pop_back(); }

private:
    struct Collection {
        bool mapping = false;
        bool nextIsKey = true;            // mappings alternate key, value
        std::map<std::string, int> keys;  // scalar key -> its line (1-based)
    };

    // yaml-cpp stops at 500 nested nodes with its message for an unreadable file, "bad file", at the end
    // of the text; a collection nested deeper than any of vri's files needs is refused here first, where
    // it starts.
    void open(const YAML::Mark& mark, Collection collection) {
        if (open_.size() == kMaxNesting)
            throw Error(source_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1) +
                        ": malformed YAML: collections nested deeper than " + std::to_string(kMaxNesting) +
                        " levels, the limit");
        open_.push_back(std::move(collection));
    }

    // A node starts at `mark`; `scalar` is its text when it is a scalar (a key that can repeat).
    void node(const YAML::Mark& mark, const std::optional<std::string>& scalar) {
        // The tree yaml-cpp builds next takes about 0.6 kB a node: counted here, on the stream, before it.
        if (++nodes_ > kMaxYamlNodes)
            throw Error(source_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1) +
                        ": more than " + std::to_string(kMaxYamlNodes) + " YAML nodes (the limit of a vri YAML file)");
        if (open_.empty() || !open_.back().mapping) return;
        Collection& map = open_.back();
        const bool isKey = map.nextIsKey;
        map.nextIsKey = !map.nextIsKey;
        if (!isKey || !scalar) return;
        const auto [it, inserted] = map.keys.emplace(*scalar, mark.line + 1);
        if (!inserted)
            throw Error(source_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1) +
                        ": duplicate key '" + *scalar + "' (first at line " + std::to_string(it->second) + ")");
    }

    static constexpr std::size_t kMaxNesting = 200;
    const std::string& text_;
    const std::string& source_;
    int lastDocumentPos_ = -1;
    std::size_t nodes_ = 0;
    std::vector<Collection> open_;
};

}  // namespace

std::string where(const std::string& source, const YAML::Node& node) {
    const YAML::Mark m = node.Mark();
    if (m.is_null()) return source;
    return source + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

YAML::Node parse(const std::string& text, const std::string& source) {
    try {
        std::istringstream events(text);
        YAML::Parser parser(events);
        DuplicateKeyFinder duplicates(text, source);
        while (parser.HandleNextDocument(duplicates)) {
        }
        return YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw Error(source + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                    ": malformed YAML: " + e.msg);
    }
}

YAML::Node load(const std::filesystem::path& path) {
    return parse(readFileText(path, "a YAML file"), path.string());
}

void requireMap(const YAML::Node& node, const std::string& source, std::string_view what) {
    if (!node.IsMap()) throw Error(where(source, node) + ": " + std::string(what) + " must be a mapping");
}

void requireKeys(const YAML::Node& map, const std::string& source, std::span<const std::string_view> allowed) {
    for (const auto& kv : map) {
        if (!kv.first.IsScalar()) throw Error(where(source, kv.first) + ": keys must be plain names");
        const std::string key = kv.first.as<std::string>();
        bool known = false;
        for (auto a : allowed) known = known || key == a;
        if (known) continue;
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        throw Error(where(source, kv.first) + ": unknown key '" + key + "' (expected one of: " + list + ")");
    }
}

double toDouble(const YAML::Node& node, const std::string& source, std::string_view what) {
    try {
        if (node.IsScalar()) return node.as<double>();
    } catch (const YAML::Exception&) {
    }
    throw Error(where(source, node) + ": " + std::string(what) + " must be a number");
}

long long toWholeNumber(const YAML::Node& node, const std::string& source, std::string_view what, long long lo,
                        long long hi) {
    const double x = toDouble(node, source, what);
    if (x != std::floor(x) || x < static_cast<double>(lo) || x > static_cast<double>(hi))
        throw Error(where(source, node) + ": " + std::string(what) + " must be a whole number in " +
                    std::to_string(lo) + ".." + std::to_string(hi) + ", got " + node.Scalar());
    return static_cast<long long>(x);
}

bool toBool(const YAML::Node& node, const std::string& source, std::string_view what) {
    try {
        if (node.IsScalar()) return node.as<bool>();
    } catch (const YAML::Exception&) {
    }
    throw Error(where(source, node) + ": " + std::string(what) + " must be true or false");
}

std::string toString(const YAML::Node& node, const std::string& source, std::string_view what) {
    if (!node.IsScalar()) throw Error(where(source, node) + ": " + std::string(what) + " must be a string");
    return node.as<std::string>();
}

}  // namespace vri::yaml
