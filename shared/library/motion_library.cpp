#include "library/motion_library.hpp"
