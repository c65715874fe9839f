// Communicator over MPI_COMM_WORLD (Open MPI). Built when CMake finds MPI (TALUS_HAVE_MPI).
#pragma once

#include "engine/communicator.h"

#include <memory>

namespace talus {

/// True when this process was started by mpirun/mpiexec/srun (their environment variables):
/// `talus run` without a launcher then never touches MPI, so it starts as fast as before.
bool launchedAsRanks();

/// Initialises MPI (once) and returns the world communicator; throws when Talus was built
/// without MPI. MPI is finalised at exit.
std::shared_ptr<Communicator> worldCommunicator(int* argc, char*** argv);

/// Ends every rank of the job (after a fatal error on one of them): MPI_Abort with `code`.
[[noreturn]] void abortAllRanks(int code);

} // namespace talus
