#include "core/scene_json.hpp"
#include "core/suggest.hpp"
#include "core/utf8.hpp"
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace terrace {

using nlohmann::json;

std::string showNumber(double x) {
    std::ostringstream o;
    o << x;
    return o.str();
}

std::string showJson(const json& v) {
    return v.dump(-1, ' ', false, json::error_handler_t::replace);
}

JsonSection::JsonSection(const json& object, std::string path, std::string origin)
    : object_(&object), path_(std::move(path)), origin_(std::move(origin)) {}

void JsonSection::refuse(const std::string& dottedName, const std::string& what) const {
    throw SceneError((origin_.empty() ? "" : origin_ + ": ") + dottedName + ": " + what);
}

void JsonSection::fail(const std::string& key, const std::string& what) const {
    refuse(name(key), what);
}

std::string JsonSection::name(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
}

void JsonSection::onlyKeys(std::initializer_list<const char*> known) const {
    if (!object_->is_object()) refuse(path_.empty() ? "<top>" : path_, "must be an object");
    const std::vector<std::string> allowed(known.begin(), known.end());
    for (const auto& [key, value] : object_->items()) {
        (void)value;
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        const std::string near = nearestName(key, allowed);
        if (!near.empty()) fail(key, "unknown key; did you mean " + name(near) + "?");
        std::string list;
        for (const auto& k : allowed)
            list += (list.empty() ? "" : ", ") + k;
        fail(key, "unknown key (" + (path_.empty() ? std::string("a scene") : path_) + " has " +
                      list + ")");
    }
}

JsonSection JsonSection::section(const std::string& key) const {
    static const json empty = json::object();
    if (!has(key)) return JsonSection(empty, name(key), origin_);
    if (!at(key).is_object()) fail(key, "must be an object");
    return JsonSection(at(key), name(key), origin_);
}

double JsonSection::number(const std::string& key, double def, double lo, double hi,
                           bool loOpen) const {
    if (!has(key)) return def;
    const json& v = at(key);
    if (!v.is_number()) fail(key, "must be a number, got " + showJson(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(key, "must be finite");
    if (loOpen ? !(x > lo) : !(x >= lo))
        fail(key, std::string("must be ") + (loOpen ? "> " : ">= ") + showNumber(lo) + ", got " +
                      showNumber(x));
    if (!(x <= hi)) fail(key, "must be <= " + showNumber(hi) + ", got " + showNumber(x));
    return x;
}

long long JsonSection::integer(const std::string& key, long long def, long long lo,
                               long long hi) const {
    if (!has(key)) return def;
    const json& v = at(key);
    if (!v.is_number_integer()) fail(key, "must be an integer, got " + showJson(v));
    // A value beyond 2^63 parses as unsigned: shown as given, never wrapped to a negative one.
    if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi))
        fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                      std::to_string(v.get<unsigned long long>()));
    const long long x = v.get<long long>();
    if (x < lo || x > hi)
        fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                      std::to_string(x));
    return x;
}

std::string JsonSection::choice(const std::string& key, const std::string& def,
                                std::initializer_list<const char*> allowed) const {
    if (!has(key)) return def;
    const json& v = at(key);
    if (!v.is_string()) fail(key, "must be a string, got " + showJson(v));
    const auto s = v.get<std::string>();
    std::string list;
    for (const char* a : allowed) {
        if (s == a) return s;
        list += (list.empty() ? "" : " | ") + std::string(a);
    }
    const std::string near =
        nearestName(s, std::vector<std::string>(allowed.begin(), allowed.end()));
    fail(key, "must be one of " + list + ", got \"" + s + "\"" +
                  (near.empty() ? "" : "; did you mean " + near + "?"));
}

bool JsonSection::boolean(const std::string& key, bool def) const {
    if (!has(key)) return def;
    if (!at(key).is_boolean()) fail(key, "must be true or false, got " + showJson(at(key)));
    return at(key).get<bool>();
}

