// camdyn CLI — `camdyn sweep` under mpirun (OpenMPI). Kept out of the core library: only
// the command-line tool links MPI (CMake option CAMDYN_WITH_MPI).
#pragma once

#include "camdyn/designer.hpp"

namespace camdyn_cli {

/// True when this process was started by mpirun/mpiexec with more than one rank
/// (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_SIZE > 1 in the environment).
bool launched_under_mpi();

/// This process's rank from the launcher's environment (0 when not under mpirun), for
/// printing input errors on rank 0 only.
int mpi_rank_from_env();

/// True when the tool was built with MPI.
bool mpi_available();

/// Run the sweep across the MPI ranks. Rank 0 is the master: it reads the journal
/// (--resume), hands point indices out one at a time on request (dynamic), writes every
/// returned point to the journal (fsync) and the sorted outputs at the end; it also
/// computes points itself on a second thread, so N ranks give N computing processes.
/// Ranks > 0 compute the points they are sent and return the journal text.
/// `*is_master` tells the caller whether to print. Returns the result on rank 0.
/// @throws SceneError on bad input (on every rank); std::runtime_error on I/O errors.
camdyn::SweepResult run_sweep_mpi(const camdyn::Scene& base, const camdyn::SweepOptions& options,
                                  bool* is_master);

}  // namespace camdyn_cli
