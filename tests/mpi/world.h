// The ranks every MPI test runs on: set by main (tests/mpi/test_ranks.cpp) before the tests.
#pragma once

#include "engine/communicator.h"

#include <memory>

namespace talus::test {
extern std::shared_ptr<Communicator> world;
} // namespace talus::test
