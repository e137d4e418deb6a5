#ifndef VIO_EVAL_EVAL_ERROR_H_
#define VIO_EVAL_EVAL_ERROR_H_

#include <stdexcept>

namespace vio {

// An evaluation that the given trajectories cannot support: too few associated
// poses, a degenerate alignment (collinear positions), no pose pair for an RPE
// length, a plot that cannot be written. what() says which and why.
class EvalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vio

#endif  // VIO_EVAL_EVAL_ERROR_H_
