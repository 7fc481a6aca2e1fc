// Checked reading of a scene file's JSON: every value is fetched through a JsonNode that knows
// its JSON Pointer path (RFC 6901, "/objects/2/material/kd"), so a value of the wrong type is
// an error naming the file and that path, and every key of an object that nobody asked for
// is a warning naming the file and the key's path (a misspelt "ambeint" is reported, not
// silently ignored). Internal to the scene-file loader: nlohmann-json stays out of the
// library's public headers.
#pragma once
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace tessera::scene_file {

// Where diagnostics go: the file's name (as the user gave it) and the warning list.
struct Diagnostics {
    std::string file;
    std::vector<std::string>* warnings = nullptr;
};

// The JSON Pointers of keys that an object of `text` (valid JSON) gives more than once, in file
// order. RFC 8259 leaves their meaning open and nlohmann-json keeps the last one, so a second
// "objects" would silently replace the first: the scene reader warns about each.
std::vector<std::string> repeated_keys(const std::string& text);

class JsonNode {
public:
    JsonNode(const nlohmann::ordered_json& value, std::string path, const Diagnostics& diagnostics)
        : value_(&value), path_(std::move(path)), diagnostics_(&diagnostics) {}

    const std::string& path() const { return path_; }
    const nlohmann::ordered_json& raw() const { return *value_; }
    bool is_object() const { return value_->is_object(); }
    bool is_string() const { return value_->is_string(); }
    bool is_array() const { return value_->is_array(); }

    // Throws SceneFileError "FILE: PATH: message".
    [[noreturn]] void fail(const std::string& message) const;
    void warn(const std::string& message) const;

    // This value as a given type (errors name the expected type).
    float as_number() const;
    int as_integer() const;
    std::string as_string() const;
    glm::vec2 as_vec2() const;
    glm::vec3 as_vec3() const;
    std::vector<float> as_numbers() const;

    // Members of an object (this node must be one: checked by expect_object()). Each
    // accessor marks the key as known; finish() warns about the others.
    void expect_object() const;
    bool has(const std::string& key) const;
    std::optional<JsonNode> find(const std::string& key) const;
    JsonNode at(const std::string& key) const;  // required member
    float number(const std::string& key, float fallback) const;
    int integer(const std::string& key, int fallback) const;
    bool boolean(const std::string& key, bool fallback) const;
    std::string string(const std::string& key, const std::string& fallback) const;
    glm::vec2 vec2(const std::string& key, glm::vec2 fallback) const;
    glm::vec3 vec3(const std::string& key, glm::vec3 fallback) const;
    // Marks a key as known without reading it (read elsewhere, or deliberately ignored).
    void accept(const std::string& key) const;
    void finish() const;

    // Elements of an array (this node must be one).
    std::vector<JsonNode> elements() const;
    // Members of an object in file order (ordered_json keeps it), all marked known.
    std::vector<std::pair<std::string, JsonNode>> members() const;

    // `key` as a step of a JSON Pointer (RFC 6901: '~' as "~0", '/' as "~1").
    static std::string escape(const std::string& key);

private:
    JsonNode child(const std::string& key) const;

    const nlohmann::ordered_json* value_;
    std::string path_;
    const Diagnostics* diagnostics_;
    mutable std::set<std::string> used_;
};

}  // namespace tessera::scene_file
