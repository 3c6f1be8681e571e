// MPI for `impactlab sweep`, only when the program was launched by mpirun:
// OpenMPI sets OMPI_COMM_WORLD_SIZE in every rank's environment, so a plain
// `impactlab sweep` neither needs nor initialises MPI. Without MPI (or built
// without it) this is a session of one rank.
#pragma once

#include <string>
#include <vector>

namespace impactlab::cli {

class MpiSession {
 public:
  MpiSession();   // MPI_Init when launched by mpirun
  ~MpiSession();  // MPI_Finalize; MPI_Abort when unwinding from an exception
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] bool active() const { return active_; }

  // The rank mpirun gave this process (OMPI_COMM_WORLD_RANK), known before
  // MPI starts; 0 when not launched by mpirun.
  [[nodiscard]] static int launched_rank();

  // Rank 0 receives every rank's text, in rank order; other ranks get {}.
  [[nodiscard]] std::vector<std::string> gather(const std::string& text) const;
  // Rank 0's flag, on every rank (a run-wide decision such as "stop").
  [[nodiscard]] bool broadcast(bool flag) const;

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
};

}  // namespace impactlab::cli
