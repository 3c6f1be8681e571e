// SeriesProgram::run compiled for the batch's tapes (a lane's order 0) and
// the dual numbers over them (the variational equations of models of two and
// of four states in lanes).
#include <impactlab/integrate/dual_number.hpp>
#include <impactlab/integrate/series_tape.hpp>
#include <impactlab/oscillators/model_file/series_program_run.hpp>

namespace impactlab {

IMPACTLAB_SERIES_PROGRAM_LANE_TYPES(IMPACTLAB_SERIES_PROGRAM_RUN)

}  // namespace impactlab
