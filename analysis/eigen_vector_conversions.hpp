// A vector of doubles as an Eigen vector and back, where the analyses hand
// vectors between their records (std::vector) and Eigen's linear algebra.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace impactlab {

inline Eigen::VectorXd to_eigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

inline std::vector<double> to_values(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

}  // namespace impactlab
