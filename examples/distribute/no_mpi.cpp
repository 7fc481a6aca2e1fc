// A build without MPI (TESSERA_MPI off or Open MPI not found): --distribute says so.
#include "examples/command.h"
#include "examples/distribute.h"

namespace tessera::cli {

std::unique_ptr<Distribution> make_mpi_distribution(DistributeMode, std::vector<int>) {
    throw UsageError("--distribute needs MPI, which this build lacks (install libopenmpi-dev and rebuild with "
                     "-DTESSERA_MPI=ON)");
}

}  // namespace tessera::cli
