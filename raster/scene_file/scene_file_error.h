// A scene file that cannot be used: missing, malformed JSON, a value of the wrong type or out
// of range. The message is one line, "FILE: /json/pointer: what is wrong", so an editor or a
// person finds the value at once. A runtime failure of the run (exit code 1), like any other
// unreadable input file.
#pragma once
#include "raster/error.h"

namespace tessera {

struct SceneFileError : Error {
    using Error::Error;
};

}  // namespace tessera
