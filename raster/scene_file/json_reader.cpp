#include "raster/scene_file/json_reader.h"

#include <cmath>

#include "raster/scene_file/scene_file_error.h"

namespace tessera::scene_file {
namespace {

const char* type_name(const nlohmann::ordered_json& v) {
    if (v.is_null()) return "null";
    if (v.is_boolean()) return "a boolean";
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_array()) return "an array";
    return "an object";
}

}  // namespace

std::vector<std::string> repeated_keys(const std::string& text) {
    // A SAX pass over the text: a stack of the containers open, each with the keys seen so far
    // (objects) or the index reached (arrays), which also spells the pointer of a repeat.
    struct Finder : nlohmann::json_sax<nlohmann::ordered_json> {
        struct Level {
            bool object = true;
            std::set<std::string> keys;
            long index = -1;
            std::string step;  // the current key or index, escaped
        };
        std::vector<Level> levels;
        std::vector<std::string> found;

        void value() {  // a value starts: in an array, at the next index
            if (!levels.empty() && !levels.back().object) levels.back().step = std::to_string(++levels.back().index);
        }
        bool open(bool object) {
            value();
            levels.push_back({object, {}, -1, {}});
            return true;
        }
        bool close() {
            levels.pop_back();
            return true;
        }
        bool null() override { return value(), true; }
        bool boolean(bool) override { return value(), true; }
        bool number_integer(number_integer_t) override { return value(), true; }
        bool number_unsigned(number_unsigned_t) override { return value(), true; }
        bool number_float(number_float_t, const string_t&) override { return value(), true; }
        bool string(string_t&) override { return value(), true; }
        bool binary(binary_t&) override { return value(), true; }
        bool start_object(std::size_t) override { return open(true); }
        bool start_array(std::size_t) override { return open(false); }
        bool end_object() override { return close(); }
        bool end_array() override { return close(); }
        bool key(string_t& k) override {
            Level& level = levels.back();
            level.step = JsonNode::escape(k);
            if (!level.keys.insert(k).second) {
                std::string pointer;
                for (const Level& l : levels) pointer += "/" + l.step;
                found.push_back(pointer);
            }
            return true;
        }
        bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
            return false;
        }
    } finder;
    nlohmann::ordered_json::sax_parse(text, &finder);
    return finder.found;
}

void JsonNode::fail(const std::string& message) const {
    throw SceneFileError(diagnostics_->file + ": " + (path_.empty() ? "/" : path_) + ": " + message);
}

void JsonNode::warn(const std::string& message) const {
    if (diagnostics_->warnings)
        diagnostics_->warnings->push_back(
            one_line_diagnostic(diagnostics_->file + ": " + (path_.empty() ? "/" : path_) + ": " + message));
}

float JsonNode::as_number() const {
    if (!value_->is_number()) fail(std::string("expected a number, got ") + type_name(*value_));
    const double d = value_->get<double>();
    if (!std::isfinite(d) || std::abs(d) > 3.0e38) fail("the number is out of range");
    return float(d);
}

int JsonNode::as_integer() const {
    if (!value_->is_number()) fail(std::string("expected an integer, got ") + type_name(*value_));
    const double d = value_->get<double>();
    if (d != std::floor(d) || std::abs(d) > 2.0e9) fail("expected an integer");
    return int(d);
}

std::string JsonNode::as_string() const {
    if (!value_->is_string()) fail(std::string("expected a string, got ") + type_name(*value_));
    return value_->get<std::string>();
}

std::vector<float> JsonNode::as_numbers() const {
    if (!value_->is_array()) fail(std::string("expected an array of numbers, got ") + type_name(*value_));
    std::vector<float> out;
    for (const JsonNode& e : elements()) out.push_back(e.as_number());
    return out;
}

glm::vec2 JsonNode::as_vec2() const {
    if (!value_->is_array() || value_->size() != 2) fail("expected an array of 2 numbers");
    const std::vector<float> v = as_numbers();
    return {v[0], v[1]};
}

glm::vec3 JsonNode::as_vec3() const {
    if (!value_->is_array() || value_->size() != 3) fail("expected an array of 3 numbers");
    const std::vector<float> v = as_numbers();
    return {v[0], v[1], v[2]};
}

void JsonNode::expect_object() const {
    if (!value_->is_object()) fail(std::string("expected an object, got ") + type_name(*value_));
}

std::string JsonNode::escape(const std::string& key) {
    // RFC 6901: '~' -> "~0", '/' -> "~1".
    std::string out;
    for (char c : key) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}

JsonNode JsonNode::child(const std::string& key) const {
    used_.insert(key);
    return JsonNode((*value_)[key], path_ + "/" + escape(key), *diagnostics_);
}

bool JsonNode::has(const std::string& key) const {
    expect_object();
    return value_->contains(key);
}

std::optional<JsonNode> JsonNode::find(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    return child(key);
}

JsonNode JsonNode::at(const std::string& key) const {
    if (!has(key)) fail("missing required key '" + key + "'");
    return child(key);
}

float JsonNode::number(const std::string& key, float fallback) const {
    const auto n = find(key);
    return n ? n->as_number() : fallback;
}

int JsonNode::integer(const std::string& key, int fallback) const {
    const auto n = find(key);
    return n ? n->as_integer() : fallback;
}

bool JsonNode::boolean(const std::string& key, bool fallback) const {
    const auto n = find(key);
    if (!n) return fallback;
    if (!n->value_->is_boolean()) n->fail(std::string("expected true or false, got ") + type_name(*n->value_));
    return n->value_->get<bool>();
}

std::string JsonNode::string(const std::string& key, const std::string& fallback) const {
    const auto n = find(key);
    return n ? n->as_string() : fallback;
}

glm::vec2 JsonNode::vec2(const std::string& key, glm::vec2 fallback) const {
    const auto n = find(key);
    return n ? n->as_vec2() : fallback;
}

glm::vec3 JsonNode::vec3(const std::string& key, glm::vec3 fallback) const {
    const auto n = find(key);
    return n ? n->as_vec3() : fallback;
}

void JsonNode::accept(const std::string& key) const { used_.insert(key); }

void JsonNode::finish() const {
    if (!value_->is_object()) return;
    for (auto it = value_->begin(); it != value_->end(); ++it)
        if (!used_.count(it.key()))
            JsonNode(it.value(), path_ + "/" + escape(it.key()), *diagnostics_)
                .warn("unknown key '" + it.key() + "'; ignored");
}

std::vector<JsonNode> JsonNode::elements() const {
    if (!value_->is_array()) fail(std::string("expected an array, got ") + type_name(*value_));
    std::vector<JsonNode> out;
    for (size_t i = 0; i < value_->size(); ++i)
        out.emplace_back((*value_)[i], path_ + "/" + std::to_string(i), *diagnostics_);
    return out;
}

std::vector<std::pair<std::string, JsonNode>> JsonNode::members() const {
    expect_object();
    std::vector<std::pair<std::string, JsonNode>> out;
    for (auto it = value_->begin(); it != value_->end(); ++it) out.emplace_back(it.key(), child(it.key()));
    return out;
}

}  // namespace tessera::scene_file
