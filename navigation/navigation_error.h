#ifndef VIO_NAVIGATION_NAVIGATION_ERROR_H_
#define VIO_NAVIGATION_NAVIGATION_ERROR_H_

#include <stdexcept>

namespace vio {

// Bad navigation input: a malformed Moving AI map or scenario file, a
// landmark file, a start or goal off the grid or blocked. what() names the
// file and line ("maps/a.map:7: ...") or the option ("--start ...").
class NavigationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vio

#endif  // VIO_NAVIGATION_NAVIGATION_ERROR_H_
