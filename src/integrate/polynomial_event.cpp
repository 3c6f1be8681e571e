// The first event on a witness's Taylor polynomial, compiled once for double.
#include <impactlab/integrate/polynomial_event.hpp>

namespace impactlab {

template LocatedEvent first_polynomial_event<double>(
    const std::array<double, taylor_max_order + 1>&, int, const double&, const double&,
    const double&, double, bool, bool, std::size_t, SeriesLane*);

}  // namespace impactlab
