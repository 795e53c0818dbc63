#include "taebp/persuasion/random.h"

#include <boost/math/special_functions/beta.hpp>

namespace taebp::persuasion {

double BetaQuantile(double alpha, double beta, double q) {
  return boost::math::ibeta_inv(alpha, beta, q);
}

}  // namespace taebp::persuasion
