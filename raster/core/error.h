// Errors tessera reports to its user. A tessera::Error carries a complete one-line message
// ("cannot read 'mesh.obj': no such file") and means "this run failed" (the command exits 1);
// bad parameter values from library calls are std::invalid_argument (the command exits 2).
#pragma once
#include <stdexcept>
#include <string>

namespace tessera {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace tessera
