// SeriesProgram::run compiled for doubles, the Taylor stepper's series and
// the dual numbers over them (the variational equations of models of two and
// of four states).
#include <impactlab/integrate/dual_number.hpp>
#include <impactlab/integrate/taylor_series.hpp>
#include <impactlab/oscillators/model_file/series_program_run.hpp>

namespace impactlab {

IMPACTLAB_SERIES_PROGRAM_NUMBER_TYPES(IMPACTLAB_SERIES_PROGRAM_RUN)

}  // namespace impactlab