Vec3 JsonSection::vec3(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != 3) fail(key, "must be an array of 3 numbers");
    Vec3 x;
    for (int a = 0; a < 3; ++a) {
        if (!v[a].is_number()) fail(key, "must be an array of 3 numbers");
        x[a] = v[a].get<double>();
        if (!std::isfinite(x[a])) fail(key, "must be finite");
    }
    // Finite elements are not enough: the length (and what is built from it) must be too.
    if (!std::isfinite(x.norm()))
        fail(key, "is too large: its length " + showNumber(x.norm()) + " overflows a double");
    return x;
}

std::vector<double> JsonSection::numbers(const std::string& key, const std::string& unit) const {
    const json& list = at(key);
    if (!list.is_array()) fail(key, "must be an array");
    std::vector<double> out;
    for (const auto& x : list) {
        if (!x.is_number() || !std::isfinite(x.get<double>()))
            fail(key, "must hold finite numbers (" + unit + ")");
        out.push_back(x.get<double>());
    }
    return out;
}

void requireOnGrid(const JsonSection& at, const std::string& key, double value, const char* unit,
                   double fsPerUnit, const std::string& gridKey, double gridFs) {
    const double ratio = value * fsPerUnit / gridFs;
    const double k = std::round(ratio);
    if (k >= 1.0 && std::abs(ratio - k) <= limits::gridTolerance * k) return;
    const double below = std::floor(ratio), above = std::ceil(ratio);
    // Enough digits that the values named are valid (six would make 1000.008 ps "1000.01 ps").
    auto valid = [&](double k) {
        std::ostringstream o;
        o.precision(15);
        o << k * gridFs / fsPerUnit;
        return o.str();
    };
    std::string nearest;
    if (below >= 1.0) nearest = valid(below) + " or ";
    nearest += valid(above);
    at.refuse(key, "must be a whole multiple of " + gridKey + " = " + showNumber(gridFs) +
                       " fs, got " + showNumber(value) + " " + unit +
                       "; nearest valid: " + nearest + " " + unit);
}

void applyOverride(json& scene, const std::string& assignment, const std::string& origin) {
    const JsonSection top(scene, "", origin);
    if (const auto bad = firstInvalidUtf8(assignment); bad != std::string::npos)
        top.refuse("--set " + printableBytes(assignment), utf8Problem(assignment, bad));
    const auto parsed = parseOverride(assignment);
    if (!parsed) top.refuse("--set " + assignment, "expected key.path=value");
    const auto& [path, value] = *parsed;
    json* node = &scene;
    std::size_t start = 0;
    while (true) {
        const auto dot = path.find('.', start);
        const std::string key = path.substr(start, dot - start);
        if (key.empty()) top.refuse(path, "empty key in --set");
        if (dot == std::string::npos) {
            (*node)[key] = value;
            return;
        }
        if (!node->contains(key)) (*node)[key] = json::object();
        node = &(*node)[key];
        if (!node->is_object()) top.refuse(path.substr(0, dot), "is not an object");
        start = dot + 1;
    }
}

namespace {

/// SAX pass that stops at the first repeated key of any object and names it by its dotted path.
class DuplicateKeyFinder : public nlohmann::json_sax<json> {
public:
    std::string duplicate; // dotted path of the first repeated key, empty if none

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        value();
        frames_.push_back({true, {}, {}, -1});
        return true;
    }
    bool key(string_t& k) override {
        auto& f = frames_.back();
        f.key = k;
        if (f.keys.insert(k).second) return true;
        duplicate = path();
        return false; // stop: the first duplicate is the one reported
    }
    bool end_object() override {
        frames_.pop_back();
        return true;
    }
    bool start_array(std::size_t) override {
        value();
        frames_.push_back({false, {}, {}, -1});
        return true;
    }
    bool end_array() override {
        frames_.pop_back();
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

private:
    struct Frame {
        bool object;
        std::set<std::string> keys;
        std::string key; // object: the key being read
        long index;      // array: the element being read
    };

    bool value() {
        if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
        return true;
    }

    std::string path() const {
        std::string p;
        for (const auto& f : frames_)
            p += f.object ? (p.empty() ? "" : ".") + f.key : "[" + std::to_string(f.index) + "]";
        return p;
    }

    std::vector<Frame> frames_;
};

} // namespace

std::string firstDuplicateKey(const std::string& text) {
    DuplicateKeyFinder finder;
    json::sax_parse(text, &finder);
    return finder.duplicate;
}

} // namespace terrace
