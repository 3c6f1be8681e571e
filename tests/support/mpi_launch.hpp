// The shell prefix that runs a command as two OpenMPI ranks on this machine,
// shared by the tests that compare an MPI run's files with a serial run's.
#pragma once

#include <string>

namespace impactlab::test {

// OpenMPI refuses to run as root unless told, and two ranks on a small machine
// need oversubscription; the variables do nothing otherwise. Under
// AddressSanitizer (scripts/test.sh --sanitize) the ranks' leak check is off:
// OpenMPI loads and unloads its components at run time, and what they leave
// is reported from an "<unknown module>" that no library-name suppression
// (scripts/lsan_suppressions.txt) can match. Every other check stays on.
inline std::string mpirun_two_ranks() {
  std::string prefix =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
      "OMPI_MCA_rmaps_base_oversubscribe=1 ";
#if defined(__SANITIZE_ADDRESS__)
  prefix += "ASAN_OPTIONS=detect_leaks=0:abort_on_error=0:strict_string_checks=1 ";
#endif
  return prefix + "mpirun -n 2 --oversubscribe ";
}

}  // namespace impactlab::test
