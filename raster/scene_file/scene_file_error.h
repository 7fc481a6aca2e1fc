// A scene file that cannot be used: missing, malformed JSON, a value of the wrong type or out
// of range. The message is one line, "FILE: /json/pointer: what is wrong", so an editor or a
// person finds the value at once. A runtime failure of the run (exit code 1), like any other
// unreadable input file.
#pragma once
#include <string>

#include "raster/core/error.h"

namespace tessera::scene_file {

// Keys and strings come from the file, so they may hold newlines or other control bytes;
// every diagnostic is one line (the command's contract), so those are shown escaped.
inline std::string one_line_diagnostic(const std::string& text) {
    static const char hex[] = "0123456789abcdef";
    std::string out;
    for (const unsigned char c : text) {
        if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else if (c < 0x20 || c == 0x7f) {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else {
            out += char(c);
        }
    }
    return out;
}

struct SceneFileError : Error {
    explicit SceneFileError(const std::string& message) : Error(one_line_diagnostic(message)) {}
};

}  // namespace tessera::scene_file
