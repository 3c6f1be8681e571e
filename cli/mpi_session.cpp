#include "mpi_session.hpp"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <stdexcept>

#ifdef IMPACTLAB_HAVE_MPI
#include <mpi.h>
#endif

namespace impactlab::cli {

MpiSession::MpiSession() {
#ifndef IMPACTLAB_HAVE_MPI
  // several copies of a program without MPI would each run the whole sweep
  const char* world = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (world != nullptr && std::atoi(world) > 1)
    throw std::runtime_error("launched by mpirun, but this impactlab was built without MPI");
#else
  if (std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  active_ = true;
#endif
}

int MpiSession::launched_rank() {
  const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
  return rank != nullptr ? std::atoi(rank) : 0;
}

MpiSession::~MpiSession() {
#ifdef IMPACTLAB_HAVE_MPI
  if (!active_) return;
  // a rank that fails must not leave the others waiting for it in a gather
  if (std::uncaught_exceptions() > 0) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Finalize();
#endif
}

std::vector<std::string> MpiSession::gather(const std::string& text) const {
  if (!active_) return {text};
#ifdef IMPACTLAB_HAVE_MPI
  // sizes first, then the texts
  const long long length = static_cast<long long>(text.size());
  std::vector<long long> lengths(rank_ == 0 ? size_ : 0);
  MPI_Gather(&length, 1, MPI_LONG_LONG, lengths.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  std::vector<std::string> texts;
  if (rank_ == 0) {
    texts.resize(size_);
    texts[0] = text;
    for (int source = 1; source < size_; ++source) {
      texts[source].resize(static_cast<std::size_t>(lengths[source]));
      // in pieces below 2^31 bytes (MPI counts are int)
      for (long long offset = 0; offset < lengths[source]; offset += 1 << 30) {
        const int piece = static_cast<int>(std::min<long long>(1 << 30, lengths[source] - offset));
        MPI_Recv(texts[source].data() + offset, piece, MPI_CHAR, source, 0, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
      }
    }
  } else {
    for (long long offset = 0; offset < length; offset += 1 << 30) {
      const int piece = static_cast<int>(std::min<long long>(1 << 30, length - offset));
      MPI_Send(text.data() + offset, piece, MPI_CHAR, 0, 0, MPI_COMM_WORLD);
    }
  }
  return texts;
#else
  return {text};
#endif
}

bool MpiSession::broadcast(bool flag) const {
  if (!active_) return flag;
#ifdef IMPACTLAB_HAVE_MPI
  int value = flag ? 1 : 0;
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value != 0;
#else
  return flag;
#endif
}

}  // namespace impactlab::cli
